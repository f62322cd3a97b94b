// Squared distance from a point to the infinite line through an edge (IPC, Li et al. 2020; the
// point–edge type of the point–triangle and edge–edge distances), 9 dofs x = (p, e0, e1):
//   d = |(e0 − p) × (e1 − p)|² / |e1 − e0|²,
// twice the area of the triangle (p, e0, e1), squared, over the squared base. Derivatives by the
// quotient rule on g(u, v) = |u × v|² with u = e0 − p, v = e1 − p and |v − u|² (vector_products).
#pragma once

#include <Eigen/Core>

#include "mlshell/contact/contact_types.hpp"

namespace mlshell {

/// d of the file comment and, where the pointers are not null, its gradient and Hessian in
/// (p, e0, e1). Throws std::domain_error when e0 = e1 (no line).
double point_line_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& e0,
                           const Eigen::Vector3d& e1, Vector9* grad = nullptr,
                           Matrix9* hess = nullptr);

}  // namespace mlshell
