// The input and output of the contact broad phase: a triangle surface's topology (vertices,
// edges, faces; positions are given separately, as they change every iteration) and the
// candidate pairs the barrier and CCD then examine exactly:
//   point–triangle (v, f)   a vertex against a face that does not contain it,
//   edge–edge (a, b), a < b  two edges with no vertex in common.
// A pair sharing a vertex is never a candidate (its distance is 0 by construction; IPC leaves it
// out). Lists are sorted, so the order depends only on the set.
#pragma once

#include <array>
#include <compare>
#include <cstddef>
#include <vector>

namespace mlshell {

/// A triangle surface for contact: #V vertices, its unique edges and its faces (indices into
/// the vertices). Several bodies and obstacles are one surface with disjoint index ranges.
struct ContactSurface {
  int num_vertices = 0;
  std::vector<std::array<int, 2>> edges;  ///< #E unique edges, v[0] < v[1], sorted
  std::vector<std::array<int, 3>> faces;  ///< #F triangles

  /// The surface of the given faces, its edges derived from them (sorted, unique). Throws
  /// std::invalid_argument for an index outside [0, num_vertices) or a face with a repeated
  /// vertex.
  static ContactSurface from_faces(int num_vertices, std::vector<std::array<int, 3>> faces);
};

struct PointTriangleCandidate {
  int vertex;
  int face;
  auto operator<=>(const PointTriangleCandidate&) const = default;
};

struct EdgeEdgeCandidate {
  int edge_a;  ///< edge_a < edge_b
  int edge_b;
  auto operator<=>(const EdgeEdgeCandidate&) const = default;
};

struct ContactCandidates {
  std::vector<PointTriangleCandidate> point_triangle;  ///< sorted, unique
  std::vector<EdgeEdgeCandidate> edge_edge;            ///< sorted, unique
  std::size_t size() const { return point_triangle.size() + edge_edge.size(); }
  bool operator==(const ContactCandidates&) const = default;
};

}  // namespace mlshell
