#include "tiling/mean_value.h"

// GCC 12 sees a vector of SparseLU's column ordering as maybe uninitialized once Eigen's
// SIMD is off (EIGEN_DONT_VECTORIZE, CMakeLists.txt): a false positive in Eigen's code.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/Sparse>
#include <Eigen/SparseLU>
#pragma GCC diagnostic pop

#include <algorithm>
#include <cmath>
#include <vector>

namespace isoquad {

bool mean_value_parameterization(const std::vector<Point2>& positions,
                                 const std::vector<std::array<int, 3>>& triangles,
                                 const std::vector<char>& is_fixed, std::vector<Point2>& uv) {
  const int n = static_cast<int>(positions.size());
  std::vector<int> unknown(n, -1);
  int num_unknowns = 0;
  for (int i = 0; i < n; ++i)
    if (!is_fixed[i]) unknown[i] = num_unknowns++;
  if (num_unknowns == 0) return true;

  // Row i: sum_j w_ij (u_i - u_j) = 0. Each triangle adds tan(a/2) / |p_j - p_i| to the
  // two edges at each of its free corners; the two triangles along an edge complete w_ij.
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(9 * triangles.size());
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(num_unknowns, 2);
  for (const auto& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      const int i = t[k];
      const int row = unknown[i];
      if (row < 0) continue;
      const int j = t[(k + 1) % 3], l = t[(k + 2) % 3];
      const double ax = positions[j].x - positions[i].x, ay = positions[j].y - positions[i].y;
      const double bx = positions[l].x - positions[i].x, by = positions[l].y - positions[i].y;
      const double la = length(ax, ay), lb = length(bx, by);
      // tan(a/2) = sin a / (1 + cos a) = |a x b| / (|a||b| + a.b): stable for small angles.
      const double tan_half = std::abs(ax * by - ay * bx) / (la * lb + ax * bx + ay * by);
      for (const auto& [other, length] : {std::pair<int, double>{j, la}, {l, lb}}) {
        const double w = tan_half / length;
        triplets.emplace_back(row, row, w);
        if (unknown[other] >= 0) {
          triplets.emplace_back(row, unknown[other], -w);
        } else {
          rhs(row, 0) += w * uv[other].x;
          rhs(row, 1) += w * uv[other].y;
        }
      }
    }
  }
  Eigen::SparseMatrix<double> matrix(num_unknowns, num_unknowns);
  matrix.setFromTriplets(triplets.begin(), triplets.end());
  matrix.makeCompressed();

  // Mean value weights are positive and the rows weakly diagonally dominant: BiCGSTAB
  // converges in a few dozen iterations, several times faster than a sparse LU on these
  // small systems (its symbolic analysis dominated). LU remains the fallback.
  Eigen::MatrixXd solution(num_unknowns, 2);
  Eigen::BiCGSTAB<Eigen::SparseMatrix<double>, Eigen::DiagonalPreconditioner<double>> iterative;
  iterative.setTolerance(1e-9);
  iterative.setMaxIterations(std::max(100, 2 * num_unknowns));
  iterative.compute(matrix);
  bool solved = iterative.info() == Eigen::Success;
  for (int c = 0; c < 2 && solved; ++c) {
    solution.col(c) = iterative.solve(rhs.col(c));
    solved = iterative.info() == Eigen::Success;
  }
  if (!solved) {
    Eigen::SparseLU<Eigen::SparseMatrix<double>> solver;
    solver.analyzePattern(matrix);
    solver.factorize(matrix);
    if (solver.info() != Eigen::Success) return false;
    solution = solver.solve(rhs);
    if (solver.info() != Eigen::Success) return false;
  }
  for (int i = 0; i < n; ++i) {
    if (unknown[i] < 0) continue;
    uv[i] = {solution(unknown[i], 0), solution(unknown[i], 1)};
  }
  return true;
}

}  // namespace isoquad
