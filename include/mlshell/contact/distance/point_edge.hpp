// Squared distance from a point to an edge (a segment), 9 dofs x = (p, e0, e1), by type: the
// closest point of the segment is e0, e1 or interior to it. With s = (p − e0)·(e1 − e0) / |e1 −
// e0|² the parameter of p's projection on the line,
//   s ≤ 0:  P_E0,  d = |p − e0|²           (point_point.hpp)
//   s ≥ 1:  P_E1,  d = |p − e1|²
//   else:   P_E,   d = point–line distance  (point_line.hpp)
// A zero-length edge is P_E0. For a fixed type d is smooth; across a type boundary it is C¹.
#pragma once

#include <Eigen/Core>

#include "mlshell/contact/contact_types.hpp"

namespace mlshell {

enum class PointEdgeDistanceType { P_E0, P_E1, P_E };

/// The type of the file comment.
PointEdgeDistanceType point_edge_distance_type(const Eigen::Vector3d& p, const Eigen::Vector3d& e0,
                                               const Eigen::Vector3d& e1);

/// d for the given type and, where the pointers are not null, its gradient and Hessian in
/// (p, e0, e1) (zero in the rows of a vertex the type does not involve).
double point_edge_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& e0,
                           const Eigen::Vector3d& e1, PointEdgeDistanceType type,
                           Vector9* grad = nullptr, Matrix9* hess = nullptr);

/// d for the classified type: the squared distance from p to the segment.
double point_edge_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& e0,
                           const Eigen::Vector3d& e1);

}  // namespace mlshell
