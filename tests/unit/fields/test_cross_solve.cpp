#include "fields/cross_solve.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <random>
#include <vector>

using namespace isoquad;

namespace {

using Complex = std::complex<double>;

// The cross field's system on an n x n grid of free vertices whose outer ring is tied to
// fixed boundary vertices: the real Laplacian L (unit weights) and H, the same with each
// edge turned by exp(4 i omega), omega uniform in [-spread, spread].
struct GridSystem {
  Eigen::SparseMatrix<double> laplacian;
  Eigen::SparseMatrix<Complex> hermitian;
  Eigen::VectorXcd rhs;
};

GridSystem grid_system(int n, double spread, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> omega(-spread, spread), value(-1.0, 1.0);
  const int size = n * n;
  std::vector<Eigen::Triplet<double>> real;
  std::vector<Eigen::Triplet<Complex>> turned;
  std::vector<double> diagonal(size, 4.0);  // four neighbours, free or fixed
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * n + i;
      for (const int b : {i + 1 < n ? a + 1 : -1, j + 1 < n ? a + n : -1}) {
        if (b < 0) continue;
        const Complex r = std::polar(1.0, 4.0 * omega(rng));
        real.emplace_back(a, b, -1.0);
        real.emplace_back(b, a, -1.0);
        turned.emplace_back(a, b, -std::conj(r));
        turned.emplace_back(b, a, -r);
      }
    }
  for (int a = 0; a < size; ++a) {
    real.emplace_back(a, a, diagonal[a]);
    turned.emplace_back(a, a, diagonal[a]);
  }
  GridSystem s;
  s.laplacian.resize(size, size);
  s.laplacian.setFromTriplets(real.begin(), real.end());
  s.hermitian.resize(size, size);
  s.hermitian.setFromTriplets(turned.begin(), turned.end());
  s.rhs.resize(size);
  for (int a = 0; a < size; ++a) s.rhs(a) = Complex(value(rng), value(rng));
  return s;
}

double relative_residual(const Eigen::SparseMatrix<Complex>& h, const Eigen::VectorXcd& u,
                         const Eigen::VectorXcd& rhs) {
  return (rhs - h * u).norm() / rhs.norm();
}

// The Hermitian matrix as the solve asks for it, counting the calls (it is built once).
std::function<Eigen::SparseMatrix<Complex>()> hermitian_of(const GridSystem& s,
                                                           int* calls = nullptr) {
  return [&s, calls] {
    if (calls) ++*calls;
    return s.hermitian;
  };
}

}  // namespace

TEST(CrossSolve, TheHermitianMatrixIsBuiltOnce) {
  const GridSystem s = grid_system(30, 3.2, 3);
  int calls = 0;
  solve_cross_system(s.laplacian, hermitian_of(s, &calls), s.rhs, 0);  // to the factorisation
  EXPECT_EQ(calls, 1);
}

TEST(CrossSolve, WithoutRotationsSolvesTheLaplacian) {
  const GridSystem s = grid_system(30, 0.0, 1);
  const Eigen::VectorXcd u = solve_cross_system(s.laplacian, {}, s.rhs);
  const Eigen::SparseMatrix<Complex> l = s.laplacian.cast<Complex>();
  EXPECT_LT(relative_residual(l, u, s.rhs), 1e-10);
}

TEST(CrossSolve, ConjugateGradientsReachTheTarget) {
  // Rotations of a few degrees per edge, as conformal sizes ask: the real factor is a
  // good preconditioner and the iterations stop at the 1e-5 target, not below 1e-10.
  const GridSystem s = grid_system(30, 0.05, 2);
  const Eigen::VectorXcd u = solve_cross_system(s.laplacian, hermitian_of(s), s.rhs);
  const double r = relative_residual(s.hermitian, u, s.rhs);
  EXPECT_LT(r, 1e-5);
  EXPECT_GT(r, 1e-12);
}

TEST(CrossSolve, TheComplexFactorisationTakesOverAndAgrees) {
  // Rotations of any angle: with no iteration allowed the Hermitian matrix is factorised,
  // which solves it to rounding; its solution is the one the iterations converge to.
  const GridSystem s = grid_system(30, 3.2, 3);
  const Eigen::VectorXcd direct = solve_cross_system(s.laplacian, hermitian_of(s), s.rhs, 0);
  EXPECT_LT(relative_residual(s.hermitian, direct, s.rhs), 1e-10);
  const Eigen::VectorXcd iterated = solve_cross_system(s.laplacian, hermitian_of(s), s.rhs, 2000);
  EXPECT_LT(relative_residual(s.hermitian, iterated, s.rhs), 1e-5);
  EXPECT_LT((direct - iterated).norm() / direct.norm(), 1e-3);
}
