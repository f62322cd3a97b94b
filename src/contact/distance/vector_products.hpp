// The two polynomials every non-trivial squared distance is built from, with their exact
// derivatives in the vectors they take, and the chain rule back to a stencil's stacked positions.
//
//   g(u, v) = |u × v|²          (point–line numerator, point–plane and line–line denominator,
//                                 the edge–edge mollifier's argument)
//   f(w, u, v) = w · (u × v)    (point–plane and line–line numerator: d = f² / g)
//
// Each distance picks its vectors as differences of its vertices, y = A x with A = C ⊗ I₃ for a
// small coefficient matrix C of ±1 and 0; then ∇ₓ = Aᵀ ∇_y and ∇²ₓ = Aᵀ ∇²_y A (no other term,
// since y is linear in x).
#pragma once

#include <Eigen/Core>

#include "mlshell/contact/contact_types.hpp"

namespace mlshell::contact_detail {

/// g = |u × v|² and, where the pointers are not null, its gradient in (u, v) and Hessian:
///   ∂g/∂u = 2 v × n,  ∂g/∂v = 2 n × u      (n = u × v: no cancellation for nearly parallel u, v)
///   ∂²g/∂u² = 2(|v|² I − v vᵀ),  ∂²g/∂v² = 2(|u|² I − u uᵀ),
///   ∂²g/∂u∂v = 4 u vᵀ − 2 v uᵀ − 2 (u·v) I     (from g = |u|²|v|² − (u·v)²).
double cross_squared_norm(const Eigen::Vector3d& u, const Eigen::Vector3d& v, Vector6* grad,
                          Matrix6* hess);

/// f = w · (u × v) and its gradient (u × v, v × w, w × u) in (w, u, v) and Hessian, whose
/// off-diagonal blocks are cross-product matrices [a]ₓ (with [a]ₓ b = a × b):
///   ∂²f/∂w∂u = −[v]ₓ,  ∂²f/∂w∂v = [u]ₓ,  ∂²f/∂u∂v = −[w]ₓ,   diagonal blocks 0.
double triple_product(const Eigen::Vector3d& w, const Eigen::Vector3d& u, const Eigen::Vector3d& v,
                      Vector9* grad, Matrix9* hess);

/// (w · n)² / |n|² with n = u × v: the squared component of w along the normal of the plane
/// spanned by u and v, with its gradient and Hessian in (w, u, v) by the quotient rule on f² / g.
/// Point–plane and line–line distances are this with their own w, u, v. Throws
/// std::domain_error when u × v = 0 (no plane).
double squared_normal_component(const Eigen::Vector3d& w, const Eigen::Vector3d& u,
                                const Eigen::Vector3d& v, Vector9* grad, Matrix9* hess);

/// The cross-product matrix [a]ₓ.
Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& a);

/// A = C ⊗ I₃: the map from a stencil's stacked positions to stacked difference vectors.
template <int K, int N>
Eigen::Matrix<double, 3 * K, 3 * N> difference_map(const Eigen::Matrix<double, K, N>& C) {
  Eigen::Matrix<double, 3 * K, 3 * N> A = Eigen::Matrix<double, 3 * K, 3 * N>::Zero();
  for (int i = 0; i < K; ++i)
    for (int j = 0; j < N; ++j)
      A.template block<3, 3>(3 * i, 3 * j).diagonal().setConstant(C(i, j));
  return A;
}

/// q = a / b with a, b > 0 given with gradients and Hessians, in place into (grad, hess) of q:
///   ∇q = (∇a − q ∇b) / b,   ∇²q = (∇²a − q ∇²b − ∇q ∇bᵀ − ∇b ∇qᵀ) / b   (from q b = a).
template <int N>
double quotient(double a, const Eigen::Matrix<double, N, 1>& grad_a,
                const Eigen::Matrix<double, N, N>& hess_a, double b,
                const Eigen::Matrix<double, N, 1>& grad_b,
                const Eigen::Matrix<double, N, N>& hess_b, Eigen::Matrix<double, N, 1>* grad,
                Eigen::Matrix<double, N, N>* hess) {
  const double q = a / b;
  const Eigen::Matrix<double, N, 1> gq = (grad_a - q * grad_b) / b;
  if (grad) *grad = gq;
  if (hess) {
    *hess = (hess_a - q * hess_b - gq * grad_b.transpose() - grad_b * gq.transpose()) / b;
  }
  return q;
}

/// Adds a stencil's local gradient and Hessian (vertices 0..M−1 of the local function) into a
/// larger stencil's, local vertex j going to vertex `to[j]` of the larger one.
template <int M, int N>
void scatter(const Eigen::Matrix<double, 3 * M, 1>& g, const Eigen::Matrix<double, 3 * M, 3 * M>& H,
             const int (&to)[M], Eigen::Matrix<double, 3 * N, 1>* grad,
             Eigen::Matrix<double, 3 * N, 3 * N>* hess) {
  if (grad) {
    grad->setZero();
    for (int j = 0; j < M; ++j) grad->template segment<3>(3 * to[j]) = g.template segment<3>(3 * j);
  }
  if (hess) {
    hess->setZero();
    for (int i = 0; i < M; ++i)
      for (int j = 0; j < M; ++j)
        hess->template block<3, 3>(3 * to[i], 3 * to[j]) = H.template block<3, 3>(3 * i, 3 * j);
  }
}

}  // namespace mlshell::contact_detail
