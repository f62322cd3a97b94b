// The contact broad phase: which point–triangle and edge–edge pairs of a surface can come
// within a distance δ, for the barrier (δ = ξ + ĝ at the current positions) and for CCD (δ = ξ
// anywhere along the step x₀ → x₁).
//
// Each primitive gets the axis-aligned box of its vertices (at x₀ and x₁ for a step: every
// vertex moves on a segment, so the swept primitive stays in the box of its end positions),
// grown by δ/2 on every side and rounded outwards. Two primitives closer than δ at some time
// have points p, q with |p_i − q_i| < δ in every coordinate, so their grown boxes overlap: the
// candidates are every pair (not sharing a vertex) whose boxes overlap, a superset of the pairs
// closer than δ. Both methods below return exactly that set; they differ only in how they find
// the overlapping boxes:
//   kSpatialHash  a uniform grid of cells about the size of an edge's box: every box is listed
//                 in the cells it covers (sorted by cell), and a pair is tested in the one cell
//                 that holds the lower corner of the two boxes' intersection;
//   kBvh          a bounding-volume hierarchy of the face boxes and one of the edge boxes,
//                 split at the median of the longest axis of the box centres (leaves of ≤ 4),
//                 queried with every vertex box and every edge box.
// Measured on three stacked rippled sheets of 50,784 faces (tests/benchmarks/
// broad_phase_benchmark.cpp, one core, CPU time): the proximity candidates within 1 mm in 71 ms
// by the hash against 143 ms by the BVH, the swept ones in 107–117 ms against 158–172 ms. The
// hash is the default; the BVH stays as the independent method the hash is checked against on
// meshes too large for a brute-force comparison (broad_phase_test.cpp).
#pragma once

#include <Eigen/Core>
#include <span>

#include "mlshell/contact/broad_phase/contact_candidates.hpp"

namespace mlshell {

enum class BroadPhaseMethod { kSpatialHash, kBvh };

/// Pairs whose grown boxes overlap at positions x (#V points): a superset of the pairs closer
/// than `distance` ≥ 0. Throws std::invalid_argument for a wrong number of positions, a
/// non-finite position or a negative or non-finite distance.
ContactCandidates find_proximity_candidates(
    const ContactSurface& surface, std::span<const Eigen::Vector3d> x, double distance,
    BroadPhaseMethod method = BroadPhaseMethod::kSpatialHash);

/// Pairs whose boxes swept over the step x0 → x1, grown, overlap: a superset of the pairs that
/// come closer than `distance` at some time of the linear step.
ContactCandidates find_swept_candidates(const ContactSurface& surface,
                                        std::span<const Eigen::Vector3d> x0,
                                        std::span<const Eigen::Vector3d> x1, double distance,
                                        BroadPhaseMethod method = BroadPhaseMethod::kSpatialHash);

}  // namespace mlshell
