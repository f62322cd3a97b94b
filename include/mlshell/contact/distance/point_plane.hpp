// Squared distance from a point to the plane of a triangle (IPC, Li et al. 2020; the interior
// type of the point–triangle distance), 12 dofs x = (p, t0, t1, t2):
//   n = (t1 − t0) × (t2 − t0),   d = ((p − t0) · n)² / |n|².
// Derivatives by the quotient rule on f² / g with f = w · (u × v), g = |u × v|², w = p − t0,
// u = t1 − t0, v = t2 − t0 (vector_products).
#pragma once

#include <Eigen/Core>

#include "mlshell/contact/contact_types.hpp"

namespace mlshell {

/// d of the file comment and, where the pointers are not null, its gradient and Hessian in
/// (p, t0, t1, t2). Throws std::domain_error for a triangle of zero area (no plane).
double point_plane_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& t0,
                            const Eigen::Vector3d& t1, const Eigen::Vector3d& t2,
                            Vector12* grad = nullptr, Matrix12* hess = nullptr);

}  // namespace mlshell
