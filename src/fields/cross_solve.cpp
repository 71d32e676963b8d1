#include "fields/cross_solve.h"

#include <Eigen/SparseCholesky>

#include "core/error.h"
#include "core/parallel.h"

namespace isoquad {

namespace {
const char* const kStage = "cross field";
}

Eigen::VectorXcd solve_cross_system(
    Eigen::SparseMatrix<double> laplacian,
    const std::function<Eigen::SparseMatrix<std::complex<double>>()>& hermitian,
    const Eigen::VectorXcd& rhs, int max_iterations) {
  const Eigen::Index n = laplacian.rows();
  const Eigen::SimplicialLLT<Eigen::SparseMatrix<double>> solver(laplacian);
  if (solver.info() != Eigen::Success)
    throw Error(ErrorClass::meshing, kStage,
                "the Laplacian could not be factorised (a mesh component without boundary?)");
  Eigen::SparseMatrix<double>().swap(laplacian);  // the factor holds what the solves need
  // The real solve of a complex vector: its real and imaginary parts, at once on two
  // threads (the factor is only read; each part is solved exactly as alone).
  auto real_solve = [&](const Eigen::VectorXcd& right) {
    Eigen::VectorXd re, im;
    run_in_parallel([&] { re = solver.solve(Eigen::VectorXd(right.real())); },
                    [&] { im = solver.solve(Eigen::VectorXd(right.imag())); });
    if (solver.info() != Eigen::Success)
      throw Error(ErrorClass::meshing, kStage, "the cross field solve failed");
    Eigen::VectorXcd out(n);
    out.real() = re;
    out.imag() = im;
    return out;
  };
  Eigen::VectorXcd u = real_solve(rhs);
  if (!hermitian) return u;

  // A relative residual of 1e-5 moves crosses by far less than a degree; France
  // automatic: 16 iterations.
  const Eigen::SparseMatrix<std::complex<double>> h = hermitian();
  const double target = 1e-5 * rhs.norm();
  Eigen::VectorXcd residual = rhs - h * u;
  Eigen::VectorXcd z = real_solve(residual);
  Eigen::VectorXcd direction = z;
  double rz = residual.dot(z).real();
  for (int it = 0; it < max_iterations && residual.norm() > target; ++it) {
    const Eigen::VectorXcd image = h * direction;
    const double alpha = rz / direction.dot(image).real();
    u += alpha * direction;
    residual -= alpha * image;
    z = real_solve(residual);
    const double rz_next = residual.dot(z).real();
    direction = z + (rz_next / rz) * direction;
    rz = rz_next;
  }
  if (residual.norm() > target) {
    // Rotations too strong for the preconditioner: factorise H itself.
    const Eigen::SimplicialLLT<Eigen::SparseMatrix<std::complex<double>>> complex_solver(h);
    if (complex_solver.info() == Eigen::Success) u = complex_solver.solve(rhs);
    if (complex_solver.info() != Eigen::Success)
      throw Error(ErrorClass::meshing, kStage, "the cross field solve failed");
  }
  return u;
}

}  // namespace isoquad
