// Squared distance from a point to a triangle, 12 dofs x = (p, t0, t1, t2), by where the
// closest point of the triangle lies (IPC, Li et al. 2020: the distance of a pair is that of
// the primitive sub-pair its closest points lie on, so every type is a smooth function):
//   P_T0, P_T1, P_T2   a vertex:           d = |p − t_i|²                       (point_point.hpp)
//   P_E0, P_E1, P_E2   the interior of edge t0t1, t1t2, t2t0: point–line d      (point_line.hpp)
//   P_T                the interior:       d = point–plane d                    (point_plane.hpp)
// Classification: with n = (t1 − t0) × (t2 − t0), p projects into the triangle when
// ((t_{i+1} − t_i) × (p − t_i)) · n ≥ 0 for the three edges; then P_T. Otherwise the closest
// point lies on the boundary, and the type is that of the nearest of the three point–edge
// distances (point_edge.hpp). A zero-area triangle (n = 0) is classified by its edges only.
#pragma once

#include <Eigen/Core>

#include "mlshell/contact/contact_types.hpp"

namespace mlshell {

enum class PointTriangleDistanceType { P_T0, P_T1, P_T2, P_E0, P_E1, P_E2, P_T };

/// The type of the file comment.
PointTriangleDistanceType point_triangle_distance_type(const Eigen::Vector3d& p,
                                                       const Eigen::Vector3d& t0,
                                                       const Eigen::Vector3d& t1,
                                                       const Eigen::Vector3d& t2);

/// d for the given type and, where the pointers are not null, its gradient and Hessian in
/// (p, t0, t1, t2) (zero in the rows of the vertices the type does not involve).
double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& t0,
                               const Eigen::Vector3d& t1, const Eigen::Vector3d& t2,
                               PointTriangleDistanceType type, Vector12* grad = nullptr,
                               Matrix12* hess = nullptr);

/// d for the classified type: the squared distance from p to the triangle.
double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& t0,
                               const Eigen::Vector3d& t1, const Eigen::Vector3d& t2);

}  // namespace mlshell
