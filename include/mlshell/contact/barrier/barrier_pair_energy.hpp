// The barrier energy of one contact pair (IPC, Li et al. 2020), on an N-dof stencil
// (N = 6, 9, 12) whose squared distance d(x) with ∇d, ∇²d comes from contact/distance/:
//   E = κ b_ξ(d(x)),   ∇E = κ b' ∇d,   ∇²E = κ (b'' ∇d ∇dᵀ + b' ∇²d),
// and for an edge–edge pair with the mollifier m(x) (edge_edge_mollifier.hpp), E = κ m b_ξ(d):
//   ∇E  = κ (b ∇m + m b' ∇d),
//   ∇²E = κ (b ∇²m + b' (∇m ∇dᵀ + ∇d ∇mᵀ) + m (b'' ∇d ∇dᵀ + b' ∇²d)).
// b_ξ is the offset barrier of barrier.hpp. With `project` the pair Hessian is projected onto
// the PSD cone (psd_projection.hpp), as projected Newton needs (IPC).
#pragma once

#include <Eigen/Core>

#include "mlshell/contact/barrier/barrier.hpp"
#include "mlshell/contact/contact_types.hpp"

namespace mlshell {

/// E = κ b_ξ(d) and, where the pointers are not null, ∇E and ∇²E (PSD-projected if `project`).
/// Returns +∞, writing neither, for d ≤ ξ² (the barrier's domain ends there).
/// Instantiated for N = 6, 9, 12.
template <int N>
double barrier_pair_energy(double kappa, const ContactBarrier& barrier, double d,
                           const Eigen::Matrix<double, N, 1>& grad_d,
                           const Eigen::Matrix<double, N, N>& hess_d,
                           Eigen::Matrix<double, N, 1>* grad, Eigen::Matrix<double, N, N>* hess,
                           bool project);

/// E = κ m b_ξ(d) of an edge–edge pair and, where the pointers are not null, ∇E and ∇²E
/// (PSD-projected if `project`). Returns +∞, writing neither, for d ≤ ξ².
double mollified_barrier_pair_energy(double kappa, const ContactBarrier& barrier, double d,
                                     const Vector12& grad_d, const Matrix12& hess_d, double m,
                                     const Vector12& grad_m, const Matrix12& hess_m, Vector12* grad,
                                     Matrix12* hess, bool project);

}  // namespace mlshell
