// The edge–edge mollifier: ε_x from the rest lengths, m in both regimes (c < ε_x and c ≥ ε_x)
// with its gradient and Hessian against central differences, m(0) = 0, and continuity of m
// and ∇m at c = ε_x.
#include "mlshell/contact/distance/edge_edge_mollifier.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "contact_fixtures.hpp"

using namespace mlshell;
using Eigen::Vector3d;
using mlshell::test::expect_derivatives;
using mlshell::test::stack;
using mlshell::test::vertex;

namespace {

/// Edge a along x of length 1, edge b of length 2 at angle θ to it in a parallel plane:
/// c = |u × v|² = (2 sin θ)².
Vector12 edges_at(double theta) {
  return stack(Vector3d(0, 0, 0), Vector3d(1, 0, 0), Vector3d(0.2, -0.3, 0.5),
               Vector3d(0.2 + 2 * std::cos(theta), -0.3 + 2 * std::sin(theta), 0.5));
}

double mollifier(const Vector12& y, double eps_x, Vector12* g, Matrix12* H) {
  return edge_edge_mollifier(vertex(y, 0), vertex(y, 1), vertex(y, 2), vertex(y, 3), eps_x, g, H);
}

}  // namespace

TEST(ContactMollifier, ThresholdFromRestLengths) {
  EXPECT_DOUBLE_EQ(edge_edge_mollifier_threshold(Vector3d(0, 0, 0), Vector3d(2, 0, 0),
                                                 Vector3d(1, 1, 1), Vector3d(1, 1, 4)),
                   1e-3 * 4 * 9);
}

TEST(ContactMollifier, CrossNormDerivatives) {
  expect_derivatives<12>(
      [](const Vector12& y, Vector12* g, Matrix12* H) {
        return edge_edge_cross_squared_norm(vertex(y, 0), vertex(y, 1), vertex(y, 2), vertex(y, 3),
                                            g, H);
      },
      edges_at(0.7), 1.0, "c = |u × v|²");
}

TEST(ContactMollifier, DerivativesInBothRegimes) {
  const double eps_x = edge_edge_mollifier_threshold(Vector3d(0, 0, 0), Vector3d(1, 0, 0),
                                                     Vector3d(0, 0, 0), Vector3d(2, 0, 0));
  // c = 4 sin²θ against ε_x = 4·10⁻³: active below sin θ ≈ 0.0316.
  for (double theta : {0.001, 0.01, 0.02, 0.03}) {
    const Vector12 x = edges_at(theta);
    ASSERT_TRUE(
        edge_edge_mollifier_active(vertex(x, 0), vertex(x, 1), vertex(x, 2), vertex(x, 3), eps_x));
    const double m = mollifier(x, eps_x, nullptr, nullptr);
    EXPECT_GT(m, 0.0);
    EXPECT_LT(m, 1.0);
    expect_derivatives<12>(
        [&](const Vector12& y, Vector12* g, Matrix12* H) { return mollifier(y, eps_x, g, H); }, x,
        1.0, "active, θ = " + std::to_string(theta));
  }
  for (double theta : {0.04, 0.5, 1.5}) {
    const Vector12 x = edges_at(theta);
    Vector12 g;
    Matrix12 H;
    EXPECT_EQ(mollifier(x, eps_x, &g, &H), 1.0);
    EXPECT_EQ(g.norm(), 0.0);
    EXPECT_EQ(H.norm(), 0.0);
  }
}

TEST(ContactMollifier, VanishesForParallelEdgesAndIsC1AtThreshold) {
  const double eps_x = 4e-3;
  EXPECT_EQ(mollifier(edges_at(0.0), eps_x, nullptr, nullptr), 0.0);
  // Just below c = ε_x: m → 1 and ∇m → 0 linearly in ε_x − c.
  const double theta = std::asin(std::sqrt(eps_x / 4.0)) * (1.0 - 1e-8);
  Vector12 g;
  const double m = mollifier(edges_at(theta), eps_x, &g, nullptr);
  EXPECT_NEAR(m, 1.0, 1e-14);
  Vector12 gc;
  const Vector12 x = edges_at(theta);
  edge_edge_cross_squared_norm(vertex(x, 0), vertex(x, 1), vertex(x, 2), vertex(x, 3), &gc,
                               nullptr);
  EXPECT_LT(g.norm(), 1e-6 * gc.norm() / eps_x);
}
