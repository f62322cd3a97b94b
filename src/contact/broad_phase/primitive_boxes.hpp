// What both broad-phase methods share (broad_phase.hpp): the grown boxes of a surface's vertices,
// edges and faces, the overlap test, the shared-vertex test, and the two methods' entry points.
#pragma once

#include <Eigen/Core>
#include <array>
#include <span>
#include <vector>

#include "mlshell/contact/broad_phase/contact_candidates.hpp"

namespace mlshell::contact_detail {

/// An axis-aligned box [lo, hi].
struct Box {
  std::array<double, 3> lo, hi;
};

inline bool overlap(const Box& a, const Box& b) {
  return a.lo[0] <= b.hi[0] && b.lo[0] <= a.hi[0] && a.lo[1] <= b.hi[1] && b.lo[1] <= a.hi[1] &&
         a.lo[2] <= b.hi[2] && b.lo[2] <= a.hi[2];
}

/// The boxes of broad_phase.hpp's file comment, one per vertex, edge and face.
struct PrimitiveBoxes {
  std::vector<Box> vertices, edges, faces;
};

/// Boxes of every primitive over the positions x0 and x1 (x1 = x0 for the proximity boxes),
/// grown by distance/2 and rounded outwards by one ulp.
PrimitiveBoxes primitive_boxes(const ContactSurface& surface, std::span<const Eigen::Vector3d> x0,
                               std::span<const Eigen::Vector3d> x1, double distance);

inline bool face_has_vertex(const std::array<int, 3>& f, int v) {
  return f[0] == v || f[1] == v || f[2] == v;
}
inline bool edges_share_vertex(const std::array<int, 2>& a, const std::array<int, 2>& b) {
  return a[0] == b[0] || a[0] == b[1] || a[1] == b[0] || a[1] == b[1];
}

/// The candidates of broad_phase.hpp by each method (sorted, unique).
ContactCandidates spatial_hash_candidates(const ContactSurface& surface,
                                          const PrimitiveBoxes& boxes);
ContactCandidates bvh_candidates(const ContactSurface& surface, const PrimitiveBoxes& boxes);

}  // namespace mlshell::contact_detail
