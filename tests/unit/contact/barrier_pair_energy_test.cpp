// The barrier energy of one pair: κ b_ξ(d(x)) for a point–triangle pair and κ m b_ξ(d(x)) for a
// nearly parallel edge–edge pair, with gradients and Hessians against central differences,
// +∞ (writing nothing) inside the thickness, and the PSD projection of the pair Hessian.
#include "mlshell/contact/barrier/barrier_pair_energy.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <string>

#include "contact_fixtures.hpp"
#include "mlshell/contact/distance/edge_edge.hpp"
#include "mlshell/contact/distance/edge_edge_mollifier.hpp"
#include "mlshell/contact/distance/point_point.hpp"
#include "mlshell/contact/distance/point_triangle.hpp"

using namespace mlshell;
using Eigen::Vector3d;
using mlshell::test::expect_derivatives;
using mlshell::test::stack;
using mlshell::test::vertex;

namespace {

const ContactBarrier kBarrier = ContactBarrier::from(0.1, 0.05);  // active below distance 0.15
constexpr double kKappa = 1e3;

double point_triangle_energy(const Vector12& y, PointTriangleDistanceType type, Vector12* g,
                             Matrix12* H, bool project) {
  Vector12 gd;
  Matrix12 hd;
  const double d = point_triangle_distance(vertex(y, 0), vertex(y, 1), vertex(y, 2), vertex(y, 3),
                                           type, &gd, &hd);
  return barrier_pair_energy<12>(kKappa, kBarrier, d, gd, hd, g, H, project);
}

double edge_edge_energy(const Vector12& y, EdgeEdgeDistanceType type, double eps_x, Vector12* g,
                        Matrix12* H, bool project) {
  Vector12 gd, gm;
  Matrix12 hd, hm;
  const Vector3d a0 = vertex(y, 0), a1 = vertex(y, 1), b0 = vertex(y, 2), b1 = vertex(y, 3);
  const double d = edge_edge_distance(a0, a1, b0, b1, type, &gd, &hd);
  const double m = edge_edge_mollifier(a0, a1, b0, b1, eps_x, &gm, &hm);
  return mollified_barrier_pair_energy(kKappa, kBarrier, d, gd, hd, m, gm, hm, g, H, project);
}

double min_eigenvalue(const Matrix12& H) {
  return Eigen::SelfAdjointEigenSolver<Matrix12>(H).eigenvalues()[0];
}

}  // namespace

TEST(ContactPairEnergy, PointTriangleDerivatives) {
  const Vector3d t0(0, 0, 0), t1(1, 0, 0), t2(0, 1, 0);
  for (const Vector3d& p : {Vector3d(0.2, 0.3, 0.12), Vector3d(0.3, 0.3, 0.101),
                            Vector3d(-0.05, -0.06, 0.09), Vector3d(0.5, -0.1, 0.08)}) {
    const Vector12 x = stack(p, t0, t1, t2);
    const auto type = point_triangle_distance_type(p, t0, t1, t2);
    ASSERT_GT(point_triangle_energy(x, type, nullptr, nullptr, false), 0.0);
    expect_derivatives<12>([&](const Vector12& y, Vector12* g,
                               Matrix12* H) { return point_triangle_energy(y, type, g, H, false); },
                           x, 0.01, "point–triangle pair, type " + std::to_string(int(type)));
  }
}

TEST(ContactPairEnergy, MollifiedEdgeEdgeDerivatives) {
  // Edges 0.12 apart at a small angle θ: c = sin²θ < ε_x = 10⁻³, the mollifier is active.
  for (double theta : {0.005, 0.02}) {
    const Vector12 x = stack(Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0.2, -0.02, 0.12),
                             Vector3d(0.2 + std::cos(theta), -0.02 + std::sin(theta), 0.12));
    const double eps_x =
        edge_edge_mollifier_threshold(vertex(x, 0), vertex(x, 1), vertex(x, 2), vertex(x, 3));
    ASSERT_TRUE(
        edge_edge_mollifier_active(vertex(x, 0), vertex(x, 1), vertex(x, 2), vertex(x, 3), eps_x));
    const auto type =
        edge_edge_distance_type(vertex(x, 0), vertex(x, 1), vertex(x, 2), vertex(x, 3));
    ASSERT_GT(edge_edge_energy(x, type, eps_x, nullptr, nullptr, false), 0.0);
    expect_derivatives<12>(
        [&](const Vector12& y, Vector12* g, Matrix12* H) {
          return edge_edge_energy(y, type, eps_x, g, H, false);
        },
        x, 0.01, "mollified edge–edge pair, θ = " + std::to_string(theta));
  }
}

TEST(ContactPairEnergy, InfiniteInsideThicknessWritesNothing) {
  const Vector3d p(0.2, 0.3, 0.099), t0(0, 0, 0), t1(1, 0, 0), t2(0, 1, 0);
  Vector12 g = Vector12::Constant(7.0);
  Matrix12 H = Matrix12::Constant(7.0);
  EXPECT_EQ(
      point_triangle_energy(stack(p, t0, t1, t2), PointTriangleDistanceType::P_T, &g, &H, true),
      std::numeric_limits<double>::infinity());
  EXPECT_EQ(g, Vector12::Constant(7.0));
  EXPECT_EQ(H, Matrix12::Constant(7.0));
}

TEST(ContactPairEnergy, ProjectedHessianIsPositiveSemiDefinite) {
  // b' < 0 times the convex ∇²d makes the exact pair Hessian indefinite (checked below), at
  // the plane, edge and vertex types alike.
  const Vector3d t0(0, 0, 0), t1(1, 0, 0), t2(0, 1, 0);
  for (const Vector3d& p :
       {Vector3d(0.5, -0.05, 0.1), Vector3d(0.2, 0.3, 0.12), Vector3d(-0.06, -0.05, 0.09)}) {
    const Vector12 x = stack(p, t0, t1, t2);
    const auto type = point_triangle_distance_type(p, t0, t1, t2);
    Matrix12 exact, projected;
    Vector12 g;
    point_triangle_energy(x, type, &g, &exact, false);
    point_triangle_energy(x, type, &g, &projected, true);
    EXPECT_LT(min_eigenvalue(exact), 0.0) << "type " << int(type) << ": the test needs an "
                                          << "indefinite exact Hessian";
    EXPECT_GE(min_eigenvalue(projected), -1e-12 * projected.norm()) << "type " << int(type);
    EXPECT_LE((projected - projected.transpose()).norm(), 1e-12 * projected.norm());
  }
  // The 6-dof (point–point) instantiation projects too.
  Vector6 gd;
  Matrix6 hd, H;
  const double d = point_point_distance(Vector3d(0, 0, 0), Vector3d(0.12, 0, 0), &gd, &hd);
  barrier_pair_energy<6>(kKappa, kBarrier, d, gd, hd, nullptr, &H, true);
  EXPECT_GE(Eigen::SelfAdjointEigenSolver<Matrix6>(H).eigenvalues()[0], -1e-12 * H.norm());
}
