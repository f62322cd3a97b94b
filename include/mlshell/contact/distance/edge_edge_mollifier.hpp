// The edge–edge mollifier for nearly parallel edges (IPC, Li et al. 2020, the mollified edge–edge
// barrier), 12 dofs x = (ea0, ea1, eb0, eb1). The edge–edge distance is only C⁰ where the edges
// become parallel (its type jumps between line–line and point–edge), so the edge–edge barrier is
// multiplied by
//   c(x) = |(ea1 − ea0) × (eb1 − eb0)|²,
//   m(c) = (2 − c/ε_x) c/ε_x   for c < ε_x,   m(c) = 1   for c ≥ ε_x,
// with ε_x = 10⁻³ |ēa1 − ēa0|² |ēb1 − ēb0|² from the rest positions (IPC's constant). m is C¹ at
// c = ε_x (m = 1, m' = 0 there) and vanishes with c as the edges become parallel. With
//   m'(c) = 2 (1 − c/ε_x)/ε_x,   m''(c) = −2/ε_x²,
// the chain rule gives ∇m = m' ∇c and ∇²m = m'' ∇c ∇cᵀ + m' ∇²c, ∇c and ∇²c those of
// |u × v|² with u = ea1 − ea0, v = eb1 − eb0.
#pragma once

#include <Eigen/Core>

#include "mlshell/contact/contact_types.hpp"

namespace mlshell {

/// ε_x = 10⁻³ |ēa1 − ēa0|² |ēb1 − ēb0|² of the file comment, from the rest positions.
double edge_edge_mollifier_threshold(const Eigen::Vector3d& rest_ea0,
                                     const Eigen::Vector3d& rest_ea1,
                                     const Eigen::Vector3d& rest_eb0,
                                     const Eigen::Vector3d& rest_eb1);

/// c = |(ea1 − ea0) × (eb1 − eb0)|² and, where the pointers are not null, its gradient and
/// Hessian in (ea0, ea1, eb0, eb1).
double edge_edge_cross_squared_norm(const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1,
                                    const Eigen::Vector3d& eb0, const Eigen::Vector3d& eb1,
                                    Vector12* grad = nullptr, Matrix12* hess = nullptr);

/// True where the mollifier is active (c < ε_x): the edge–edge barrier must then be mollified.
bool edge_edge_mollifier_active(const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1,
                                const Eigen::Vector3d& eb0, const Eigen::Vector3d& eb1,
                                double eps_x);

/// m(c(x)) and, where the pointers are not null, its gradient and Hessian in
/// (ea0, ea1, eb0, eb1) (zero for c ≥ ε_x). eps_x must be positive.
double edge_edge_mollifier(const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1,
                           const Eigen::Vector3d& eb0, const Eigen::Vector3d& eb1, double eps_x,
                           Vector12* grad = nullptr, Matrix12* hess = nullptr);

}  // namespace mlshell
