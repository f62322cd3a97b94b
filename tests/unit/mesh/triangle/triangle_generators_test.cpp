// Generated triangle meshes: topology, exact and discretised areas, orientation, groups, the
// unstructured rectangle's edge lengths and determinism, and parameter checks.
#include "mlshell/triangle/triangle_generators.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <set>

using namespace mlshell;

namespace {

constexpr double kPi = std::numbers::pi;

/// Twice-area normal of triangle f (its direction is the triangle's orientation).
Point3 area_normal(const TriangleMesh& m, int f) {
  const auto& [a, b, c] = m.triangles[f];
  return (m.points[b] - m.points[a]).cross(m.points[c] - m.points[a]);
}

Point3 centroid(const TriangleMesh& m, int f) {
  const auto& [a, b, c] = m.triangles[f];
  return (m.points[a] + m.points[b] + m.points[c]) / 3.0;
}

double total_area(const TriangleMesh& m) {
  double area = 0.0;
  for (int f = 0; f < m.num_triangles(); ++f) area += 0.5 * area_normal(m, f).norm();
  return area;
}

/// Volume enclosed by a closed mesh, positive when it is oriented outwards.
double signed_volume(const TriangleMesh& m) {
  double volume = 0.0;
  for (const auto& [a, b, c] : m.triangles)
    volume += m.points[a].dot(m.points[b].cross(m.points[c])) / 6.0;
  return volume;
}

double min_angle_degrees(const TriangleMesh& m) {
  double least = 180.0;
  for (const Triangle& t : m.triangles)
    for (int k = 0; k < 3; ++k) {
      const Point3 u = (m.points[t[(k + 1) % 3]] - m.points[t[k]]).normalized();
      const Point3 v = (m.points[t[(k + 2) % 3]] - m.points[t[k]]).normalized();
      least = std::min(least, std::acos(std::clamp(u.dot(v), -1.0, 1.0)) * 180.0 / kPi);
    }
  return least;
}

double edge_length(const TriangleMesh& m, const TriangleEdge& e) {
  return (m.points[e.v[0]] - m.points[e.v[1]]).norm();
}

/// The std::invalid_argument message of `f`, or "no error".
std::string argument_error(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no error";
}

/// Euler characteristic and number of boundary loops.
void expect_topology(const TriangleMesh& m, int euler, int loops) {
  const TriangleTopology t(m);
  EXPECT_EQ(t.euler_characteristic(), euler);
  EXPECT_EQ(static_cast<int>(t.boundary_loops().size()), loops);
  EXPECT_EQ(t.closed(), loops == 0);
}

}  // namespace

TEST(TriangleGenerators, RectangleCountsTopologyAreaAndOrientation) {
  const TriangleMesh m = make_triangle_rectangle(3.0, 2.0, 6, 4, -1.0, 0.5);
  EXPECT_EQ(m.num_points(), 7 * 5);
  EXPECT_EQ(m.num_triangles(), 2 * 6 * 4);
  expect_topology(m, 1, 1);
  EXPECT_NEAR(total_area(m), 6.0, 1e-13);
  for (int f = 0; f < m.num_triangles(); ++f) EXPECT_GT(area_normal(m, f).z(), 0.0) << f;
  EXPECT_EQ(m.points[0], Point3(-1.0, 0.5, 0.0));
  EXPECT_EQ(m.points[4 * 7 + 6], Point3(2.0, 2.5, 0.0));  // vertex (i, j) = j·(nx + 1) + i
  EXPECT_EQ(m.points[1 * 7 + 2], Point3(0.0, 1.0, 0.0));
}

TEST(TriangleGenerators, RectangleDiagonalsAlternate) {
  // Criss-cross: interior vertices with i + j even are on all four cells' diagonals (valence
  // 8), the others on none (valence 4).
  const int nx = 6, ny = 5;
  const TriangleMesh m = make_triangle_rectangle(1.0, 1.0, nx, ny, 0.0, 0.0);
  const TriangleTopology t(m);
  std::vector<int> valence(m.num_points(), 0);
  for (const TriangleEdge& e : t.edges()) ++valence[e.v[0]], ++valence[e.v[1]];
  for (int j = 1; j < ny; ++j)
    for (int i = 1; i < nx; ++i)
      EXPECT_EQ(valence[j * (nx + 1) + i], (i + j) % 2 == 0 ? 8 : 4) << i << ", " << j;
}

// Uniform diagonals: every interior vertex has valence 6, and the two triangles at every
// interior edge form a parallelogram (x2 + x3 = x0 + x1 for each hinge), the property midedge
// bending needs to reproduce every constant curvature.
TEST(TriangleGenerators, RectangleUniformDiagonalsMakeParallelograms) {
  const int nx = 6, ny = 5;
  const TriangleMesh m = make_triangle_rectangle(1.2, 1.0, nx, ny, 0.5, -0.3, true);
  const TriangleTopology t(m);
  EXPECT_EQ(m.num_triangles(), 2 * nx * ny);
  std::vector<int> valence(m.num_points(), 0);
  for (const TriangleEdge& e : t.edges()) ++valence[e.v[0]], ++valence[e.v[1]];
  for (int j = 1; j < ny; ++j)
    for (int i = 1; i < nx; ++i) EXPECT_EQ(valence[j * (nx + 1) + i], 6) << i << ", " << j;
  for (const Hinge& h : t.hinges()) {
    const Point3 mismatch =
        m.points[h.v[2]] + m.points[h.v[3]] - m.points[h.v[0]] - m.points[h.v[1]];
    EXPECT_LT(mismatch.norm(), 1e-14) << h.v[0] << "-" << h.v[1];
  }
}

TEST(TriangleGenerators, RectangleSideGroups) {
  const TriangleMesh m = make_triangle_rectangle(2.0, 1.0, 4, 3, 1.0, 1.0);
  ASSERT_EQ(m.groups.size(), 4u);
  EXPECT_EQ(m.groups.at("left"), (std::vector<int>{0, 5, 10, 15}));
  EXPECT_EQ(m.groups.at("right"), (std::vector<int>{4, 9, 14, 19}));
  EXPECT_EQ(m.groups.at("bottom"), (std::vector<int>{0, 1, 2, 3, 4}));
  EXPECT_EQ(m.groups.at("top"), (std::vector<int>{15, 16, 17, 18, 19}));
}

TEST(TriangleGenerators, BoundaryLoopOfRectangleIsCounterClockwise) {
  const TriangleMesh m = make_triangle_rectangle(2.0, 1.0, 2, 1, 0.0, 0.0);
  const TriangleTopology t(m);
  ASSERT_EQ(t.boundary_loops().size(), 1u);
  EXPECT_EQ(t.boundary_loops()[0], (std::vector<int>{0, 1, 2, 5, 4, 3}));
}

TEST(TriangleGenerators, UnstructuredRectangleEdgeLengthsAndShape) {
  for (const double target : {0.3, 0.1, 0.04}) {
    const double width = 2.0, height = 1.0;
    const TriangleMesh m = make_unstructured_rectangle(width, height, target, 0.5, -1.0);
    expect_topology(m, 1, 1);
    EXPECT_NEAR(total_area(m), width * height, 1e-12);
    for (int f = 0; f < m.num_triangles(); ++f) EXPECT_GT(area_normal(m, f).z(), 0.0) << f;
    EXPECT_GT(min_angle_degrees(m), 20.0);
    const TriangleTopology t(m);
    double sum = 0.0, longest = 0.0, shortest = 1e300;
    for (const TriangleEdge& e : t.edges()) {
      const double l = edge_length(m, e);
      sum += l, longest = std::max(longest, l), shortest = std::min(shortest, l);
      if (e.on_boundary()) {
        // The sides keep their even seeding: 2/target and 1/target segments.
        const bool horizontal = m.points[e.v[0]].y() == m.points[e.v[1]].y();
        const double side = horizontal ? width : height;
        EXPECT_NEAR(l, side / std::round(side / target), 1e-12) << "target " << target;
      }
    }
    const double mean = sum / t.num_edges();
    EXPECT_NEAR(mean / target, 1.0, 0.15) << "target " << target;
    EXPECT_LE(longest, 1.45 * target * (1 + 1e-9)) << "target " << target;
    EXPECT_GT(shortest, 0.5 * target) << "target " << target;
  }
}

TEST(TriangleGenerators, UnstructuredRectangleIsDeterministicAndCanonical) {
  const TriangleMesh a = make_unstructured_rectangle(1.0, 0.7, 0.06, 0.0, 0.0);
  const TriangleMesh b = make_unstructured_rectangle(1.0, 0.7, 0.06, 0.0, 0.0);
  EXPECT_EQ(a.points, b.points);
  EXPECT_EQ(a.triangles, b.triangles);
  EXPECT_EQ(a.groups, b.groups);
  for (int v = 0; v + 1 < a.num_points(); ++v)
    EXPECT_LT(std::make_pair(a.points[v].y(), a.points[v].x()),
              std::make_pair(a.points[v + 1].y(), a.points[v + 1].x()));
  EXPECT_TRUE(std::is_sorted(a.triangles.begin(), a.triangles.end()));
  for (const Triangle& t : a.triangles) EXPECT_LT(t[0], std::min(t[1], t[2]));
}

TEST(TriangleGenerators, UnstructuredRectangleSideGroups) {
  const double x0 = -0.25, y0 = 2.0, w = 1.0, h = 0.5;
  const TriangleMesh m = make_unstructured_rectangle(w, h, 0.1, x0, y0);
  const TriangleTopology t(m);
  ASSERT_EQ(m.groups.size(), 4u);
  EXPECT_EQ(m.groups.at("left").size(), 6u);
  EXPECT_EQ(m.groups.at("right").size(), 6u);
  EXPECT_EQ(m.groups.at("bottom").size(), 11u);
  EXPECT_EQ(m.groups.at("top").size(), 11u);
  std::set<int> sides;
  for (const auto& [name, vertices] : m.groups) {
    EXPECT_TRUE(std::is_sorted(vertices.begin(), vertices.end()));
    for (int v : vertices) {
      const Point3& p = m.points[v];
      if (name == "left") {
        EXPECT_EQ(p.x(), x0);
      }
      if (name == "right") {
        EXPECT_EQ(p.x(), x0 + w);
      }
      if (name == "bottom") {
        EXPECT_EQ(p.y(), y0);
      }
      if (name == "top") {
        EXPECT_EQ(p.y(), y0 + h);
      }
      sides.insert(v);
    }
  }
  ASSERT_EQ(t.boundary_loops().size(), 1u);
  const auto& loop = t.boundary_loops()[0];
  EXPECT_EQ(std::set<int>(loop.begin(), loop.end()), sides);
  // Counter-clockwise seen from +z: positive shoelace area.
  double shoelace = 0.0;
  for (size_t i = 0; i < loop.size(); ++i) {
    const Point3 &p = m.points[loop[i]], &q = m.points[loop[(i + 1) % loop.size()]];
    shoelace += 0.5 * (p.x() * q.y() - q.x() * p.y());
  }
  EXPECT_NEAR(shoelace, w * h, 1e-12);
}

TEST(TriangleGenerators, CylinderTopologyAreaOrientationAndLoops) {
  const double radius = 0.5, length = 2.0;
  for (const int n_around : {3, 8, 9, 32}) {
    const int n_along = 5;
    const TriangleMesh m = make_cylinder(radius, length, n_around, n_along);
    EXPECT_EQ(m.num_points(), n_around * (n_along + 1));
    EXPECT_EQ(m.num_triangles(), 2 * n_around * n_along);
    expect_topology(m, 0, 2);
    // Exactly the area of the inscribed prism.
    EXPECT_NEAR(total_area(m), n_around * 2.0 * radius * std::sin(kPi / n_around) * length, 1e-12);
    for (int f = 0; f < m.num_triangles(); ++f) {
      Point3 radial = centroid(m, f);
      radial.z() = 0.0;
      EXPECT_GT(area_normal(m, f).dot(radial), 0.0) << f;
      EXPECT_NEAR(area_normal(m, f).z(), 0.0, 1e-12) << f;
    }
    for (const Point3& p : m.points) EXPECT_NEAR(std::hypot(p.x(), p.y()), radius, 1e-15);
    const TriangleTopology t(m);
    std::vector<int> bottom(n_around), top{n_around * n_along};
    for (int i = 0; i < n_around; ++i) bottom[i] = i;
    for (int i = n_around - 1; i > 0; --i) top.push_back(n_around * n_along + i);
    EXPECT_EQ(t.boundary_loops()[0], bottom);  // counter-clockwise seen from +z
    EXPECT_EQ(t.boundary_loops()[1], top);     // clockwise seen from +z
    EXPECT_EQ(m.groups.at("bottom"), bottom);
    for (int v : m.groups.at("top")) EXPECT_EQ(m.points[v].z(), length);
    EXPECT_EQ(m.groups.at("top").size(), static_cast<size_t>(n_around));
  }
}

TEST(TriangleGenerators, SphericalCapTopologyOrientationAndGroups) {
  const double radius = 1.3;
  for (const double angle : {0.4, kPi / 2, 2.5, 3.1}) {
    const TriangleMesh m = make_spherical_cap(radius, angle, 6);
    expect_topology(m, 1, 1);
    EXPECT_EQ(m.points[0], Point3(0, 0, radius));
    EXPECT_EQ(m.groups.at("apex"), std::vector<int>{0});
    for (const Point3& p : m.points) EXPECT_NEAR(p.norm(), radius, 1e-14);
    for (int f = 0; f < m.num_triangles(); ++f)
      EXPECT_GT(area_normal(m, f).dot(centroid(m, f)), 0.0) << f;
    const TriangleTopology t(m);
    const auto& loop = t.boundary_loops()[0];
    const auto& boundary = m.groups.at("boundary");
    EXPECT_EQ(std::vector<int>(loop.begin(), loop.end()), boundary);  // ring order = loop order
    for (int v : boundary) EXPECT_NEAR(m.points[v].z(), radius * std::cos(angle), 1e-14);
    EXPECT_GE(boundary.size(), 3u);
  }
}

TEST(TriangleGenerators, SphericalCapAreaConvergesQuadratically) {
  // The inscribed surface misses area of order (ring spacing)², a quarter per halving.
  const double radius = 2.0;
  for (const double angle : {0.5, kPi / 2, 2.5}) {
    const double exact = 2.0 * kPi * radius * radius * (1.0 - std::cos(angle));
    double previous = 0.0;
    for (const int rings : {4, 8, 16, 32}) {
      const TriangleMesh m = make_spherical_cap(radius, angle, rings);
      const double h = angle / rings;
      const double error = (exact - total_area(m)) / exact;
      EXPECT_GT(error, 0.0) << angle << " " << rings;
      EXPECT_LT(error, h * h) << angle << " " << rings;
      if (previous > 0.0) {
        EXPECT_GT(previous / error, 3.0) << angle << " " << rings;
        EXPECT_LT(previous / error, 5.0) << angle << " " << rings;
      }
      previous = error;
    }
  }
}

TEST(TriangleGenerators, SphericalCapTrianglesAreRoughlyUniform) {
  const TriangleMesh m = make_spherical_cap(1.0, kPi / 2, 16);
  EXPECT_GT(min_angle_degrees(m), 25.0);
  const TriangleTopology t(m);
  double shortest = 1e300, longest = 0.0;
  for (const TriangleEdge& e : t.edges()) {
    shortest = std::min(shortest, edge_length(m, e));
    longest = std::max(longest, edge_length(m, e));
  }
  EXPECT_LT(longest / shortest, 2.5);
}

TEST(TriangleGenerators, SphereCountsRadiusOrientationAndArea) {
  const double radius = 1.7;
  double previous = 0.0;
  for (int s = 0; s <= 4; ++s) {
    const TriangleMesh m = make_sphere(radius, s);
    const int p = 1 << (2 * s);
    EXPECT_EQ(m.num_points(), 10 * p + 2);
    EXPECT_EQ(m.num_triangles(), 20 * p);
    expect_topology(m, 2, 0);
    for (const Point3& x : m.points) EXPECT_NEAR(x.norm(), radius, 1e-14);
    for (int f = 0; f < m.num_triangles(); ++f)
      EXPECT_GT(area_normal(m, f).dot(centroid(m, f)), 0.0) << f;
    const double volume = signed_volume(m), exact_volume = 4.0 / 3.0 * kPi * std::pow(radius, 3);
    EXPECT_GT(volume, 0.0);
    EXPECT_LT(volume, exact_volume);
    const double exact = 4.0 * kPi * radius * radius;
    const double error = (exact - total_area(m)) / exact;
    if (s == 0) {
      // The icosahedron inscribed in the sphere: edge = radius / sin(2π/5).
      const double a = radius / std::sin(2.0 * kPi / 5.0);
      EXPECT_NEAR(total_area(m), 5.0 * std::sqrt(3.0) * a * a, 1e-12);
    } else if (s >= 2) {  // from the icosahedron to s = 1 the ratio is 3.3
      EXPECT_GT(previous / error, 3.5) << s;
      EXPECT_LT(previous / error, 4.5) << s;
    }
    previous = error;
  }
}

TEST(TriangleGenerators, SphereTrianglesAreWellShaped) {
  EXPECT_GT(min_angle_degrees(make_sphere(1.0, 4)), 50.0);
}

TEST(TriangleGenerators, RejectsNonsenseParameters) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(argument_error([] { make_triangle_rectangle(1, 1, 0, 2, 0, 0); }),
            "make_triangle_rectangle: nx = 0 (expected an integer >= 1)");
  EXPECT_EQ(argument_error([] { make_triangle_rectangle(-1, 1, 2, 2, 0, 0); }),
            "make_triangle_rectangle: width = -1 (expected a positive finite number)");
  EXPECT_EQ(argument_error([&] { make_triangle_rectangle(1, nan, 2, 2, 0, 0); }),
            "make_triangle_rectangle: height = nan (expected a positive finite number)");
  EXPECT_EQ(argument_error([&] { make_triangle_rectangle(1, 1, 2, 2, nan, 0); }),
            "make_triangle_rectangle: x0 = nan (expected a finite number)");
  const std::string too_many =
      argument_error([] { make_triangle_rectangle(1, 1, 100000, 100000, 0, 0); });
  EXPECT_NE(too_many.find("nx = 100000 (expected a mesh small enough for int vertex indices)"),
            std::string::npos);
  EXPECT_EQ(argument_error([] { make_unstructured_rectangle(1, 1, 0, 0, 0); }),
            "make_unstructured_rectangle: edge_length = 0 (expected a positive finite number)");
  const std::string too_fine =
      argument_error([] { make_unstructured_rectangle(1, 1, 1e-5, 0, 0); });
  EXPECT_NE(too_fine.find("edge_length = 1e-05 (expected at most 1e8 squares"), std::string::npos);
  EXPECT_EQ(argument_error([] { make_cylinder(1, 1, 2, 1); }),
            "make_cylinder: n_around = 2 (expected an integer >= 3)");
  EXPECT_EQ(argument_error([] { make_cylinder(1, 0, 3, 1); }),
            "make_cylinder: length = 0 (expected a positive finite number)");
  EXPECT_EQ(argument_error([] { make_cylinder(1, 1, 3, 0); }),
            "make_cylinder: n_along = 0 (expected an integer >= 1)");
  EXPECT_EQ(argument_error([] { make_spherical_cap(1, kPi, 3); }),
            "make_spherical_cap: opening_angle = 3.14159 (expected an angle in (0, pi) radians)");
  EXPECT_NE(argument_error([] { make_spherical_cap(1, 0, 3); }).find("opening_angle = 0"),
            std::string::npos);
  EXPECT_EQ(argument_error([] { make_spherical_cap(1, 1, 0); }),
            "make_spherical_cap: n_rings = 0 (expected an integer >= 1)");
  EXPECT_EQ(argument_error([] { make_spherical_cap(0, 1, 2); }),
            "make_spherical_cap: radius = 0 (expected a positive finite number)");
  EXPECT_EQ(argument_error([] { make_sphere(1, -1); }),
            "make_sphere: subdivisions = -1 (expected an integer >= 0)");
  EXPECT_EQ(argument_error([] { make_sphere(1, 14); }),
            "make_sphere: subdivisions = 14 (expected at most 13)");
  EXPECT_EQ(argument_error([] { make_sphere(-2, 1); }),
            "make_sphere: radius = -2 (expected a positive finite number)");
}
