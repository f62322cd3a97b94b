// Contact distances: closed-form gradients and Hessians of the primitives (point–point,
// point–line, point–plane, line–line) and of every point–edge, point–triangle and edge–edge
// type against central differences, at generic, rotated and degenerate states (point in the
// plane, point on the edge's line, edges crossing at a point, nearly parallel lines), plus
// known values and the refusal of degenerate primitives.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>
#include <stdexcept>
#include <string>

#include "contact_fixtures.hpp"
#include "mlshell/contact/distance/edge_edge.hpp"
#include "mlshell/contact/distance/line_line.hpp"
#include "mlshell/contact/distance/point_edge.hpp"
#include "mlshell/contact/distance/point_line.hpp"
#include "mlshell/contact/distance/point_plane.hpp"
#include "mlshell/contact/distance/point_point.hpp"
#include "mlshell/contact/distance/point_triangle.hpp"

using namespace mlshell;
using Eigen::Vector3d;
using mlshell::test::expect_derivatives;
using mlshell::test::random_rotation;
using mlshell::test::stack;
using mlshell::test::vertex;

namespace {

Vector6 stack2(const Vector3d& a, const Vector3d& b) {
  Vector6 x;
  x << a, b;
  return x;
}

void expect_point_triangle_derivatives(const Vector12& x, PointTriangleDistanceType type,
                                       const std::string& where) {
  expect_derivatives<12>(
      [&](const Vector12& y, Vector12* g, Matrix12* H) {
        return point_triangle_distance(vertex(y, 0), vertex(y, 1), vertex(y, 2), vertex(y, 3), type,
                                       g, H);
      },
      x, 1.0, where);
}

void expect_edge_edge_derivatives(const Vector12& x, EdgeEdgeDistanceType type,
                                  const std::string& where) {
  expect_derivatives<12>(
      [&](const Vector12& y, Vector12* g, Matrix12* H) {
        return edge_edge_distance(vertex(y, 0), vertex(y, 1), vertex(y, 2), vertex(y, 3), type, g,
                                  H);
      },
      x, 1.0, where);
}

/// The same configuration turned by a random rotation and moved, so that no test relies on
/// axis-aligned coordinates.
Vector12 moved(const Vector12& x, std::mt19937& rng) {
  const Eigen::Matrix3d R = random_rotation(rng);
  const Vector3d c(0.3, -0.7, 1.1);
  Vector12 y;
  for (int i = 0; i < 4; ++i) y.segment<3>(3 * i) = R * vertex(x, i) + c;
  return y;
}

}  // namespace

TEST(ContactDistance, PointPointValueAndDerivatives) {
  const Vector3d p(0.1, 0.2, 0.3), q(-0.4, 0.6, 1.3);
  EXPECT_DOUBLE_EQ(point_point_distance(p, q), (p - q).squaredNorm());
  expect_derivatives<6>(
      [](const Vector6& y, Vector6* g, Matrix6* H) {
        return point_point_distance(y.head<3>(), y.tail<3>(), g, H);
      },
      stack2(p, q), 1.0, "point–point");
}

TEST(ContactDistance, PointLineValueAndDerivatives) {
  // p at height 0.5 above the x axis, its foot outside the edge: the line's distance, not the
  // segment's.
  const Vector3d p(2.0, 0.3, 0.4), e0(0, 0, 0), e1(1, 0, 0);
  EXPECT_NEAR(point_line_distance(p, e0, e1), 0.25, 1e-15);
  std::mt19937 rng(1);
  const auto f = [](const Vector9& y, Vector9* g, Matrix9* H) {
    return point_line_distance(y.segment<3>(0), y.segment<3>(3), y.segment<3>(6), g, H);
  };
  expect_derivatives<9>(f, stack(p, e0, e1), 1.0, "point–line");
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 20; ++k) {
    Vector9 x;
    for (int i = 0; i < 9; ++i) x[i] = u(rng);
    expect_derivatives<9>(f, x, 1.0, "point–line random " + std::to_string(k));
  }
  // The point on the line (d = 0, ∇d = 0): the Hessian alone carries the distance.
  expect_derivatives<9>(f, stack(Vector3d(0.3, 0, 0), e0, e1), 1.0, "point on the line");
  EXPECT_THROW(point_line_distance(p, e0, e0), std::domain_error);
}

TEST(ContactDistance, PointPlaneValueAndDerivatives) {
  const Vector3d t0(0, 0, 0), t1(1, 0, 0), t2(0, 1, 0);
  EXPECT_NEAR(point_plane_distance(Vector3d(5.0, -3.0, 0.7), t0, t1, t2), 0.49, 1e-15);
  const auto f = [](const Vector12& y, Vector12* g, Matrix12* H) {
    return point_plane_distance(vertex(y, 0), vertex(y, 1), vertex(y, 2), vertex(y, 3), g, H);
  };
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 20; ++k) {
    Vector12 x;
    for (int i = 0; i < 12; ++i) x[i] = u(rng);
    expect_derivatives<12>(f, x, 1.0, "point–plane random " + std::to_string(k));
  }
  expect_derivatives<12>(f, moved(stack(Vector3d(0.2, 0.3, 0.0), t0, t1, t2), rng), 1.0,
                         "point in the plane");
  EXPECT_THROW(point_plane_distance(Vector3d(0, 0, 1), t0, t1, Vector3d(2, 0, 0)),
               std::domain_error);
}

TEST(ContactDistance, LineLineValueAndDerivatives) {
  const Vector3d a0(0, 0, 0), a1(1, 0, 0);
  // Skew lines 0.6 apart whose closest points lie outside both edges.
  EXPECT_NEAR(line_line_distance(a0, a1, Vector3d(3, 2, 0.6), Vector3d(3, 5, 0.6)), 0.36, 1e-15);
  const auto f = [](const Vector12& y, Vector12* g, Matrix12* H) {
    return line_line_distance(vertex(y, 0), vertex(y, 1), vertex(y, 2), vertex(y, 3), g, H);
  };
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 20; ++k) {
    Vector12 x;
    for (int i = 0; i < 12; ++i) x[i] = u(rng);
    expect_derivatives<12>(f, x, 1.0, "line–line random " + std::to_string(k));
  }
  // Edges crossing at a point (d = 0, ∇d = 0).
  expect_derivatives<12>(f,
                         moved(stack(a0, a1, Vector3d(0.5, -0.5, 0), Vector3d(0.5, 0.5, 0)), rng),
                         1.0, "crossing edges");
  // Nearly parallel lines (sin θ = 10⁻²): the Hessian grows like 1/sin²θ, still exact.
  expect_derivatives<12>(
      f, moved(stack(a0, a1, Vector3d(0.2, 0.3, 0.1), Vector3d(1.2, 0.3, 0.11)), rng), 1.0,
      "nearly parallel lines");
  EXPECT_THROW(line_line_distance(a0, a1, Vector3d(0, 1, 0), Vector3d(2, 1, 0)), std::domain_error);
}

TEST(ContactDistance, PointEdgeTypesAndDerivatives) {
  const Vector3d e0(0, 0, 0), e1(1, 0, 0);
  struct Case {
    Vector3d p;
    PointEdgeDistanceType type;
    double d;
  };
  const Case cases[] = {{Vector3d(-0.3, 0.4, 0), PointEdgeDistanceType::P_E0, 0.25},
                        {Vector3d(1.3, 0, 0.4), PointEdgeDistanceType::P_E1, 0.25},
                        {Vector3d(0.6, 0.3, 0.4), PointEdgeDistanceType::P_E, 0.25}};
  for (const Case& c : cases) {
    const std::string where = "point–edge type " + std::to_string(static_cast<int>(c.type));
    EXPECT_EQ(point_edge_distance_type(c.p, e0, e1), c.type) << where;
    EXPECT_NEAR(point_edge_distance(c.p, e0, e1), c.d, 1e-15) << where;
    expect_derivatives<9>(
        [&](const Vector9& y, Vector9* g, Matrix9* H) {
          return point_edge_distance(y.segment<3>(0), y.segment<3>(3), y.segment<3>(6), c.type, g,
                                     H);
        },
        stack(c.p, e0, e1), 1.0, where);
  }
  // A zero-length edge is a point.
  EXPECT_EQ(point_edge_distance_type(Vector3d(0.5, 0.5, 0), e0, e0), PointEdgeDistanceType::P_E0);
  EXPECT_NEAR(point_edge_distance(Vector3d(0.5, 0.5, 0), e0, e0), 0.5, 1e-15);
}

TEST(ContactDistance, PointTriangleEveryTypeDerivatives) {
  using T = PointTriangleDistanceType;
  const Vector3d t0(0, 0, 0), t1(1, 0, 0), t2(0, 1, 0);
  struct Case {
    Vector3d p;
    T type;
  };
  const Case cases[] = {{Vector3d(-0.5, -0.4, 0.3), T::P_T0},
                        {Vector3d(1.6, -0.2, 0.3), T::P_T1},
                        {Vector3d(-0.2, 1.5, -0.3), T::P_T2},
                        {Vector3d(0.5, -0.6, 0.2), T::P_E0},
                        {Vector3d(0.8, 0.8, 0.1), T::P_E1},
                        {Vector3d(-0.7, 0.4, -0.2), T::P_E2},
                        {Vector3d(0.2, 0.3, 0.5), T::P_T},
                        // degenerate: in the plane, inside the triangle (d = 0) and outside it
                        {Vector3d(0.2, 0.3, 0.0), T::P_T},
                        {Vector3d(0.5, -0.6, 0.0), T::P_E0}};
  std::mt19937 rng(4);
  for (const Case& c : cases) {
    const Vector12 x = moved(stack(c.p, t0, t1, t2), rng);
    const std::string where = "point–triangle type " + std::to_string(static_cast<int>(c.type)) +
                              " p = " + std::to_string(c.p.x()) + "," + std::to_string(c.p.y()) +
                              "," + std::to_string(c.p.z());
    EXPECT_EQ(point_triangle_distance_type(vertex(x, 0), vertex(x, 1), vertex(x, 2), vertex(x, 3)),
              c.type)
        << where;
    expect_point_triangle_derivatives(x, c.type, where);
  }
}

TEST(ContactDistance, EdgeEdgeEveryTypeDerivatives) {
  using T = EdgeEdgeDistanceType;
  const Vector3d a0(0, 0, 0), a1(1, 0, 0);
  // One configuration per family; the others by swapping endpoints or edges (ea0 ↔ ea1,
  // eb0 ↔ eb1, a ↔ b), which permute the types.
  const Vector12 pp = stack(a0, a1, Vector3d(-0.5, -0.3, 0.2), Vector3d(-1.0, -1.0, 0.5));
  const Vector12 pe = stack(a0, a1, Vector3d(0.5, 0.0, 0.4), Vector3d(0.5, 0.5, 1.4));
  const auto swap_a = [](Vector12 x) {
    x.head<6>() = stack2(vertex(x, 1), vertex(x, 0));
    return x;
  };
  const auto swap_b = [](Vector12 x) {
    x.tail<6>() = stack2(vertex(x, 3), vertex(x, 2));
    return x;
  };
  const auto swap_ab = [](Vector12 x) {
    Vector12 y;
    y << x.tail<6>(), x.head<6>();
    return y;
  };
  struct Case {
    Vector12 x;
    T type;
    const char* what;
  };
  const Case cases[] = {
      {pp, T::EA0_EB0, "EA0_EB0"},
      {swap_b(pp), T::EA0_EB1, "EA0_EB1"},
      {swap_a(pp), T::EA1_EB0, "EA1_EB0"},
      {swap_a(swap_b(pp)), T::EA1_EB1, "EA1_EB1"},
      {pe, T::EA_EB0, "EA_EB0"},
      {swap_b(pe), T::EA_EB1, "EA_EB1"},
      {swap_ab(pe), T::EA0_EB, "EA0_EB"},
      {swap_a(swap_ab(pe)), T::EA1_EB, "EA1_EB"},
      {stack(a0, a1, Vector3d(0.5, -0.5, 0.3), Vector3d(0.4, 0.5, 0.3)), T::EA_EB, "EA_EB"},
      {stack(a0, a1, Vector3d(0.5, -0.5, 0.0), Vector3d(0.5, 0.5, 0.0)), T::EA_EB,
       "crossing at a point"},
      // Parallel and overlapping: the endpoint ea1 against b's interior.
      {stack(a0, a1, Vector3d(0.3, 0.5, 0.0), Vector3d(1.5, 0.5, 0.0)), T::EA1_EB,
       "parallel, overlapping"},
      {stack(a0, a1, Vector3d(1.5, 0.5, 0.0), Vector3d(2.5, 0.5, 0.0)), T::EA1_EB0,
       "parallel, apart"},
      // Nearly parallel (sin²θ = 10⁻¹⁴, below the threshold): a point–edge type, eb0 (in a's
      // plane) against a's interior.
      {stack(a0, a1, Vector3d(0.3, 0.5, 0.0), Vector3d(1.5, 0.5, 1.2e-7)), T::EA_EB0,
       "nearly parallel"},
      // A zero-length edge b: a point against a's interior.
      {stack(a0, a1, Vector3d(0.5, 0.2, 0.3), Vector3d(0.5, 0.2, 0.3)), T::EA_EB0,
       "zero-length edge"}};
  std::mt19937 rng(5);
  for (const Case& c : cases) {
    const Vector12 x = moved(c.x, rng);
    EXPECT_EQ(edge_edge_distance_type(vertex(x, 0), vertex(x, 1), vertex(x, 2), vertex(x, 3)),
              c.type)
        << c.what;
    expect_edge_edge_derivatives(x, c.type, c.what);
  }
}

TEST(ContactDistance, RandomStatesDerivativesOfTheClassifiedType) {
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int k = 0; k < 100; ++k) {
    Vector12 x;
    for (int i = 0; i < 12; ++i) x[i] = u(rng);
    const auto pt =
        point_triangle_distance_type(vertex(x, 0), vertex(x, 1), vertex(x, 2), vertex(x, 3));
    expect_point_triangle_derivatives(x, pt, "random point–triangle " + std::to_string(k));
    const auto ee = edge_edge_distance_type(vertex(x, 0), vertex(x, 1), vertex(x, 2), vertex(x, 3));
    expect_edge_edge_derivatives(x, ee, "random edge–edge " + std::to_string(k));
  }
}
