// The exact intersection audit: meshes at rest are clean; a sheet folded through itself is
// caught; two triangles are told apart exactly (a vertex 1e-18 above a triangle misses it, one
// on it touches it), between surfaces as within one.
#include <gtest/gtest.h>

#include <cmath>

#include "mlshell/contact/audit/intersection_audit.hpp"
#include "mlshell/triangle/triangle_generators.hpp"

using namespace mlshell;

namespace {

/// One triangle in the plane z = 0 and one standing across it, its tip at height `tip`.
struct TwoTriangles {
  std::vector<Point3> a{Point3(0, 0, 0), Point3(1, 0, 0), Point3(0, 1, 0)};
  std::vector<Point3> b;
  std::vector<Triangle> one{{0, 1, 2}};
  explicit TwoTriangles(double tip) {
    b = {Point3(0.25, 0.25, tip), Point3(0.3, 0.2, 1), Point3(0.2, 0.3, 1)};
  }
};

}  // namespace

TEST(IntersectionAudit, MeshesAtRestAreClean) {
  const TriangleMesh plate = make_unstructured_rectangle(1.0, 1.0, 0.05);
  EXPECT_EQ(self_intersections(plate.points, plate.triangles).pairs, 0);
  const TriangleMesh sphere = make_sphere(1.0, 3);
  EXPECT_EQ(self_intersections(sphere.points, sphere.triangles).pairs, 0);
}

TEST(IntersectionAudit, ASheetFoldedThroughItselfIsCaught) {
  TriangleMesh sheet = make_triangle_rectangle(1.0, 0.25, 16, 4);
  const double tilt = 10.0 * std::acos(-1.0) / 180.0;
  // The right half turned back over the left one, starting below it and rising through it.
  for (Point3& p : sheet.points)
    if (p.x() > 0.5 - 1e-12) {
      const double s = p.x() - 0.5;
      p = Point3(0.5 - s * std::cos(tilt), p.y(), -0.02 + s * std::sin(tilt));
    }
  const IntersectionReport r = self_intersections(sheet.points, sheet.triangles);
  EXPECT_GT(r.pairs, 0);
  ASSERT_FALSE(r.examples.empty());
  for (const auto& [s, t] : r.examples) {
    EXPECT_NE(s, t);
    EXPECT_LT(std::max(s, t), sheet.num_triangles());
  }
  // Folded over it without crossing (above, from the fold line up): clean.
  TriangleMesh above = make_triangle_rectangle(1.0, 0.25, 16, 4);
  for (Point3& p : above.points)
    if (p.x() > 0.5 - 1e-12) {
      const double s = p.x() - 0.5;
      p = Point3(0.5 - s * std::cos(tilt), p.y(), s * std::sin(tilt));
    }
  EXPECT_EQ(self_intersections(above.points, above.triangles).pairs, 0);
}

TEST(IntersectionAudit, DecidesExactlyBetweenSurfaces) {
  // A tip 1e-18 above the triangle misses it, exactly on it touches it, below it pierces it.
  for (const auto& [tip, expected] :
       {std::pair{1e-18, 0L}, std::pair{0.0, 1L}, std::pair{-1e-18, 1L}, std::pair{-0.1, 1L}}) {
    const TwoTriangles t(tip);
    const IntersectionReport r = intersections_between(t.a, t.one, t.b, t.one);
    EXPECT_EQ(r.pairs, expected) << "tip at z = " << tip;
    if (expected) EXPECT_EQ(r.examples.front(), (std::array<int, 2>{0, 0}));
  }
}

TEST(IntersectionAudit, RefusesATriangleSoupThatIsNoSurface) {
  // Three triangles on one edge: no manifold surface, said so instead of a wrong answer.
  const std::vector<Point3> p{Point3(0, 0, 0), Point3(1, 0, 0), Point3(0, 1, 0),
                              Point3(0, -1, 0), Point3(0, 0, 1)};
  const std::vector<Triangle> t{{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  EXPECT_THROW(self_intersections(p, t), std::invalid_argument);
}
