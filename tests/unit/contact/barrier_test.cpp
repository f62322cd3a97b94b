// The clamped log barrier and its thickness offset: zero at and beyond the activation
// distance, positive and decreasing below it, +∞ at and below contact, C² at d̂; b' and b''
// against central differences; the offset form's activation at (ξ + ĝ)² and blow-up at ξ².
#include "mlshell/contact/barrier/barrier.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

using namespace mlshell;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// b' and b'' of a scalar function against central differences at d (step 10⁻⁶ d), relative
/// to the size of each term.
template <class F, class DF, class D2F>
void expect_scalar_derivatives(F f, DF df, D2F d2f, double d, const std::string& where) {
  const double h = 1e-6 * d;
  const double fd1 = (f(d + h) - f(d - h)) / (2 * h), fd2 = (df(d + h) - df(d - h)) / (2 * h);
  EXPECT_NEAR(df(d), fd1, 1e-6 * (std::abs(df(d)) + std::abs(d2f(d)) * d)) << where;
  EXPECT_NEAR(d2f(d), fd2, 1e-6 * std::abs(d2f(d)) + 1e-12 * std::abs(df(d)) / d) << where;
}

}  // namespace

TEST(ContactBarrier, ZeroAtAndBeyondActivation) {
  const double dhat = 1e-4;
  for (double d : {dhat, 1.5 * dhat, 1e3 * dhat}) {
    EXPECT_EQ(barrier(d, dhat), 0.0);
    EXPECT_EQ(barrier_first_derivative(d, dhat), 0.0);
    EXPECT_EQ(barrier_second_derivative(d, dhat), 0.0);
  }
}

TEST(ContactBarrier, PositiveDecreasingConvexBelowActivation) {
  const double dhat = 2.5e-3;
  double previous = 0.0;
  for (double r = 0.999; r > 1e-9; r *= 0.5) {
    const double d = r * dhat;
    EXPECT_GT(barrier(d, dhat), previous) << d;
    EXPECT_LT(barrier_first_derivative(d, dhat), 0.0) << d;
    EXPECT_GT(barrier_second_derivative(d, dhat), 0.0) << d;
    previous = barrier(d, dhat);
  }
  // → +∞ as d → 0⁺, and +∞ (with its infinite slopes) at and below contact.
  EXPECT_GT(barrier(1e-300, dhat), 1e-4 * dhat * dhat);
  for (double d : {0.0, -1e-12, -1.0}) {
    EXPECT_EQ(barrier(d, dhat), kInf);
    EXPECT_EQ(barrier_first_derivative(d, dhat), -kInf);
    EXPECT_EQ(barrier_second_derivative(d, dhat), kInf);
  }
}

TEST(ContactBarrier, DerivativesMatchDifferences) {
  const double dhat = 1e-2;
  for (double r : {1e-4, 1e-2, 0.1, 0.5, 0.9, 0.999}) {
    expect_scalar_derivatives([&](double d) { return barrier(d, dhat); },
                              [&](double d) { return barrier_first_derivative(d, dhat); },
                              [&](double d) { return barrier_second_derivative(d, dhat); },
                              r * dhat, "d/d̂ = " + std::to_string(r));
  }
}

TEST(ContactBarrier, TwiceContinuousAtActivation) {
  // b ~ (d̂ − d)³/d̂, b' ~ −(d̂ − d)²·(3/d̂)… all three vanish as d → d̂⁻.
  const double dhat = 3e-3;
  for (double delta : {1e-3, 1e-5, 1e-7}) {
    const double d = dhat * (1.0 - delta);
    EXPECT_LT(barrier(d, dhat), 2.0 * std::pow(delta, 3) * dhat * dhat);
    EXPECT_LT(-barrier_first_derivative(d, dhat), 4.0 * delta * delta * dhat);
    EXPECT_LT(barrier_second_derivative(d, dhat), 7.0 * delta);
  }
}

TEST(ContactBarrier, ThicknessOffsetActivatesAtThicknessPlusGap) {
  const ContactBarrier b = ContactBarrier::from(0.01, 0.002);
  EXPECT_DOUBLE_EQ(b.activation_squared_distance(), 0.012 * 0.012);
  const double on = 0.012 * 0.012;
  EXPECT_EQ(b.value(on), 0.0);
  EXPECT_EQ(b.value(1.0001 * on), 0.0);
  EXPECT_GT(b.value(0.9999 * on), 0.0);
  // +∞ where the distance reaches the thickness.
  EXPECT_EQ(b.value(0.01 * 0.01), kInf);
  EXPECT_EQ(b.value(0.5 * 0.01 * 0.01), kInf);
  EXPECT_GT(b.value(0.01 * 0.01 * (1 + 1e-12)), b.value(0.0105 * 0.0105));
  // b_ξ(d) = b(d − ξ², 2ξĝ + ĝ²): at distance ξ + g/2 against the plain barrier's formula.
  const double d = 0.011 * 0.011;
  EXPECT_DOUBLE_EQ(b.value(d), barrier(d - 1e-4, 0.012 * 0.012 - 1e-4));
  for (double s : {0.01001, 0.0105, 0.0119}) {
    expect_scalar_derivatives([&](double x) { return b.value(x); },
                              [&](double x) { return b.first_derivative(x); },
                              [&](double x) { return b.second_derivative(x); }, s * s,
                              "offset barrier at distance " + std::to_string(s));
  }
  // Without thickness it is the plain barrier with d̂ = ĝ².
  const ContactBarrier plain = ContactBarrier::from(0.0, 0.002);
  EXPECT_EQ(plain.value(1e-6), barrier(1e-6, 4e-6));
}

TEST(ContactBarrier, RejectsBadParameters) {
  EXPECT_THROW(ContactBarrier::from(-1e-3, 1e-3), std::invalid_argument);
  EXPECT_THROW(ContactBarrier::from(1e-3, 0.0), std::invalid_argument);
  EXPECT_THROW(ContactBarrier::from(1e-3, std::nan("")), std::invalid_argument);
  EXPECT_NO_THROW(ContactBarrier::from(0.0, 1e-3));
}
