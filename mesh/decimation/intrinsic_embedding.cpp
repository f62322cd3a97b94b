// The intrinsic prolongation U of a decimation hierarchy (Liu et al. 2021, "Surface multigrid via
// intrinsic prolongation"; paper 2 §4.2, Fig. 8): every vertex of the finer level is a point of
// the surface, tracked through the collapses that turn the finer level into the coarser one.
//
// A point is either a vertex (weight 1 on itself, while the vertex is untouched) or barycentric
// coordinates in a triangle of the current mesh. Collapse by collapse (records in order), the
// points in the collapse's `before` triangles and both split vertices (paper 2 §4.2: the
// removed one, and the kept one, which the placement moves) go through the collapse's joint
// flattening (collapse_chart.hpp): their before-chart positions are located in the after chart,
// which gives their coordinates in an `after` triangle. A kept vertex whose placement is its
// own position lands on itself. Points are kept in
// per-triangle lists keyed by the sorted vertex triple, so a collapse touches only its own
// points: O(records × ring size + points) in all.
#include "mlshell/decimation/intrinsic_embedding.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "collapse_chart.hpp"

namespace mlshell {

namespace {

using TriangleKey = std::array<int, 3>;

TriangleKey sorted_key(const Triangle& t) {
  TriangleKey k = t;
  std::sort(k.begin(), k.end());
  return k;
}

struct TriangleKeyHash {
  size_t operator()(const TriangleKey& k) const {
    uint64_t h = static_cast<uint32_t>(k[0]);
    h = h * 0x9E3779B97F4A7C15ull ^ static_cast<uint32_t>(k[1]);
    h = h * 0x9E3779B97F4A7C15ull ^ static_cast<uint32_t>(k[2]);
    return static_cast<size_t>(h ^ (h >> 29));
  }
};

/// A tracked point: a surviving vertex, or coordinates in a triangle of the current mesh
/// (finest-mesh vertex indices, in the order the triangle was recorded with).
struct TrackedPoint {
  int vertex = -1;  ///< ≥ 0 while the point is this vertex
  Triangle corners{-1, -1, -1};
  Eigen::Vector3d weights = Eigen::Vector3d::Zero();
  int next = -1;  ///< next point in the same triangle's list
};

}  // namespace

std::vector<EmbeddedPoint> intrinsic_embedding(const DecimationHierarchy& hierarchy, int coarse,
                                               int fine, EmbeddingReport* report) {
  const int levels = hierarchy.num_levels();
  if (fine < 0 || fine >= levels || coarse < 0 || coarse >= fine)
    throw std::invalid_argument("intrinsic_embedding: levels coarse = " + std::to_string(coarse) +
                                ", fine = " + std::to_string(fine) +
                                ": expected 0 ≤ coarse < fine < " + std::to_string(levels));
  const DecimationLevel& from = hierarchy.levels[fine];
  const DecimationLevel& to = hierarchy.levels[coarse];
  const int finest_points = hierarchy.levels.back().mesh.num_points();
  const int first = from.num_records, last = to.num_records;
  if (first > last || last > static_cast<int>(hierarchy.records.size()))
    throw std::invalid_argument("intrinsic_embedding: level " + std::to_string(coarse) +
                                " has records [0, " + std::to_string(last) + "), level " +
                                std::to_string(fine) + " [0, " + std::to_string(first) +
                                "), of " + std::to_string(hierarchy.records.size()));

  // Current positions (finest-mesh indices) of the vertices alive at level `fine`.
  std::vector<Point3> position(finest_points, Point3::Zero());
  std::vector<TrackedPoint> points(from.finest_vertex.size());
  std::vector<int> vertex_point(finest_points, -1);
  for (size_t i = 0; i < from.finest_vertex.size(); ++i) {
    const int v = from.finest_vertex[i];
    position[v] = from.mesh.points[i];
    points[i].vertex = v;
    vertex_point[v] = static_cast<int>(i);
  }

  std::unordered_map<TriangleKey, int, TriangleKeyHash> head;  // first point in each triangle
  EmbeddingReport counts;
  std::vector<int> touched;
  for (int r = first; r < last; ++r) {
    const CollapseRecord& record = hierarchy.records[r];
    const CollapseChart chart(record, [&](int v) -> const Point3& { return position[v]; });
    ++counts.collapses;
    if (chart.fell_back()) ++counts.fallback_charts;

    touched.clear();
    for (const Triangle& t : record.before) {
      const auto it = head.find(sorted_key(t));
      if (it == head.end()) continue;
      for (int p = it->second; p >= 0; p = points[p].next) touched.push_back(p);
      head.erase(it);
    }
    for (int v : {record.removed, record.kept}) {
      const int vertex_point_of_v = vertex_point[v];
      if (vertex_point_of_v < 0) continue;
      // A kept vertex that does not move stays a vertex point (weight 1 on itself).
      if (v == record.kept && record.placement == record.kept_from) continue;
      vertex_point[v] = -1;
      touched.push_back(vertex_point_of_v);
    }
    for (int p : touched) {
      TrackedPoint& point = points[p];
      const Eigen::Vector2d at =
          point.vertex == record.removed ? chart.removed_position()
          : point.vertex == record.kept  ? chart.kept_position()
                                         : chart.before_position(point.corners, point.weights);
      double snap = 0.0;
      const int t = chart.locate(at, &point.weights, &snap);
      if (snap > 1e-12) ++counts.snapped_points;
      counts.largest_snap = std::max(counts.largest_snap, snap);
      point.vertex = -1;
      point.corners = record.after[t];
      int& first_point = head.try_emplace(sorted_key(point.corners), -1).first->second;
      point.next = first_point;
      first_point = p;
    }
    position[record.kept] = record.placement;
  }

  // The coarse level's numbering: its triangles by sorted finest-mesh vertex triple, and one
  // triangle at each of its vertices.
  const TriangleMesh& mesh = to.mesh;
  std::vector<int> coarse_vertex(finest_points, -1);
  for (size_t i = 0; i < to.finest_vertex.size(); ++i)
    coarse_vertex[to.finest_vertex[i]] = static_cast<int>(i);
  std::unordered_map<TriangleKey, int, TriangleKeyHash> triangle_of;
  triangle_of.reserve(mesh.triangles.size());
  std::vector<int> vertex_triangle(mesh.num_points(), -1);
  for (int t = 0; t < mesh.num_triangles(); ++t) {
    Triangle finest;
    for (int k = 0; k < 3; ++k) {
      finest[k] = to.finest_vertex[mesh.triangles[t][k]];
      if (vertex_triangle[mesh.triangles[t][k]] < 0) vertex_triangle[mesh.triangles[t][k]] = t;
    }
    triangle_of.emplace(sorted_key(finest), t);
  }

  std::vector<EmbeddedPoint> embedded(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const TrackedPoint& point = points[i];
    EmbeddedPoint& out = embedded[i];
    if (point.vertex >= 0) {
      const int v = coarse_vertex[point.vertex];
      if (v < 0 || vertex_triangle[v] < 0)
        throw std::logic_error("intrinsic_embedding: vertex " + std::to_string(point.vertex) +
                               " survives the records but is not on level " +
                               std::to_string(coarse));
      out.triangle = vertex_triangle[v];
      for (int k = 0; k < 3; ++k) out.weights[k] = mesh.triangles[out.triangle][k] == v ? 1.0 : 0.0;
      continue;
    }
    const auto it = triangle_of.find(sorted_key(point.corners));
    if (it == triangle_of.end())
      throw std::logic_error("intrinsic_embedding: triangle (" + std::to_string(point.corners[0]) +
                             ", " + std::to_string(point.corners[1]) + ", " +
                             std::to_string(point.corners[2]) + ") of the records is not on level " +
                             std::to_string(coarse));
    out.triangle = it->second;
    for (int k = 0; k < 3; ++k) {
      const int v = to.finest_vertex[mesh.triangles[out.triangle][k]];
      const int m = static_cast<int>(std::find(point.corners.begin(), point.corners.end(), v) -
                                     point.corners.begin());
      out.weights[k] = std::max(0.0, point.weights[m]);
    }
    out.weights /= out.weights.sum();
  }
  if (report) *report = counts;
  return embedded;
}

}  // namespace mlshell
