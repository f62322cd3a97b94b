// Squared distance between two edges (segments) a = (ea0, ea1) and b = (eb0, eb1), 12 dofs
// x = (ea0, ea1, eb0, eb1), by where the closest points lie (IPC, Li et al. 2020):
//   EA0_EB0, EA0_EB1, EA1_EB0, EA1_EB1   two endpoints:                  point–point d
//   EA_EB0, EA_EB1                       eb0 or eb1 against a's interior: point–line d
//   EA0_EB, EA1_EB                       ea0 or ea1 against b's interior: point–line d
//   EA_EB                                both interiors:                 line–line d
// Classification: with u = ea1 − ea0, v = eb1 − eb0, w = ea0 − eb0, the closest points of the
// infinite lines are ea0 + s u and eb0 + t v,
//   s = ((u·v)(v·w) − |v|²(u·w)) / |u × v|²,   t = (|u|²(v·w) − (u·v)(u·w)) / |u × v|²;
// if both lie strictly inside (0, 1) the type is EA_EB (the squared distance is a convex
// function of (s, t), so an interior stationary point is the minimum). Otherwise the minimum
// lies on the boundary of [0, 1]², where one endpoint is closest to the other edge, and the
// type is that of the nearest of the four endpoint–edge distances (point_edge.hpp).
// Parallel and nearly parallel edges, |u × v|² ≤ 10⁻¹⁰ |u|²|v|², skip the line–line candidate:
// there s, t lose accuracy as 1/sin²θ and the line–line formula is singular; the endpoint–edge
// distances are exact for parallel edges and off by at most ~10⁻¹⁰ |u||v| below the threshold.
// A zero-length edge is handled by the same fallback.
#pragma once

#include <Eigen/Core>

#include "mlshell/contact/contact_types.hpp"

namespace mlshell {

// clang-format off
enum class EdgeEdgeDistanceType {
  EA0_EB0, EA0_EB1, EA1_EB0, EA1_EB1,  // point–point
  EA_EB0, EA_EB1, EA0_EB, EA1_EB,      // point–edge
  EA_EB                                // line–line
};
// clang-format on

/// The relative threshold sin²θ = |u × v|² / (|u|²|v|²) at and below which edges count as
/// parallel for the classification.
inline constexpr double kEdgeEdgeParallelThreshold = 1e-10;

/// The type of the file comment.
EdgeEdgeDistanceType edge_edge_distance_type(const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1,
                                             const Eigen::Vector3d& eb0,
                                             const Eigen::Vector3d& eb1);

/// d for the given type and, where the pointers are not null, its gradient and Hessian in
/// (ea0, ea1, eb0, eb1) (zero in the rows of the vertices the type does not involve).
double edge_edge_distance(const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1,
                          const Eigen::Vector3d& eb0, const Eigen::Vector3d& eb1,
                          EdgeEdgeDistanceType type, Vector12* grad = nullptr,
                          Matrix12* hess = nullptr);

/// d for the classified type: the squared distance between the two segments.
double edge_edge_distance(const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1,
                          const Eigen::Vector3d& eb0, const Eigen::Vector3d& eb1);

}  // namespace mlshell
