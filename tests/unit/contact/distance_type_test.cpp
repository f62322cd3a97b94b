// Contact distance classification: the squared distance of the classified type equals a
// brute-force minimum over densely sampled points of the two primitives, for random states
// (where every type must occur) and for hand-built degenerate ones (parallel, nearly parallel
// and crossing edges, zero-length edges, points in the triangle's plane, degenerate triangles).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <random>
#include <string>

#include "contact_fixtures.hpp"
#include "mlshell/contact/distance/edge_edge.hpp"
#include "mlshell/contact/distance/point_triangle.hpp"

using namespace mlshell;
using Eigen::Vector3d;
using mlshell::test::sampled_edge_edge_distance;
using mlshell::test::sampled_point_triangle_distance;

namespace {

/// The classified distance is the minimum: never above any sample (to round-off), and the
/// samples come within their own resolution of it.
void expect_minimum(double classified, double sampled, const std::string& where) {
  EXPECT_LE(classified, sampled + 1e-13) << where;
  EXPECT_LE(sampled - classified, 1e-9)
      << where << " classified " << classified << " sampled " << sampled;
}

void expect_point_triangle(const Vector3d& p, const Vector3d& t0, const Vector3d& t1,
                           const Vector3d& t2, const std::string& where) {
  expect_minimum(point_triangle_distance(p, t0, t1, t2),
                 sampled_point_triangle_distance(p, t0, t1, t2), where);
}

void expect_edge_edge(const Vector3d& a0, const Vector3d& a1, const Vector3d& b0,
                      const Vector3d& b1, const std::string& where) {
  expect_minimum(edge_edge_distance(a0, a1, b0, b1), sampled_edge_edge_distance(a0, a1, b0, b1),
                 where);
}

}  // namespace

TEST(ContactDistanceType, PointTriangleRandomStatesMatchSampledMinimum) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::array<int, 7> seen{};
  for (int k = 0; k < 300; ++k) {
    Vector3d x[4];
    for (auto& v : x) v = Vector3d(u(rng), u(rng), u(rng));
    ++seen[static_cast<int>(point_triangle_distance_type(x[0], x[1], x[2], x[3]))];
    expect_point_triangle(x[0], x[1], x[2], x[3], "random " + std::to_string(k));
  }
  for (int t = 0; t < 7; ++t) EXPECT_GT(seen[t], 0) << "point–triangle type " << t << " never seen";
}

TEST(ContactDistanceType, EdgeEdgeRandomStatesMatchSampledMinimum) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::array<int, 9> seen{};
  for (int k = 0; k < 300; ++k) {
    Vector3d x[4];
    for (auto& v : x) v = Vector3d(u(rng), u(rng), u(rng));
    ++seen[static_cast<int>(edge_edge_distance_type(x[0], x[1], x[2], x[3]))];
    expect_edge_edge(x[0], x[1], x[2], x[3], "random " + std::to_string(k));
  }
  for (int t = 0; t < 9; ++t) EXPECT_GT(seen[t], 0) << "edge–edge type " << t << " never seen";
}

TEST(ContactDistanceType, EdgeEdgeParallelAndDegenerateMatchSampledMinimum) {
  std::mt19937 rng(13);
  for (int k = 0; k < 20; ++k) {
    const Eigen::Matrix3d R = mlshell::test::random_rotation(rng);
    const auto m = [&](double x, double y, double z) { return Vector3d(R * Vector3d(x, y, z)); };
    const std::string at = " (rotation " + std::to_string(k) + ")";
    // Exactly parallel: overlapping, apart, opposite directions, collinear.
    expect_edge_edge(m(0, 0, 0), m(1, 0, 0), m(0.3, 0.5, 0), m(1.5, 0.5, 0),
                     "parallel overlapping" + at);
    expect_edge_edge(m(0, 0, 0), m(1, 0, 0), m(1.5, 0.5, 0), m(2.5, 0.5, 0), "parallel apart" + at);
    expect_edge_edge(m(0, 0, 0), m(1, 0, 0), m(1.5, 0.5, 0.2), m(0.3, 0.5, 0.2),
                     "antiparallel" + at);
    expect_edge_edge(m(0, 0, 0), m(1, 0, 0), m(1.5, 0, 0), m(2.5, 0, 0), "collinear apart" + at);
    // Nearly parallel, on both sides of the threshold sin²θ = 10⁻¹⁰.
    for (double tilt : {1e-7, 1e-5, 1e-3, 1e-1})
      expect_edge_edge(m(0, 0, 0), m(1, 0, 0), m(0.3, 0.5, 0), m(1.5, 0.5, tilt),
                       "nearly parallel, tilt " + std::to_string(tilt) + at);
    // Crossing at a point, and touching at an endpoint.
    expect_edge_edge(m(0, 0, 0), m(1, 0, 0), m(0.5, -0.5, 0), m(0.5, 0.5, 0), "crossing" + at);
    expect_edge_edge(m(0, 0, 0), m(1, 0, 0), m(1, 0, 0), m(1, 1, 1), "shared endpoint" + at);
    // Zero-length edges.
    expect_edge_edge(m(0, 0, 0), m(1, 0, 0), m(0.5, 0.2, 0.3), m(0.5, 0.2, 0.3), "point b" + at);
    expect_edge_edge(m(0.4, 0.4, 0.4), m(0.4, 0.4, 0.4), m(0, 0, 0), m(1, 0, 0), "point a" + at);
  }
}

TEST(ContactDistanceType, PointTriangleDegenerateMatchSampledMinimum) {
  std::mt19937 rng(14);
  for (int k = 0; k < 20; ++k) {
    const Eigen::Matrix3d R = mlshell::test::random_rotation(rng);
    const auto m = [&](double x, double y, double z) { return Vector3d(R * Vector3d(x, y, z)); };
    const Vector3d t0 = m(0, 0, 0), t1 = m(1, 0, 0), t2 = m(0, 1, 0);
    const std::string at = " (rotation " + std::to_string(k) + ")";
    // In the plane: inside, on an edge, beyond an edge, beyond a vertex.
    expect_point_triangle(m(0.2, 0.3, 0), t0, t1, t2, "in the plane, inside" + at);
    expect_point_triangle(m(0.5, 0.5, 0), t0, t1, t2, "on the hypotenuse" + at);
    expect_point_triangle(m(0.5, -0.5, 0), t0, t1, t2, "in the plane, beyond an edge" + at);
    expect_point_triangle(m(1.5, -0.5, 0), t0, t1, t2, "in the plane, beyond a vertex" + at);
    // At a vertex, and on an edge's line beyond the triangle.
    expect_point_triangle(t1, t0, t1, t2, "at a vertex" + at);
    expect_point_triangle(m(2, 0, 0.3), t0, t1, t2, "above the edge's line" + at);
    // Degenerate triangles: collinear vertices, and all three at one point.
    expect_point_triangle(m(0.5, 0.5, 0.5), t0, t1, m(2, 0, 0), "collinear triangle" + at);
    expect_point_triangle(m(0.5, 0.5, 0.5), t0, t0, t0, "point triangle" + at);
  }
}
