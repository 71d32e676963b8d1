// The linear solve behind the boundary-aligned cross field (cross_field.h): its own
// header so that Eigen stays out of the field's interface, and so that both ways of
// solving can be tested.
#pragma once

#include <Eigen/Sparse>

#include <complex>
#include <functional>

namespace isoquad {

// Solves H u = rhs for the cross field's unknowns u = exp(4 i theta).
//
// `laplacian` is the real cotan Laplacian of the free vertices (symmetric positive
// definite); `hermitian`, when the field is asked to rotate along edges, returns the
// same matrix with each off-diagonal entry turned by its edge's rotation (Hermitian
// positive definite); empty when there are no rotations, and then H = laplacian. It is
// called once, after the real factorisation, and `laplacian` (taken by value: move it
// in) is freed before: the three matrices are never held at once.
//
// Without rotations: one real factorisation, the real and imaginary parts solved at
// once on two threads. With them: conjugate gradients on H preconditioned by the real
// factor (its solves on two threads too), up to max_iterations, to a relative residual
// of 1e-5; failing that, H factorised itself (twice the memory of the real factor).
// Eigen's simplicial LLT with its AMD ordering, measured against CHOLMOD's supernodal
// LLT with Debian's OpenBLAS: France automatic (44,542 unknowns) factorised in 0.07 s
// against 0.24 s, the Arctic Ocean at 1:10m
// (288,610) in 0.63 s against 1.2 s, solves as fast; and no BLAS, whose kernels differ
// from one CPU to another and with them the last bits of the field.
//
// Throws Error (meshing) when a factorisation fails (a component without a fixed
// boundary vertex).
Eigen::VectorXcd solve_cross_system(
    Eigen::SparseMatrix<double> laplacian,
    const std::function<Eigen::SparseMatrix<std::complex<double>>()>& hermitian,
    const Eigen::VectorXcd& rhs, int max_iterations = 200);

}  // namespace isoquad
