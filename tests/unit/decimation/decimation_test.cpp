// Decimation hierarchies (paper 2 §4.1, mesh/decimation/decimation.cpp): every level reaches its
// vertex count, is a valid mesh of the fine mesh's topology (Euler characteristic, boundary
// loops), and replays from the records; boundaries keep their fine shape and corners, groups
// their vertices where they were; no triangle folds or gets thin; the same input gives the same
// hierarchy bit for bit; nonsense options and unreachable targets are refused by name.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <stdexcept>

#include "mlshell/decimation/decimation.hpp"
#include "mlshell/triangle/triangle_generators.hpp"

using namespace mlshell;

namespace {

constexpr double kDegree = std::numbers::pi / 180.0;

Triangle canonical(Triangle t) {
  std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  return t;
}

/// A level's triangles in finest-mesh indices, rotated to start at their smallest vertex.
std::set<Triangle> finest_triangles(const DecimationLevel& level) {
  std::set<Triangle> s;
  for (const Triangle& t : level.mesh.triangles)
    s.insert(canonical({level.finest_vertex[t[0]], level.finest_vertex[t[1]],
                        level.finest_vertex[t[2]]}));
  return s;
}

double min_angle(const Point3& a, const Point3& b, const Point3& c) {
  const auto angle = [](const Point3& p, const Point3& q, const Point3& r) {
    const Eigen::Vector3d u = q - p, v = r - p;
    return std::atan2(u.cross(v).norm(), u.dot(v));
  };
  return std::min({angle(a, b, c), angle(b, c, a), angle(c, a, b)});
}

double mesh_min_angle(const TriangleMesh& m) {
  double least = std::numbers::pi;
  for (const Triangle& t : m.triangles)
    least = std::min(least, min_angle(m.points[t[0]], m.points[t[1]], m.points[t[2]]));
  return least;
}

Point3 normal(const TriangleMesh& m, const Triangle& t) {
  return (m.points[t[1]] - m.points[t[0]]).cross(m.points[t[2]] - m.points[t[0]]);
}

Point3 centroid(const TriangleMesh& m, const Triangle& t) {
  return (m.points[t[0]] + m.points[t[1]] + m.points[t[2]]) / 3.0;
}

/// A unit square plate of n × n cells with the cells of [0.375, 0.625]² cut out (a square hole),
/// no groups.
TriangleMesh plate_with_hole(int n) {
  const TriangleMesh plate = make_triangle_rectangle(1.0, 1.0, n, n);
  TriangleMesh m;
  std::vector<int> index(plate.points.size(), -1);
  for (const Triangle& t : plate.triangles) {
    const Point3 c = centroid(plate, t);
    if (std::abs(c.x() - 0.5) < 0.125 && std::abs(c.y() - 0.5) < 0.125) continue;
    Triangle u{};
    for (int k = 0; k < 3; ++k) {
      if (index[t[k]] < 0) {
        index[t[k]] = m.num_points();
        m.points.push_back(plate.points[t[k]]);
      }
      u[k] = index[t[k]];
    }
    m.triangles.push_back(u);
  }
  return m;
}

/// What every hierarchy must satisfy: level counts, targets, numbering, validity, topology, and
/// the fine mesh as the last level.
void expect_valid_levels(const DecimationHierarchy& h, const TriangleMesh& fine,
                         const DecimationOptions& options) {
  const int n = static_cast<int>(options.vertices.size());
  ASSERT_EQ(h.num_levels(), n + 1);
  ASSERT_EQ(static_cast<int>(h.build_seconds.size()), n + 1);
  const TriangleTopology fine_topology(fine);
  EXPECT_EQ(h.levels.back().num_records, 0);
  EXPECT_EQ(h.levels.back().mesh.points, fine.points);
  EXPECT_EQ(h.levels.back().mesh.triangles, fine.triangles);
  EXPECT_EQ(h.levels.front().num_records, static_cast<int>(h.records.size()));
  for (int l = 0; l < n; ++l) {
    const DecimationLevel& level = h.levels[l];
    const int target = options.vertices[n - 1 - l];
    SCOPED_TRACE("level " + std::to_string(l));
    EXPECT_LE(level.mesh.num_points(), target);
    EXPECT_GE(level.mesh.num_points(), target - 3);
    EXPECT_EQ(level.mesh.num_points(), fine.num_points() - level.num_records);
    EXPECT_GT(level.num_records, h.levels[l + 1].num_records);
    EXPECT_GE(h.build_seconds[l], 0.0);
    ASSERT_EQ(level.finest_vertex.size(), level.mesh.points.size());
    EXPECT_TRUE(std::is_sorted(level.finest_vertex.begin(), level.finest_vertex.end()));
    EXPECT_NO_THROW(validate_triangle_mesh(level.mesh, "level"));
    const TriangleTopology topology(level.mesh);
    EXPECT_EQ(topology.euler_characteristic(), fine_topology.euler_characteristic());
    EXPECT_EQ(topology.boundary_loops().size(), fine_topology.boundary_loops().size());
  }
}

/// Triangles keep at least min(bound, the fine mesh's least angle); every triangle's normal
/// points to the fine surface's side given by `outward(centroid)`.
template <class Outward>
void expect_no_folds_or_slivers(const DecimationHierarchy& h, const TriangleMesh& fine,
                                const DecimationOptions& options, Outward outward) {
  const double bound = std::min(options.min_angle_degrees * kDegree, mesh_min_angle(fine));
  for (int l = 0; l + 1 < h.num_levels(); ++l) {
    const TriangleMesh& m = h.levels[l].mesh;
    EXPECT_GE(mesh_min_angle(m), bound - 1e-6) << "level " << l;
    int flipped = 0;
    for (const Triangle& t : m.triangles)
      if (normal(m, t).normalized().dot(outward(centroid(m, t))) <= 0.0) ++flipped;
    EXPECT_EQ(flipped, 0) << "level " << l;
  }
}

/// Applying the records in order from the fine mesh gives every level's triangles; undoing them
/// (removing `after`, adding `before`) from the coarsest gives every level back to the fine one.
void expect_replay(const DecimationHierarchy& h, const TriangleMesh& fine) {
  std::set<Triangle> current;
  for (const Triangle& t : fine.triangles) current.insert(canonical(t));
  const std::set<Triangle> fine_set = current;
  int done = 0;
  for (int l = h.num_levels() - 1; l >= 0; --l) {
    for (; done < h.levels[l].num_records; ++done) {
      const CollapseRecord& r = h.records[done];
      ASSERT_NE(r.removed, r.kept);
      for (const Triangle& t : r.before) ASSERT_EQ(current.erase(canonical(t)), 1u) << done;
      for (const Triangle& t : r.after) {
        ASSERT_TRUE(current.insert(canonical(t)).second) << done;
        ASSERT_EQ(std::count(t.begin(), t.end(), r.removed), 0) << done;
      }
    }
    ASSERT_EQ(current, finest_triangles(h.levels[l])) << "level " << l;
  }
  for (int l = 0; l < h.num_levels(); ++l) {
    for (; done > h.levels[l].num_records; --done) {
      const CollapseRecord& r = h.records[done - 1];
      for (const Triangle& t : r.after) ASSERT_EQ(current.erase(canonical(t)), 1u) << done;
      for (const Triangle& t : r.before) ASSERT_TRUE(current.insert(canonical(t)).second);
    }
    ASSERT_EQ(current, finest_triangles(h.levels[l])) << "expanding, level " << l;
  }
  EXPECT_EQ(current, fine_set);
}

/// The records' positions agree with the levels: a level's vertex is where the last record that
/// kept it placed it, or at its fine position.
void expect_record_positions(const DecimationHierarchy& h, const TriangleMesh& fine) {
  std::vector<Point3> at = fine.points;
  std::vector<char> alive(fine.points.size(), 1);
  int done = 0;
  for (int l = h.num_levels() - 1; l >= 0; --l) {
    for (; done < h.levels[l].num_records; ++done) {
      const CollapseRecord& r = h.records[done];
      ASSERT_TRUE(alive[r.removed] && alive[r.kept]);
      EXPECT_EQ(r.removed_at, at[r.removed]);
      EXPECT_EQ(r.kept_from, at[r.kept]);
      alive[r.removed] = 0;
      at[r.kept] = r.placement;
    }
    const DecimationLevel& level = h.levels[l];
    for (int v = 0; v < level.mesh.num_points(); ++v) {
      ASSERT_TRUE(alive[level.finest_vertex[v]]);
      ASSERT_EQ(level.mesh.points[v], at[level.finest_vertex[v]]) << "level " << l;
    }
  }
}

/// Whether p lies on the segment a–c to within `tolerance` × its length.
bool on_segment(const Point3& p, const Point3& a, const Point3& c, double tolerance) {
  const Point3 ac = c - a;
  const double t = (p - a).dot(ac) / ac.squaredNorm();
  return t > 0.0 && t < 1.0 && (p - a - t * ac).norm() <= tolerance * ac.norm();
}

/// Every level's boundary vertex is a fine boundary vertex at its fine position; the fine
/// corners survive; each level's boundary edge a–b covers fine boundary vertices that all lie on
/// the segment a–b (the boundary keeps its shape). Returns how many fine boundary vertices the
/// coarsest level lost.
int expect_boundary_kept(const DecimationHierarchy& h, const TriangleMesh& fine, double tolerance) {
  const TriangleTopology fine_topology(fine);
  std::vector<int> loop_of(fine.points.size(), -1), position(fine.points.size(), -1);
  std::vector<char> corner(fine.points.size(), 0);
  const auto& loops = fine_topology.boundary_loops();
  for (int k = 0; k < static_cast<int>(loops.size()); ++k)
    for (int i = 0; i < static_cast<int>(loops[k].size()); ++i) {
      const int n = static_cast<int>(loops[k].size());
      const int v = loops[k][i];
      loop_of[v] = k, position[v] = i;
      corner[v] = !on_segment(fine.points[v], fine.points[loops[k][(i + n - 1) % n]],
                              fine.points[loops[k][(i + 1) % n]], tolerance + 1e-12);
    }
  int lost = 0;
  for (int l = 0; l + 1 < h.num_levels(); ++l) {
    SCOPED_TRACE("level " + std::to_string(l));
    const DecimationLevel& level = h.levels[l];
    const TriangleTopology topology(level.mesh);
    std::vector<char> kept(fine.points.size(), 0);
    for (int v = 0; v < level.mesh.num_points(); ++v) {
      const int f = level.finest_vertex[v];
      kept[f] = 1;
      if (!topology.on_boundary(v)) continue;
      EXPECT_TRUE(fine_topology.on_boundary(f)) << "vertex " << f;
      EXPECT_EQ(level.mesh.points[v], fine.points[f]) << "vertex " << f;
    }
    for (int f = 0; f < fine.num_points(); ++f) {
      if (corner[f]) EXPECT_TRUE(kept[f]) << "corner " << f;
      if (l == 0 && loop_of[f] >= 0 && !kept[f]) ++lost;
    }
    for (const auto& loop : topology.boundary_loops())
      for (size_t i = 0; i < loop.size(); ++i) {
        const int a = level.finest_vertex[loop[i]];
        const int b = level.finest_vertex[loop[(i + 1) % loop.size()]];
        EXPECT_EQ(loop_of[a], loop_of[b]);
        if (loop_of[a] < 0 || loop_of[a] != loop_of[b]) continue;
        const auto& fine_loop = loops[loop_of[a]];
        const int n = static_cast<int>(fine_loop.size());
        for (int j = (position[a] + 1) % n; fine_loop[j] != b; j = (j + 1) % n) {
          EXPECT_FALSE(kept[fine_loop[j]]);
          EXPECT_TRUE(on_segment(fine.points[fine_loop[j]], fine.points[a], fine.points[b],
                                 tolerance + 1e-12))
              << "fine vertex " << fine_loop[j] << " off the level's edge " << a << "–" << b;
        }
      }
  }
  return lost;
}

DecimationHierarchy decimate_by_ratio(const TriangleMesh& fine, int levels, double ratio,
                                      DecimationOptions* used = nullptr) {
  DecimationOptions o = DecimationOptions::by_ratio(fine.num_points(), levels, ratio);
  if (used) *used = o;
  return decimate(fine, o);
}

}  // namespace

TEST(Decimation, SphereLevelsReachTheirTargetsWithTheTopologyKept) {
  const TriangleMesh fine = make_sphere(1.0, 4);  // 2562 vertices
  DecimationOptions o;
  const DecimationHierarchy h = decimate_by_ratio(fine, 4, 4.0, &o);
  EXPECT_EQ(o.vertices, (std::vector<int>{641, 160, 40}));
  expect_valid_levels(h, fine, o);
  expect_no_folds_or_slivers(h, fine, o, [](const Point3& c) { return c.normalized(); });
}

TEST(Decimation, PlateLevelsKeepTheBoundaryShapeAndCorners) {
  TriangleMesh fine = make_unstructured_rectangle(2.0, 1.0, 0.05);
  // The sides' groups stay: a side group loses vertices along its side only.
  DecimationOptions o;
  const DecimationHierarchy h = decimate_by_ratio(fine, 4, 4.0, &o);
  expect_valid_levels(h, fine, o);
  expect_no_folds_or_slivers(h, fine, o, [](const Point3&) { return Point3(0, 0, 1); });
  // Straight sides do get coarser: the rule keeps the shape without pinning the boundary.
  EXPECT_GT(expect_boundary_kept(h, fine, o.boundary_deviation), 30);
  for (const DecimationLevel& level : h.levels)
    for (const Point3& p : level.mesh.points) EXPECT_EQ(p.z(), 0.0);
}

TEST(Decimation, PlateWithAHoleKeepsBothLoopsAndTheirCorners) {
  const TriangleMesh fine = plate_with_hole(24);
  DecimationOptions o;
  const DecimationHierarchy h = decimate_by_ratio(fine, 3, 3.0, &o);
  expect_valid_levels(h, fine, o);
  EXPECT_EQ(TriangleTopology(h.levels.front().mesh).boundary_loops().size(), 2u);
  EXPECT_GT(expect_boundary_kept(h, fine, o.boundary_deviation), 20);
  expect_no_folds_or_slivers(h, fine, o, [](const Point3&) { return Point3(0, 0, 1); });
  expect_replay(h, fine);
}

TEST(Decimation, DomeRimCoarsensIntoChordsWithinTheDeviationAndFacesOutwards) {
  TriangleMesh fine = make_spherical_cap(1.0, 1.0, 24);
  fine.groups.clear();
  const int rim = static_cast<int>(TriangleTopology(fine).boundary_loops()[0].size());
  // Every rim vertex lies off the chord of its neighbours: with a deviation of 1e-6 the rim
  // stays whole; with the default (5 % of a chord) a level with fewer vertices than the rim
  // has is in reach, every fine rim vertex within 5 % of the chord that replaced it.
  DecimationOptions o;
  o.vertices = {fine.num_points() / 3};
  o.boundary_deviation = 1e-6;
  const DecimationHierarchy strict = decimate(fine, o);
  expect_valid_levels(strict, fine, o);
  EXPECT_EQ(expect_boundary_kept(strict, fine, o.boundary_deviation), 0);
  o = DecimationOptions{};
  o.vertices = {fine.num_points() / 3, rim / 2};
  const DecimationHierarchy h = decimate(fine, o);
  expect_valid_levels(h, fine, o);
  EXPECT_GE(expect_boundary_kept(h, fine, o.boundary_deviation), rim / 2);
  expect_no_folds_or_slivers(h, fine, o, [](const Point3& c) { return c.normalized(); });
}

TEST(Decimation, BoundaryVerticesOffTheSegmentStayWithinTheStraightnessTolerance) {
  // A square plate whose every second side vertex sticks out by 1e-5 of a cell (in the plane):
  // with boundary_deviation 1e-6 no side vertex lies on the segment of its neighbours within
  // 1e-6 of its length, so none may go however cheap its collapse, and 36 vertices (fewer than
  // the 120 on the sides) are out of reach; with 1e-3 the sides coarsen again.
  const int n = 30;
  TriangleMesh fine = make_triangle_rectangle(1.0, 1.0, n, n);
  fine.groups.clear();
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) {
      const bool side_x = i == 0 || i == n, side_y = j == 0 || j == n;
      if (side_x == side_y || (i + j) % 2 == 0) continue;  // interior, corner, or unmoved
      Point3& p = fine.points[j * (n + 1) + i];
      const double bump = 1e-5 / n;
      if (side_x) p.x() += i == 0 ? -bump : bump;
      if (side_y) p.y() += j == 0 ? -bump : bump;
    }
  DecimationOptions o = DecimationOptions::by_ratio(fine.num_points(), 4, 3.0);
  o.boundary_deviation = 1e-6;
  ASSERT_EQ(o.vertices.back(), 36);
  EXPECT_THROW(decimate(fine, o), MeshError);
  const std::vector<int> targets = o.vertices;
  o.vertices = {320, 160};
  const DecimationHierarchy strict = decimate(fine, o);
  EXPECT_EQ(expect_boundary_kept(strict, fine, o.boundary_deviation), 0);
  o.boundary_deviation = 1e-3;
  o.vertices = targets;
  const DecimationHierarchy loose = decimate(fine, o);
  expect_valid_levels(loose, fine, o);
  EXPECT_GT(expect_boundary_kept(loose, fine, o.boundary_deviation), 60);
}

TEST(Decimation, NormalChangeBoundRefusesCollapsesOnCurvedSurfacesOnly) {
  // On an icosphere of 642 vertices every collapse turns some normal by degrees: a bound of
  // 0.5° leaves the target out of reach. On a flat plate no normal turns.
  DecimationOptions o;
  o.max_normal_change_degrees = 0.5;
  const TriangleMesh sphere = make_sphere(1.0, 3);
  o.vertices = {400};
  EXPECT_THROW(decimate(sphere, o), MeshError);
  o.max_normal_change_degrees = 60;
  EXPECT_NO_THROW(decimate(sphere, o));
  o.max_normal_change_degrees = 0.5;
  TriangleMesh plate = make_unstructured_rectangle(1.0, 1.0, 0.05);
  o.vertices = {plate.num_points() / 2};
  EXPECT_NO_THROW(decimate(plate, o));
}

TEST(Decimation, RecordsReplayEveryLevelAndExpandBackToTheFineMesh) {
  TriangleMesh plate = make_unstructured_rectangle(1.0, 1.0, 0.06);
  plate.groups.clear();
  for (const TriangleMesh& fine : {make_sphere(1.0, 3), plate}) {
    const DecimationHierarchy h = decimate_by_ratio(fine, 4, 3.0);
    expect_replay(h, fine);
    expect_record_positions(h, fine);
    for (const CollapseRecord& r : h.records) {
      // The two triangles on the edge go (one on the boundary), the rest are relabelled.
      const size_t gone = r.before.size() - r.after.size();
      EXPECT_TRUE(gone == 1 || gone == 2);
    }
  }
}

TEST(Decimation, GroupsKeepTheirMeaningAndVerticesNeverMove) {
  // The rectangle's side groups (left, right, bottom, top: a corner is in two), an interior line
  // and single-vertex groups (as the scene's point selections are kept).
  TriangleMesh fine = make_unstructured_rectangle(1.0, 1.0, 0.04);
  std::vector<int>& line = fine.groups["line"];
  std::vector<std::string> spots;
  for (int v = 0; v < fine.num_points(); ++v) {
    const Point3& p = fine.points[v];
    const bool interior = p.x() > 1e-9 && p.x() < 1 - 1e-9 && p.y() > 1e-9 && p.y() < 1 - 1e-9;
    if (!interior) continue;
    if (std::abs(p.x() - 0.5) < 0.02 && p.y() > 0.2 && p.y() < 0.8) line.push_back(v);
    if (v % 97 == 0) {
      spots.push_back("spot" + std::to_string(v));
      fine.groups[spots.back()] = {v};
    }
  }
  ASSERT_GE(line.size(), 5u);
  ASSERT_GE(spots.size(), 3u);
  std::vector<std::set<std::string>> groups_of(fine.num_points());
  for (const auto& [name, vertices] : fine.groups)
    for (int v : vertices) groups_of[v].insert(name);
  DecimationOptions o;
  const DecimationHierarchy h = decimate_by_ratio(fine, 3, 4.0, &o);
  expect_valid_levels(h, fine, o);
  for (const DecimationLevel& level : h.levels) {
    ASSERT_EQ(level.mesh.groups.size(), fine.groups.size());
    for (const auto& [name, vertices] : fine.groups) {
      // The level's group is exactly its surviving vertices of the fine group, unmoved.
      std::vector<int> survivors;
      for (size_t k = 0; k < level.finest_vertex.size(); ++k)
        if (std::binary_search(vertices.begin(), vertices.end(), level.finest_vertex[k]))
          survivors.push_back(static_cast<int>(k));
      const std::vector<int>& g = level.mesh.groups.at(name);
      EXPECT_EQ(g, survivors) << name;
      EXPECT_FALSE(g.empty()) << name;
      for (int k : g) EXPECT_EQ(level.mesh.points[k], fine.points[level.finest_vertex[k]]) << name;
    }
    for (const std::string& spot : spots) EXPECT_EQ(level.mesh.groups.at(spot).size(), 1u);
  }
  // The sides do lose vertices along them: the boundary is decimated, not pinned.
  EXPECT_LT(2 * h.levels.front().mesh.groups.at("left").size(), fine.groups.at("left").size());
  for (const CollapseRecord& r : h.records) {
    // A group vertex goes only into a vertex of the same groups, and a kept one never moves.
    if (!groups_of[r.removed].empty()) EXPECT_EQ(groups_of[r.removed], groups_of[r.kept]);
    if (!groups_of[r.kept].empty()) EXPECT_EQ(r.placement, r.kept_from);
  }
}

TEST(Decimation, SameInputSameFingerprint) {
  const TriangleMesh fine = make_sphere(1.0, 3);
  const DecimationOptions o = DecimationOptions::by_ratio(fine.num_points(), 3, 4.0);
  const DecimationHierarchy a = decimate(fine, o), b = decimate(fine, o);
  EXPECT_EQ(a.fingerprint().size(), 16u);
  EXPECT_EQ(a.fingerprint(), b.fingerprint());
  ASSERT_EQ(a.records.size(), b.records.size());
  for (size_t i = 0; i < a.records.size(); ++i) {
    EXPECT_EQ(a.records[i].removed, b.records[i].removed);
    EXPECT_EQ(a.records[i].placement, b.records[i].placement);
  }
  TriangleMesh moved = fine;
  moved.points[7] *= 1.01;
  EXPECT_NE(decimate(moved, o).fingerprint(), a.fingerprint());
  DecimationOptions fewer = o;
  fewer.vertices.back() -= 5;
  EXPECT_NE(decimate(fine, fewer).fingerprint(), a.fingerprint());
}

TEST(Decimation, NonsenseOptionsAreRefusedByName) {
  const auto message = [](auto f) {
    try {
      f();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  EXPECT_EQ(message([] { DecimationOptions::by_ratio(100, 3, 1.0); }),
            "hierarchy: ratio 1 must be > 1");
  EXPECT_NE(message([] { DecimationOptions::by_ratio(100, 1, 2.0); }).find("levels 1"),
            std::string::npos);
  DecimationOptions o;
  EXPECT_NE(message([&] { o.validate(100); }).find("levels 1"), std::string::npos);
  o.vertices = {50, 50};
  EXPECT_NE(message([&] { o.validate(100); }).find("vertices[1] = 50 must be < vertices[0] = 50"),
            std::string::npos);
  o.vertices = {100, 20};
  EXPECT_NE(message([&] { o.validate(100); }).find("vertices[0] = 100 must be < the fine mesh's"),
            std::string::npos);
  o.vertices = {50, 3};
  EXPECT_NE(message([&] { o.validate(100); }).find("vertices[1] = 3 must be >= 4"),
            std::string::npos);
  o.vertices = {50, 20};
  EXPECT_EQ(message([&] { o.validate(100); }), "no exception");
  o.min_angle_degrees = 75;
  EXPECT_NE(message([&] { o.validate(100); }).find("min_angle_degrees 75"), std::string::npos);
  o.min_angle_degrees = 10;
  o.max_normal_change_degrees = 0;
  EXPECT_NE(message([&] { o.validate(100); }).find("max_normal_change_degrees 0"),
            std::string::npos);
  o.max_normal_change_degrees = 60;
  o.boundary_deviation = -1;
  EXPECT_NE(message([&] { o.validate(100); }).find("boundary_deviation -1"), std::string::npos);
  // decimate() checks its options before anything else.
  o.boundary_deviation = 1e-6;
  o.vertices = {2000};
  EXPECT_THROW(decimate(make_sphere(1.0, 1), o), std::invalid_argument);
}

TEST(Decimation, UnreachableTargetsNameTheLevelAndTheCounts) {
  const auto message = [](const TriangleMesh& fine, std::vector<int> vertices) {
    DecimationOptions o;
    o.vertices = std::move(vertices);
    o.boundary_deviation = 1e-6;
    try {
      decimate(fine, o);
    } catch (const MeshError& e) {
      return std::string(e.what());
    }
    return std::string("no exception");
  };
  // Every vertex a group of its own (a point selection): nothing may go.
  TriangleMesh pinned = make_triangle_rectangle(1.0, 1.0, 4, 4);
  for (int v = 0; v < pinned.num_points(); ++v) pinned.groups["v" + std::to_string(v)] = {v};
  EXPECT_NE(message(pinned, {20}).find("level 0 of 2 (0 coarsest): reached 25 vertices, target 20"),
            std::string::npos)
      << message(pinned, {20});
  // A dome's rim is curved, so with a deviation of 1e-6 it keeps all its vertices: fewer
  // vertices than the rim has is out of reach (on the coarsest level, after a reachable one).
  TriangleMesh dome = make_spherical_cap(1.0, 1.0, 8);
  dome.groups.clear();
  const int rim = static_cast<int>(TriangleTopology(dome).boundary_loops()[0].size());
  const std::string m = message(dome, {rim + 20, rim - 2});
  EXPECT_NE(m.find("level 0 of 3"), std::string::npos) << m;
  EXPECT_NE(m.find("target " + std::to_string(rim - 2)), std::string::npos) << m;
}
