// Contact broad phase (contact/broad_phase/broad_phase.hpp): the spatial hash and the BVH find
// exactly the same sorted candidates; the proximity candidates hold every pair closer than the
// distance (brute force over all pairs); no candidate shares a vertex; the swept candidates
// hold every pair that additive CCD reports colliding, but for CCD's own false positives.
#include "mlshell/contact/broad_phase/broad_phase.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <random>
#include <stdexcept>

#include "contact/ccd_fixtures.hpp"
#include "contact/stacked_sheets.hpp"

namespace mlshell {
namespace {

using test::stacked_sheets;

constexpr auto kHash = BroadPhaseMethod::kSpatialHash;
constexpr auto kBvh = BroadPhaseMethod::kBvh;

/// Two rippled 6 × 6 sheets 0.05 apart (ripple ±0.02) with every vertex jittered by up to 0.01.
test::SheetScene small_scene(unsigned seed) {
  auto s = stacked_sheets(2, 6, 0.05, 0.02);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.01, 0.01);
  for (auto& p : s.x) p += Eigen::Vector3d(jitter(rng), jitter(rng), jitter(rng));
  return s;
}

/// A step x → x1 that moves the upper sheet down through the lower one and swirls both.
std::vector<Eigen::Vector3d> step_through(const test::SheetScene& s, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> swirl(-0.03, 0.03);
  std::vector<Eigen::Vector3d> x1 = s.x;
  const std::size_t half = s.x.size() / 2;
  for (std::size_t i = 0; i < x1.size(); ++i)
    x1[i] += Eigen::Vector3d(swirl(rng), swirl(rng), (i < half ? 0.02 : -0.1) + swirl(rng));
  return x1;
}

template <class T>
bool contains(const std::vector<T>& sorted, const T& value) {
  return std::binary_search(sorted.begin(), sorted.end(), value);
}

void expect_sorted_unique_and_disjoint(const ContactSurface& surface, const ContactCandidates& c) {
  EXPECT_TRUE(std::adjacent_find(c.point_triangle.begin(), c.point_triangle.end(),
                                 std::greater_equal<>()) == c.point_triangle.end());
  EXPECT_TRUE(std::adjacent_find(c.edge_edge.begin(), c.edge_edge.end(), std::greater_equal<>()) ==
              c.edge_edge.end());
  for (const auto& [v, f] : c.point_triangle) {
    const auto& t = surface.faces[f];
    EXPECT_TRUE(t[0] != v && t[1] != v && t[2] != v) << v << " in face " << f;
  }
  for (const auto& [a, b] : c.edge_edge) {
    EXPECT_LT(a, b);
    const auto &ea = surface.edges[a], &eb = surface.edges[b];
    EXPECT_TRUE(ea[0] != eb[0] && ea[0] != eb[1] && ea[1] != eb[0] && ea[1] != eb[1])
        << "edges " << a << " and " << b << " share a vertex";
  }
}

TEST(ContactBroadPhase, SurfaceEdgesAreUniqueAndSorted) {
  const auto s = ContactSurface::from_faces(4, {{0, 1, 2}, {2, 1, 3}});
  const std::vector<std::array<int, 2>> expected = {{0, 1}, {0, 2}, {1, 2}, {1, 3}, {2, 3}};
  EXPECT_EQ(s.edges, expected);
  EXPECT_THROW(ContactSurface::from_faces(3, {{0, 1, 3}}), std::invalid_argument);
  EXPECT_THROW(ContactSurface::from_faces(3, {{0, 1, 1}}), std::invalid_argument);
}

TEST(ContactBroadPhase, BothMethodsFindTheSameSortedCandidates) {
  for (const unsigned seed : {1u, 2u, 3u}) {
    const auto s = small_scene(seed);
    const auto x1 = step_through(s, seed);
    for (const double distance : {0.0, 0.01, 0.05, 0.3}) {
      SCOPED_TRACE(testing::Message() << "seed " << seed << " distance " << distance);
      const auto hash = find_proximity_candidates(s.surface, s.x, distance, kHash);
      const auto bvh = find_proximity_candidates(s.surface, s.x, distance, kBvh);
      EXPECT_EQ(hash, bvh);
      expect_sorted_unique_and_disjoint(s.surface, bvh);
      const auto swept_hash = find_swept_candidates(s.surface, s.x, x1, distance, kHash);
      const auto swept_bvh = find_swept_candidates(s.surface, s.x, x1, distance, kBvh);
      EXPECT_EQ(swept_hash, swept_bvh);
      expect_sorted_unique_and_disjoint(s.surface, swept_bvh);
      EXPECT_GE(swept_bvh.size(), bvh.size());
      if (distance > 0.0) EXPECT_GT(bvh.size(), 0u);
    }
  }
}

TEST(ContactBroadPhase, ProximityCandidatesHoldEveryPairCloserThanTheDistance) {
  const auto s = small_scene(7);
  const auto& x = s.x;
  for (const double distance : {0.03, 0.05, 0.1}) {
    SCOPED_TRACE(distance);
    const double d2 = distance * distance;
    const auto c = find_proximity_candidates(s.surface, x, distance, kHash);
    int close = 0;
    for (int v = 0; v < s.surface.num_vertices; ++v)
      for (int f = 0; f < static_cast<int>(s.surface.faces.size()); ++f) {
        const auto& t = s.surface.faces[f];
        if (t[0] == v || t[1] == v || t[2] == v) continue;
        if (point_triangle_distance(x[v], x[t[0]], x[t[1]], x[t[2]]) < d2) {
          ++close;
          EXPECT_TRUE(contains(c.point_triangle, PointTriangleCandidate{v, f})) << v << " " << f;
        }
      }
    const auto& edges = s.surface.edges;
    for (int a = 0; a < static_cast<int>(edges.size()); ++a)
      for (int b = a + 1; b < static_cast<int>(edges.size()); ++b) {
        const auto &ea = edges[a], &eb = edges[b];
        if (ea[0] == eb[0] || ea[0] == eb[1] || ea[1] == eb[0] || ea[1] == eb[1]) continue;
        if (edge_edge_distance(x[ea[0]], x[ea[1]], x[eb[0]], x[eb[1]]) < d2) {
          ++close;
          EXPECT_TRUE(contains(c.edge_edge, EdgeEdgeCandidate{a, b})) << a << " " << b;
        }
      }
    EXPECT_GT(close, 0);  // the scene has teeth
    // The boxes prune: far from every pair of a mesh of 72 vertices and 100 faces.
    EXPECT_LT(c.point_triangle.size(), 72u * 100u / 2);
  }
}

TEST(ContactBroadPhase, SweptCandidatesHoldEveryPairThatCcdReportsColliding) {
  using test::MovingStencil;
  using test::StencilKind;
  const double thickness = 0.01;
  for (const unsigned seed : {11u, 12u}) {
    const auto s = small_scene(seed);
    const auto x1 = step_through(s, seed);
    const auto c = find_swept_candidates(s.surface, s.x, x1, thickness, kBvh);
    const auto stencil = [&](StencilKind kind, std::array<int, 4> v) {
      MovingStencil m;
      m.kind = kind;
      for (int i = 0; i < 4; ++i) m.set(i, s.x[v[i]], x1[v[i]] - s.x[v[i]]);
      return m;
    };
    int colliding = 0, ccd_false_positives = 0;
    for (int v = 0; v < s.surface.num_vertices; ++v)
      for (int f = 0; f < static_cast<int>(s.surface.faces.size()); ++f) {
        const auto& t = s.surface.faces[f];
        if (t[0] == v || t[1] == v || t[2] == v) continue;
        const auto m = stencil(StencilKind::kPointTriangle, {v, t[0], t[1], t[2]});
        if (!m.ccd(thickness, 1.0).may_collide) continue;
        ++colliding;
        if (contains(c.point_triangle, PointTriangleCandidate{v, f})) continue;
        ++ccd_false_positives;  // allowed only where the pair never comes within ξ
        EXPECT_FALSE(std::isfinite(test::first_contact_time(m, thickness, 1.0))) << v << " " << f;
      }
    const auto& edges = s.surface.edges;
    for (int a = 0; a < static_cast<int>(edges.size()); ++a)
      for (int b = a + 1; b < static_cast<int>(edges.size()); ++b) {
        const auto &ea = edges[a], &eb = edges[b];
        if (ea[0] == eb[0] || ea[0] == eb[1] || ea[1] == eb[0] || ea[1] == eb[1]) continue;
        const auto m = stencil(StencilKind::kEdgeEdge, {ea[0], ea[1], eb[0], eb[1]});
        if (!m.ccd(thickness, 1.0).may_collide) continue;
        ++colliding;
        if (contains(c.edge_edge, EdgeEdgeCandidate{a, b})) continue;
        ++ccd_false_positives;
        EXPECT_FALSE(std::isfinite(test::first_contact_time(m, thickness, 1.0))) << a << " " << b;
      }
    EXPECT_GT(colliding, 20);  // the upper sheet falls through the lower one
    EXPECT_LT(ccd_false_positives, colliding / 2);
  }
}

TEST(ContactBroadPhase, BothMethodsAgreeOnALargerStack) {
  // 3 layers of 30 × 30 cells (5,400 faces): too large for the brute force above, so the BVH
  // is the hash's reference here.
  const auto s = stacked_sheets(3, 30, 0.01, 0.004);
  std::vector<Eigen::Vector3d> x1 = s.x;
  for (std::size_t i = 0; i < x1.size(); ++i) x1[i].z() += (i < x1.size() / 3 ? 0.01 : -0.01);
  const auto hash = find_proximity_candidates(s.surface, s.x, 0.004, kHash);
  EXPECT_EQ(hash, find_proximity_candidates(s.surface, s.x, 0.004, kBvh));
  const auto swept = find_swept_candidates(s.surface, s.x, x1, 0.001, kHash);
  EXPECT_EQ(swept, find_swept_candidates(s.surface, s.x, x1, 0.001, kBvh));
  EXPECT_GT(swept.size(), hash.size());
}

TEST(ContactBroadPhase, OneVertexMovingFarKeepsBothMethodsEqual) {
  auto s = small_scene(5);
  auto x1 = s.x;
  x1[3] += Eigen::Vector3d(40.0, -25.0, 60.0);  // a box thousands of cells long
  const auto hash = find_swept_candidates(s.surface, s.x, x1, 0.01, kHash);
  const auto bvh = find_swept_candidates(s.surface, s.x, x1, 0.01, kBvh);
  EXPECT_EQ(hash, bvh);
  expect_sorted_unique_and_disjoint(s.surface, bvh);
}

TEST(ContactBroadPhase, RejectsInvalidInput) {
  const auto s = small_scene(1);
  EXPECT_THROW(find_proximity_candidates(s.surface, s.x, -1.0), std::invalid_argument);
  EXPECT_THROW(find_proximity_candidates(s.surface, s.x, std::numeric_limits<double>::infinity()),
               std::invalid_argument);
  auto few = s.x;
  few.pop_back();
  EXPECT_THROW(find_proximity_candidates(s.surface, few, 0.1), std::invalid_argument);
  auto nan = s.x;
  nan[2].y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(find_swept_candidates(s.surface, s.x, nan, 0.1), std::invalid_argument);
}

}  // namespace
}  // namespace mlshell
