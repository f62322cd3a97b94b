// Squared distance between the infinite lines through two edges (IPC, Li et al. 2020; the
// interior type of the edge–edge distance), 12 dofs x = (ea0, ea1, eb0, eb1):
//   n = (ea1 − ea0) × (eb1 − eb0),   d = ((eb0 − ea0) · n)² / |n|².
// Derivatives by the quotient rule on f² / g with w = eb0 − ea0, u = ea1 − ea0, v = eb1 − eb0
// (vector_products). Singular for parallel lines (n = 0), and its Hessian grows like 1/|n|² as
// they become parallel: edge_edge_distance_type never picks it there, and the edge–edge
// mollifier (edge_edge_mollifier.hpp) switches the energy off smoothly.
#pragma once

#include <Eigen/Core>

#include "mlshell/contact/contact_types.hpp"

namespace mlshell {

/// d of the file comment and, where the pointers are not null, its gradient and Hessian in
/// (ea0, ea1, eb0, eb1). Throws std::domain_error for parallel lines or a zero-length edge.
double line_line_distance(const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1,
                          const Eigen::Vector3d& eb0, const Eigen::Vector3d& eb1,
                          Vector12* grad = nullptr, Matrix12* hess = nullptr);

}  // namespace mlshell
