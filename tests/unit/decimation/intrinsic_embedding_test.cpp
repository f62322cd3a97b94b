// The intrinsic embedding of a decimation hierarchy (mesh/decimation/intrinsic_embedding.cpp) on
// hierarchies made by hand (collapse_fixture.hpp): a flat plate (boundary collapses included),
// a dome and a sphere.
#include "mlshell/decimation/intrinsic_embedding.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <numbers>

#include "decimation/collapse_fixture.hpp"
#include "mlshell/triangle/triangle_generators.hpp"

namespace mlshell {
namespace {

DecimationHierarchy flat_plate() {
  return collapse_hierarchy(make_triangle_rectangle(2.0, 1.0, 16, 8), {110, 75, 45},
                            mixed_along_edge(), /*boundary=*/true);
}
/// Half-edge collapses (the kept vertex stays where it is), interior and boundary.
DecimationHierarchy half_edge_plate() {
  return collapse_hierarchy(make_triangle_rectangle(2.0, 1.0, 16, 8), {110, 75, 45},
                            along_edge(0.0), /*boundary=*/true);
}
DecimationHierarchy dome() {
  const TriangleMesh cap = make_spherical_cap(1.0, 1.0, 8);
  const int n = cap.num_points();
  return collapse_hierarchy(cap, {n * 6 / 10, n * 35 / 100}, midpoint_on_sphere(1.0));
}
DecimationHierarchy sphere() {
  return collapse_hierarchy(make_sphere(1.0, 3), {350, 180, 90}, midpoint_on_sphere(1.0));
}

/// Whether level `fine`'s vertex i is also a vertex of level `coarse` (its index there, or -1).
int surviving_index(const DecimationHierarchy& h, int coarse, int fine, int i) {
  const auto& c = h.levels[coarse].finest_vertex;
  const int v = h.levels[fine].finest_vertex[i];
  const auto it = std::lower_bound(c.begin(), c.end(), v);
  return it != c.end() && *it == v ? static_cast<int>(it - c.begin()) : -1;
}

/// Where level `fine`'s vertex i is when it stops being a vertex on the way to level `coarse`:
/// where the collapse that removes it finds it, or its place on `coarse` if it survives. A
/// vertex is a point that moves with its vertex until then (kept vertices move to placements),
/// and a point of the surface after.
Point3 tracked_start(const DecimationHierarchy& h, int coarse, int fine, int i) {
  const int v = h.levels[fine].finest_vertex[i];
  for (int r = h.levels[fine].num_records; r < h.levels[coarse].num_records; ++r)
    if (h.records[r].removed == v) return h.records[r].removed_at;
  return h.levels[coarse].mesh.points[surviving_index(h, coarse, fine, i)];
}

Point3 embedded_position(const DecimationHierarchy& h, int coarse, const EmbeddedPoint& p) {
  const TriangleMesh& mesh = h.levels[coarse].mesh;
  Point3 x = Point3::Zero();
  for (int k = 0; k < 3; ++k) x += p.weights[k] * mesh.points[mesh.triangles[p.triangle][k]];
  return x;
}

double mean_edge_length(const TriangleMesh& mesh) {
  double sum = 0.0;
  for (const Triangle& t : mesh.triangles)
    for (int k = 0; k < 3; ++k) sum += (mesh.points[t[k]] - mesh.points[t[(k + 1) % 3]]).norm();
  return sum / (3.0 * mesh.num_triangles());
}

/// Rows of U: one per fine vertex, a coarse triangle, weights ≥ 0 summing to 1.
void expect_valid(const DecimationHierarchy& h, int coarse, int fine,
                  const std::vector<EmbeddedPoint>& points) {
  ASSERT_EQ(static_cast<int>(points.size()), h.levels[fine].mesh.num_points());
  for (size_t i = 0; i < points.size(); ++i) {
    const EmbeddedPoint& p = points[i];
    ASSERT_GE(p.triangle, 0) << "vertex " << i;
    ASSERT_LT(p.triangle, h.levels[coarse].mesh.num_triangles()) << "vertex " << i;
    ASSERT_TRUE(p.weights.allFinite()) << "vertex " << i;
    EXPECT_GE(p.weights.minCoeff(), -1e-12) << "vertex " << i << " " << coarse << "←" << fine;
    EXPECT_NEAR(p.weights.sum(), 1.0, 1e-12) << "vertex " << i;
  }
}

TEST(IntrinsicEmbedding, PartitionOfUnityOnEveryLevelPair) {
  for (const auto& h : {flat_plate(), dome(), sphere()})
    for (int fine = 1; fine < h.num_levels(); ++fine)
      for (int coarse = 0; coarse < fine; ++coarse) {
        EmbeddingReport report;
        const auto points = intrinsic_embedding(h, coarse, fine, &report);
        expect_valid(h, coarse, fine, points);
        EXPECT_EQ(report.collapses, h.levels[coarse].num_records - h.levels[fine].num_records);
      }
}

TEST(IntrinsicEmbedding, VerticesThatNeverMoveKeepWeightOne) {
  // A vertex of the finer level that reaches the coarser one where it was (every boundary
  // vertex, and interior ones never moved by a placement) has weight 1 on itself; a moved one
  // is anchored where it was, inside a coarse triangle (paper 2 §4.2).
  for (const bool plate : {true, false}) {
    const DecimationHierarchy h = plate ? flat_plate() : sphere();
    for (int fine = 1; fine < h.num_levels(); ++fine)
      for (int coarse = 0; coarse < fine; ++coarse) {
        const auto points = intrinsic_embedding(h, coarse, fine);
        const DecimationLevel& c = h.levels[coarse];
        int unmoved = 0, moved = 0;
        for (size_t i = 0; i < points.size(); ++i) {
          const int own = surviving_index(h, coarse, fine, static_cast<int>(i));
          if (own < 0) continue;
          if (c.mesh.points[own] != h.levels[fine].mesh.points[i]) {
            ++moved;
            continue;
          }
          ++unmoved;
          const Triangle& t = c.mesh.triangles[points[i].triangle];
          for (int k = 0; k < 3; ++k)
            EXPECT_EQ(points[i].weights[k], t[k] == own ? 1.0 : 0.0)
                << "vertex " << i << " levels " << coarse << "←" << fine;
        }
        if (plate) EXPECT_GT(unmoved, 0);  // its boundary never moves
        EXPECT_GT(moved, 0);
        EXPECT_EQ(unmoved + moved, c.mesh.num_points());
      }
  }
}

TEST(IntrinsicEmbedding, FlatPlateIsReproducedExactly) {
  // Every placement lies in the plane, on the collapsed edge: each joint flattening is one
  // similarity of the plane, and both split vertices are anchored where they were, so every
  // point is embedded exactly at its rest position on the fine level, whether the collapses
  // move vertices or not (half-edge collapses).
  for (const bool half_edge : {false, true}) {
    const DecimationHierarchy h = half_edge ? half_edge_plate() : flat_plate();
    ASSERT_GT(h.records.size(), 100u);
    int boundary_records = 0, moved = 0;
    for (const auto& r : h.records) {
      boundary_records += r.before.size() == r.after.size() + 1;
      moved += r.placement != r.kept_from;
    }
    ASSERT_GT(boundary_records, 3);
    ASSERT_EQ(moved > 0, !half_edge);
    for (int fine = 1; fine < h.num_levels(); ++fine)
      for (int coarse = 0; coarse < fine; ++coarse) {
        EmbeddingReport report;
        const auto points = intrinsic_embedding(h, coarse, fine, &report);
        EXPECT_EQ(report.fallback_charts, 0);
        EXPECT_EQ(report.snapped_points, 0);
        double worst = 0.0;
        for (size_t i = 0; i < points.size(); ++i) {
          const int v = static_cast<int>(i);
          const Point3 expected = h.levels[fine].mesh.points[v];
          worst = std::max(worst, (embedded_position(h, coarse, points[i]) - expected).norm());
        }
        EXPECT_LT(worst, 1e-12 * 2.0)
            << (half_edge ? "half-edge" : "mixed") << " levels " << coarse << "←" << fine;
      }
  }
}

TEST(IntrinsicEmbedding, ComposesThroughAMiddleLevel) {
  // Flat, half-edge collapses (no vertex moves): fine → coarse and fine → middle → coarse give
  // the same positions.
  const DecimationHierarchy plate = half_edge_plate();
  const int fine = plate.num_levels() - 1, middle = 1, coarse = 0;
  const auto direct = intrinsic_embedding(plate, coarse, fine);
  const auto first = intrinsic_embedding(plate, middle, fine);
  const auto second = intrinsic_embedding(plate, coarse, middle);
  const TriangleMesh& mid = plate.levels[middle].mesh;
  for (size_t i = 0; i < direct.size(); ++i) {
    Point3 composed = Point3::Zero();
    for (int k = 0; k < 3; ++k)
      composed += first[i].weights[k] *
                  embedded_position(plate, coarse, second[mid.triangles[first[i].triangle][k]]);
    EXPECT_LT((composed - embedded_position(plate, coarse, direct[i])).norm(), 2e-12)
        << "vertex " << i;
  }
  // Curved: a fine vertex that reaches the middle level unmoved is tracked from there on as the
  // middle level's vertex, so both embeddings agree exactly.
  const DecimationHierarchy s = sphere();
  const int sf = s.num_levels() - 1, sm = 2, sc = 0;
  const auto s_direct = intrinsic_embedding(s, sc, sf);
  const auto s_second = intrinsic_embedding(s, sc, sm);
  for (size_t i = 0; i < s_direct.size(); ++i) {
    const int m = surviving_index(s, sm, sf, static_cast<int>(i));
    if (m < 0 || s.levels[sm].mesh.points[m] != s.levels[sf].mesh.points[i]) continue;
    const EmbeddedPoint& other = s_second[m];
    EXPECT_EQ(s_direct[i].triangle, other.triangle) << "vertex " << i;
    EXPECT_EQ(s_direct[i].weights, other.weights) << "vertex " << i;
  }
}

TEST(IntrinsicEmbedding, CurvedSurfacesStayNearTheFineVertices) {
  // Not exact on a curved surface: a point's place drifts a little with each flattening
  // (measured: at most 0.27 of the coarse mean edge from its fine rest position on the sphere,
  // 552 collapses to 90 vertices).
  for (const auto& h : {dome(), sphere()}) {
    const int fine = h.num_levels() - 1;
    for (int coarse = 0; coarse < fine; ++coarse) {
      EmbeddingReport report;
      const auto points = intrinsic_embedding(h, coarse, fine, &report);
      double from_rest = 0.0;
      for (size_t i = 0; i < points.size(); ++i) {
        const Point3 x = embedded_position(h, coarse, points[i]);
        from_rest = std::max(from_rest, (x - h.levels[fine].mesh.points[i]).norm());
      }
      const double size = mean_edge_length(h.levels[coarse].mesh);
      EXPECT_LT(from_rest, 0.5 * size) << "levels " << coarse << "←" << fine;
      // Interior collapses share their link in both charts: nothing falls outside.
      EXPECT_EQ(report.fallback_charts, 0);
      EXPECT_EQ(report.snapped_points, 0);
    }
  }
}

TEST(IntrinsicEmbedding, FoldedChartFallsBack) {
  // A collapse whose placement lies beyond the one-ring: the after triangles fold in space and
  // in the LSCM chart, so the kept vertex goes into its link's kernel instead.
  const TriangleMesh plate = make_triangle_rectangle(1.0, 1.0, 8, 8);
  CollapseSequence s(plate);
  DecimationHierarchy h;
  h.levels.push_back(s.level());
  const int removed = 4 * 9 + 4, kept = 4 * 9 + 5;
  s.collapse(removed, kept, s.position(kept) + 2.5 * (s.position(kept) - s.position(removed)));
  s.collapse_to(50, along_edge(0.5));
  h.levels.push_back(s.level());
  std::reverse(h.levels.begin(), h.levels.end());
  h.records = s.records();
  EmbeddingReport report;
  const auto points = intrinsic_embedding(h, 0, 1, &report);
  expect_valid(h, 0, 1, points);
  EXPECT_GE(report.fallback_charts, 1);
  // The kernel chart covers the link polygon as the before chart does: nothing is snapped.
  EXPECT_EQ(report.snapped_points, 0);
  EXPECT_LT(report.largest_snap, 1e-12);
}

TEST(IntrinsicEmbedding, WavyLinkFallsBackToTutte) {
  // One interior edge (0, 0, 0)–(1, 0, 0) whose link of ten vertices around it zigzags up and
  // down by ±1: the LSCM chart of so much angle excess folds, and the link laid out by it is
  // seen counter-clockwise from no point (an empty kernel), so the collapse gets Tutte's chart
  // (link on a circle), which covers the same polygon before and after.
  const int m = 10, j = m / 2;
  TriangleMesh ring;
  ring.points = {Point3(0, 0, 0), Point3(1, 0, 0)};
  for (int i = 0; i < m; ++i) {
    const double angle = std::numbers::pi / 2 + 2 * std::numbers::pi * i / m;
    ring.points.emplace_back(0.5 + 1.5 * std::cos(angle), 1.5 * std::sin(angle), i % 2 ? 1.0 : -1.0);
  }
  const auto link = [&](int i) { return 2 + i % m; };
  ring.triangles = {{0, 1, link(0)}, {1, 0, link(j)}};
  for (int i = 0; i < j; ++i) ring.triangles.push_back({0, link(i), link(i + 1)});
  for (int i = j; i < m; ++i) ring.triangles.push_back({1, link(i), link(i + 1)});
  CollapseSequence s(ring);
  DecimationHierarchy h;
  h.levels.push_back(s.level());
  s.collapse(0, 1, Point3(0.5, 0.0, 0.0));
  h.levels.push_back(s.level());
  std::reverse(h.levels.begin(), h.levels.end());
  h.records = s.records();
  EmbeddingReport report;
  const auto points = intrinsic_embedding(h, 0, 1, &report);
  expect_valid(h, 0, 1, points);
  EXPECT_EQ(report.fallback_charts, 1);
  EXPECT_EQ(report.snapped_points, 0);
  // Tutte's chart by hand: link vertex i at angle 2πi/m on the unit circle, the removed and
  // kept vertices at the average of their neighbours, the kept one at the circle's centre after.
  std::vector<Eigen::Vector2d> circle(m);
  for (int i = 0; i < m; ++i)
    circle[i] = {std::cos(2 * std::numbers::pi * i / m), std::sin(2 * std::numbers::pi * i / m)};
  Eigen::Vector2d around_removed = Eigen::Vector2d::Zero(), around_kept = Eigen::Vector2d::Zero();
  for (int i = 0; i <= j; ++i) around_removed += circle[i];
  for (int i = j; i <= m; ++i) around_kept += circle[i % m];
  // 7 r − k = Σ, 7 k − r = Σ' (each has six link neighbours and the other).
  const Eigen::Vector2d removed = (7.0 * around_removed + around_kept) / 48.0;
  Point3 expected = Point3::Zero();
  int found = 0;
  for (int i = 0; i < m; ++i) {
    const Eigen::Vector2d a = circle[i], b = circle[(i + 1) % m];
    const double area = a.x() * b.y() - a.y() * b.x();  // (0, a, b), twice its area
    const double wa = (removed.x() * b.y() - removed.y() * b.x()) / area;
    const double wb = (a.x() * removed.y() - a.y() * removed.x()) / area;
    if (wa < 0 || wb < 0 || wa + wb > 1) continue;
    ++found;
    const auto& x = h.levels[0].mesh.points;  // coarse: kept = 0, link i = 1 + i
    expected = (1 - wa - wb) * x[0] + wa * x[1 + i] + wb * x[1 + (i + 1) % m];
  }
  ASSERT_EQ(found, 1);
  EXPECT_LT((embedded_position(h, 0, points[0]) - expected).norm(), 1e-12);
}

TEST(IntrinsicEmbedding, RejectsLevelsOutOfOrder) {
  const DecimationHierarchy h = flat_plate();
  EXPECT_THROW(intrinsic_embedding(h, 1, 1), std::invalid_argument);
  EXPECT_THROW(intrinsic_embedding(h, 2, 1), std::invalid_argument);
  EXPECT_THROW(intrinsic_embedding(h, 0, h.num_levels()), std::invalid_argument);
}

// Timing, by hand: --gtest_also_run_disabled_tests --gtest_filter='IntrinsicEmbedding.*Timing*'.
TEST(IntrinsicEmbedding, DISABLED_LargeSphereTiming) {
  const auto start = std::chrono::steady_clock::now();
  const DecimationHierarchy h =
      collapse_hierarchy(make_sphere(1.0, 7), {40000, 10000, 2500}, midpoint_on_sphere(1.0));
  const auto built = std::chrono::steady_clock::now();
  EmbeddingReport report;
  double seconds = 0.0;
  for (int fine = 1; fine < h.num_levels(); ++fine) {
    const auto t0 = std::chrono::steady_clock::now();
    const auto points = intrinsic_embedding(h, fine - 1, fine, &report);
    seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    expect_valid(h, fine - 1, fine, points);
  }
  const auto t0 = std::chrono::steady_clock::now();
  const auto direct = intrinsic_embedding(h, 0, h.num_levels() - 1, &report);
  const double direct_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cout << h.levels.back().mesh.num_triangles() << " faces, " << h.records.size()
            << " records; fixture " << std::chrono::duration<double>(built - start).count()
            << " s; level by level " << seconds << " s; finest → coarsest " << direct_seconds
            << " s (fallbacks " << report.fallback_charts << ", snapped " << report.snapped_points
            << ", largest snap " << report.largest_snap << ")\n";
}

}  // namespace
}  // namespace mlshell
