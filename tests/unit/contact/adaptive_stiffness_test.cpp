// Adaptive barrier stiffness: κ_min from the barrier's curvature at d₀ = (ξ + 10⁻⁸ L)² and the
// average mass, κ_max = 100 κ_min, the initial κ balancing the gradients and clamped to
// [κ_min, κ_max], the probe's fallback for a gap below 10⁻⁸ L, and the doubling rule.
#include "mlshell/contact/barrier/adaptive_stiffness.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

using namespace mlshell;

TEST(ContactAdaptiveStiffness, MinimumFromCurvatureAndMass) {
  const ContactBarrier b = ContactBarrier::from(0.0, 1e-3);
  const double d0 = 1e-16;  // (10⁻⁸ · 1)²
  const double expected = 1e11 * 0.5 / (4.0 * d0 * barrier_second_derivative(d0, 1e-6));
  EXPECT_DOUBLE_EQ(min_barrier_stiffness(b, 1.0, 0.5), expected);
  // With a thickness the probe sits 10⁻⁸ L beyond it, on the offset barrier.
  const ContactBarrier thick = ContactBarrier::from(0.01, 1e-3);
  const double d1 = (0.01 + 1e-8) * (0.01 + 1e-8);
  EXPECT_DOUBLE_EQ(min_barrier_stiffness(thick, 1.0, 0.5),
                   1e11 * 0.5 / (4.0 * d1 * thick.second_derivative(d1)));
  // A gap below 10⁻⁸ L: the probe moves to half the gap.
  const ContactBarrier tiny = ContactBarrier::from(0.0, 1e-3);
  const double d2 = 0.25e-6;
  EXPECT_DOUBLE_EQ(min_barrier_stiffness(tiny, 1e6, 2.0),
                   1e11 * 2.0 / (4.0 * d2 * barrier_second_derivative(d2, 1e-6)));
  EXPECT_THROW(min_barrier_stiffness(b, 0.0, 1.0), std::invalid_argument);
  EXPECT_THROW(min_barrier_stiffness(b, 1.0, -1.0), std::invalid_argument);
}

TEST(ContactAdaptiveStiffness, InitialBalancesGradientsWithinBounds) {
  const ContactBarrier b = ContactBarrier::from(0.0, 1e-3);
  const double kmin = min_barrier_stiffness(b, 1.0, 0.5);
  double kmax = 0.0;
  // No barrier gradient: κ = 1, clamped up to κ_min.
  Eigen::VectorXd ge(3), gb = Eigen::VectorXd::Zero(3);
  ge << 1.0, -2.0, 0.5;
  EXPECT_EQ(initial_barrier_stiffness(b, 1.0, 0.5, ge, gb, &kmax), kmin);
  EXPECT_DOUBLE_EQ(kmax, 100.0 * kmin);
  // g_e = −κ* g_b: κ* itself where it lies in [κ_min, κ_max].
  gb << 0.3, 0.1, -0.2;
  for (double k : {3.0 * kmin, 50.0 * kmin}) {
    const Eigen::VectorXd balanced = -k * gb;
    EXPECT_NEAR(initial_barrier_stiffness(b, 1.0, 0.5, balanced, gb, &kmax), k, 1e-12 * k);
  }
  EXPECT_EQ(initial_barrier_stiffness(b, 1.0, 0.5, Eigen::VectorXd(-1e3 * kmin * gb), gb, &kmax),
            kmax);
  // Gradients pointing the same way (κ* < 0): κ_min.
  EXPECT_EQ(initial_barrier_stiffness(b, 1.0, 0.5, Eigen::VectorXd(gb), gb, &kmax), kmin);
  EXPECT_THROW(initial_barrier_stiffness(b, 1.0, 0.5, Eigen::VectorXd(2), gb, &kmax),
               std::invalid_argument);
}

TEST(ContactAdaptiveStiffness, DoublesWhileDistanceSmallAndShrinking) {
  const double L = 2.0, near = (1e-9 * L) * (1e-9 * L);
  // Small and shrinking: doubled, up to κ_max.
  EXPECT_EQ(update_barrier_stiffness(0.5 * near, 0.25 * near, 1e6, 10.0, L), 20.0);
  EXPECT_EQ(update_barrier_stiffness(0.5 * near, 0.25 * near, 15.0, 10.0, L), 15.0);
  // Growing, or not small: unchanged.
  EXPECT_EQ(update_barrier_stiffness(0.25 * near, 0.5 * near, 1e6, 10.0, L), 10.0);
  EXPECT_EQ(update_barrier_stiffness(2.0 * near, 0.5 * near, 1e6, 10.0, L), 10.0);
  EXPECT_EQ(update_barrier_stiffness(4.0 * near, 2.0 * near, 1e6, 10.0, L), 10.0);
  // With a thickness ξ the test is on the gap beyond ξ.
  const double xi = 1e-3, reach = (xi + 1e-9 * L) * (xi + 1e-9 * L);
  EXPECT_EQ(update_barrier_stiffness(0.9999999 * reach, xi * xi * 1.0000001, 1e6, 10.0, L, xi),
            20.0);
  EXPECT_EQ(update_barrier_stiffness(1.1 * reach, 1.05 * reach, 1e6, 10.0, L, xi), 10.0);
}
