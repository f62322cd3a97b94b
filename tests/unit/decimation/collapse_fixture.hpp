// Small decimation hierarchies made by hand for tests of what is built on the collapse records
// (the intrinsic embedding): edge collapses of a TriangleMesh chosen greedily in rounds, each
// recorded as decimate() records it (CollapseRecord's before/after triangles in finest-mesh
// indices), and a DecimationLevel taken whenever a vertex count is reached. No quadrics: the
// caller says where the kept vertex goes.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "mlshell/decimation/decimation.hpp"

namespace mlshell {

class CollapseSequence {
 public:
  /// Where the kept vertex goes when `removed` merges into `kept` (the sequence's current state).
  using Placement = std::function<Point3(const CollapseSequence&, int removed, int kept)>;

  explicit CollapseSequence(TriangleMesh fine) : fine_(std::move(fine)) {
    fine_.groups.clear();  // the fixture may remove any vertex
    position_ = fine_.points;
    alive_.assign(fine_.points.size(), 1);
    vertex_triangles_.resize(fine_.points.size());
    for (const Triangle& t : fine_.triangles) add_triangle(t);
    alive_count_ = fine_.num_points();
  }

  int alive_count() const { return alive_count_; }
  const Point3& position(int v) const { return position_[v]; }
  int num_records() const { return static_cast<int>(records_.size()); }
  const std::vector<CollapseRecord>& records() const { return records_; }

  /// Alive triangles with both a and b.
  std::vector<int> edge_triangles(int a, int b) const {
    std::vector<int> out;
    for (int t : vertex_triangles_[a])
      if (contains(triangles_[t], b)) out.push_back(t);
    return out;
  }
  std::vector<int> neighbours(int v) const {
    std::vector<int> out;
    for (int t : vertex_triangles_[v])
      for (int u : triangles_[t])
        if (u != v && std::find(out.begin(), out.end(), u) == out.end()) out.push_back(u);
    std::sort(out.begin(), out.end());
    return out;
  }
  bool boundary_edge(int a, int b) const { return edge_triangles(a, b).size() == 1; }
  /// The other ends of v's boundary edges (none for an interior vertex).
  std::vector<int> boundary_neighbours(int v) const {
    std::vector<int> out;
    for (int u : neighbours(v))
      if (boundary_edge(v, u)) out.push_back(u);
    return out;
  }
  /// A boundary vertex whose two boundary edges are collinear.
  bool straight_boundary_vertex(int v) const {
    const auto b = boundary_neighbours(v);
    if (b.size() != 2) return false;
    const Point3 d1 = position_[b[0]] - position_[v], d2 = position_[b[1]] - position_[v];
    return d1.cross(d2).norm() <= 1e-9 * d1.norm() * d2.norm() && d1.dot(d2) < 0.0;
  }

  /// Whether decimate() could make this collapse: the link condition, an interior edge between
  /// interior vertices or a boundary edge whose removed vertex lies on a straight stretch (and
  /// kept too unless it stays put), no triangle flipped (normal turned by more than
  /// max_turn_degrees) or with an angle below min_angle_degrees.
  bool allowed(int removed, int kept, const Point3& placement, double min_angle_degrees = 10.0,
               double max_turn_degrees = 60.0, bool boundary = false) const {
    const auto shared = edge_triangles(removed, kept);
    if (shared.empty()) return false;
    const auto nr = neighbours(removed), nk = neighbours(kept);
    std::vector<int> common;
    std::set_intersection(nr.begin(), nr.end(), nk.begin(), nk.end(), std::back_inserter(common));
    if (common.size() != shared.size()) return false;  // the link condition
    if (nr.size() < 3 || nk.size() < 3) return false;
    if (shared.size() == 2) {
      if (!boundary_neighbours(removed).empty() || !boundary_neighbours(kept).empty()) return false;
    } else {
      if (!boundary || !straight_boundary_vertex(removed)) return false;
      if (!straight_boundary_vertex(kept) && (placement - position_[kept]).norm() > 0.0)
        return false;
      // The placement on the line of the edge.
      const Point3 d = position_[removed] - position_[kept];
      if (d.cross(placement - position_[kept]).norm() > 1e-9 * d.squaredNorm()) return false;
    }
    const double cos_turn = std::cos(max_turn_degrees * std::numbers::pi / 180.0);
    const double min_angle = min_angle_degrees * std::numbers::pi / 180.0;
    for (int v : {removed, kept})
      for (int t : vertex_triangles_[v]) {
        const Triangle& tri = triangles_[t];
        if (contains(tri, removed) && contains(tri, kept)) continue;
        Point3 x[3];
        for (int k = 0; k < 3; ++k)
          x[k] = (tri[k] == removed || tri[k] == kept) ? placement : position_[tri[k]];
        const Point3 n0 = normal(position_[tri[0]], position_[tri[1]], position_[tri[2]]);
        const Point3 n1 = normal(x[0], x[1], x[2]);
        if (!(n1.norm() > 0.0) || n0.normalized().dot(n1.normalized()) < cos_turn) return false;
        for (int k = 0; k < 3; ++k) {
          const Point3 a = x[(k + 1) % 3] - x[k], b = x[(k + 2) % 3] - x[k];
          if (std::atan2(a.cross(b).norm(), a.dot(b)) < min_angle) return false;
        }
      }
    return true;
  }

  /// Merges `removed` into `kept`, which moves to `placement`, and records it (no checks).
  void collapse(int removed, int kept, const Point3& placement) {
    CollapseRecord record;
    record.removed = removed;
    record.kept = kept;
    record.removed_at = position_[removed];
    record.kept_from = position_[kept];
    record.placement = placement;
    std::vector<int> before = vertex_triangles_[removed];
    for (int t : vertex_triangles_[kept])
      if (!contains(triangles_[t], removed)) before.push_back(t);
    std::sort(before.begin(), before.end());
    for (int t : before) {
      const Triangle tri = triangles_[t];
      record.before.push_back(tri);
      remove_triangle(t);
      if (contains(tri, removed) && contains(tri, kept)) continue;
      Triangle after = tri;
      for (int& v : after)
        if (v == removed) v = kept;
      record.after.push_back(after);
      add_triangle(after);
    }
    alive_[removed] = 0;
    --alive_count_;
    position_[kept] = placement;
    records_.push_back(std::move(record));
  }

  /// Greedy rounds of collapses until `target` vertices are left: edges in the order of the
  /// alive triangles, at most one collapse per neighbourhood and round; throws if stuck.
  void collapse_to(int target, const Placement& placement, bool boundary = false) {
    while (alive_count_ > target) {
      std::vector<char> touched(alive_.size(), 0);
      bool progress = false;
      for (size_t t = 0; t < triangles_.size() && alive_count_ > target; ++t) {
        if (!triangle_alive_[t]) continue;
        for (int k = 0; k < 3 && alive_count_ > target && triangle_alive_[t]; ++k) {
          const int a = triangles_[t][k], b = triangles_[t][(k + 1) % 3];
          if (touched[a] || touched[b]) continue;
          for (auto [removed, kept] : {std::pair{std::max(a, b), std::min(a, b)},
                                       std::pair{std::min(a, b), std::max(a, b)}}) {
            const Point3 p = placement(*this, removed, kept);
            if (!allowed(removed, kept, p, 10.0, 60.0, boundary)) continue;
            for (int v : {removed, kept}) {
              touched[v] = 1;
              for (int u : neighbours(v)) touched[u] = 1;
            }
            collapse(removed, kept, p);
            progress = true;
            break;
          }
        }
      }
      if (!progress)
        throw std::runtime_error("collapse fixture: stuck at " + std::to_string(alive_count_) +
                                 " vertices, target " + std::to_string(target));
    }
  }

  /// The current mesh as a level (vertices renumbered in increasing finest index).
  DecimationLevel level() const {
    DecimationLevel level;
    std::vector<int> renumber(alive_.size(), -1);
    for (size_t v = 0; v < alive_.size(); ++v)
      if (alive_[v]) {
        renumber[v] = static_cast<int>(level.finest_vertex.size());
        level.finest_vertex.push_back(static_cast<int>(v));
        level.mesh.points.push_back(position_[v]);
      }
    for (size_t t = 0; t < triangles_.size(); ++t)
      if (triangle_alive_[t]) {
        // Corners turned by t mod 3 (orientation kept): a level need not list a triangle's
        // corners in the order the records do.
        const Triangle& tri = triangles_[t];
        Triangle turned;
        for (int k = 0; k < 3; ++k) turned[k] = renumber[tri[(k + t) % 3]];
        level.mesh.triangles.push_back(turned);
      }
    level.num_records = num_records();
    return level;
  }

 private:
  static bool contains(const Triangle& t, int v) { return t[0] == v || t[1] == v || t[2] == v; }
  static Point3 normal(const Point3& a, const Point3& b, const Point3& c) {
    return (b - a).cross(c - a);
  }
  void add_triangle(const Triangle& t) {
    const int id = static_cast<int>(triangles_.size());
    triangles_.push_back(t);
    triangle_alive_.push_back(1);
    for (int v : t) vertex_triangles_[v].push_back(id);
  }
  void remove_triangle(int id) {
    triangle_alive_[id] = 0;
    for (int v : triangles_[id]) {
      auto& list = vertex_triangles_[v];
      list.erase(std::find(list.begin(), list.end(), id));
    }
  }

  TriangleMesh fine_;
  std::vector<Point3> position_;
  std::vector<char> alive_;
  int alive_count_ = 0;
  std::vector<Triangle> triangles_;
  std::vector<char> triangle_alive_;
  std::vector<std::vector<int>> vertex_triangles_;
  std::vector<CollapseRecord> records_;
};

/// A hierarchy of `fine` with levels of the given vertex counts (finest-but-one first), each by
/// collapse_to. Levels are coarsest first, the fine mesh last, as decimate() returns them.
inline DecimationHierarchy collapse_hierarchy(const TriangleMesh& fine,
                                              const std::vector<int>& vertices,
                                              const CollapseSequence::Placement& placement,
                                              bool boundary = false) {
  CollapseSequence sequence(fine);
  DecimationHierarchy h;
  h.levels.push_back(sequence.level());
  for (int target : vertices) {
    sequence.collapse_to(target, placement, boundary);
    h.levels.push_back(sequence.level());
  }
  std::reverse(h.levels.begin(), h.levels.end());
  h.records = sequence.records();
  h.build_seconds.assign(h.levels.size(), 0.0);
  return h;
}

/// Placements: a fixed fraction of the way from kept to removed...
inline CollapseSequence::Placement along_edge(double fraction) {
  return [fraction](const CollapseSequence& s, int removed, int kept) -> Point3 {
    return s.position(kept) + fraction * (s.position(removed) - s.position(kept));
  };
}
/// ...or the two cycled (0, ½, ¼ of the way, by record count), all in the edge's plane...
inline CollapseSequence::Placement mixed_along_edge() {
  return [](const CollapseSequence& s, int removed, int kept) -> Point3 {
    const double fraction[3] = {0.0, 0.5, 0.25};
    return s.position(kept) + fraction[s.num_records() % 3] * (s.position(removed) - s.position(kept));
  };
}
/// ...or the midpoint pushed out to the sphere of radius R around the origin.
inline CollapseSequence::Placement midpoint_on_sphere(double radius) {
  return [radius](const CollapseSequence& s, int removed, int kept) -> Point3 {
    return radius * (0.5 * (s.position(removed) + s.position(kept))).normalized();
  };
}

}  // namespace mlshell
