// Additive CCD (contact/ccd/additive_ccd.hpp): the hard cases of the IPC Toolkit's CCD tests as
// named tests, and seeded random trajectories, each checked one-sidedly against the sampled
// reference of ccd_fixtures.hpp (a false positive may pass, a false negative never).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "contact/ccd_fixtures.hpp"

namespace mlshell {
namespace {

using test::expect_conservative;
using test::first_contact_time;
using test::MovingStencil;
using test::StencilKind;
using V = Eigen::Vector3d;

const V kZero = V::Zero();

/// The unit right triangle in z = 0 (static) and a point p moving by dp.
MovingStencil point_over_triangle(const V& p, const V& dp) {
  MovingStencil s;
  s.kind = StencilKind::kPointTriangle;
  s.set(0, p, dp);
  s.set(1, V(0, 0, 0), kZero);
  s.set(2, V(1, 0, 0), kZero);
  s.set(3, V(0, 1, 0), kZero);
  return s;
}

/// Edge a from a0 to a1 (static) and edge b from b0 to b1 moving by db.
MovingStencil edges(const V& a0, const V& a1, const V& b0, const V& b1, const V& db) {
  MovingStencil s;
  s.kind = StencilKind::kEdgeEdge;
  s.set(0, a0, kZero);
  s.set(1, a1, kZero);
  s.set(2, b0, db);
  s.set(3, b1, db);
  return s;
}

/// The same stencil with positions and displacements scaled by `scale` (times scale too).
MovingStencil scaled(MovingStencil s, double scale) {
  s.x0 *= scale;
  s.dx *= scale;
  return s;
}

TEST(ContactCcd, ParallelEdgesApproachingCollideAtTheirContactTime) {
  for (const double xi : {0.0, 0.1}) {
    SCOPED_TRACE(xi);
    // Parallel, one above the other, b falls by 2: contact when the gap 1 − 2t reaches ξ.
    const auto fall = edges(V(0, 0, 0), V(1, 0, 0), V(0, 0, 1), V(1, 0, 1), V(0, 0, -2));
    const auto r = fall.ccd(xi, 1.0);
    const double t_star = expect_conservative(fall, xi, 1.0, r);
    EXPECT_NEAR(t_star, 0.5 * (1.0 - xi), 1e-9);
    EXPECT_GE(r.toi, 0.5 * t_star);  // efficiency, loosely
    // Half overlapping and shifted sideways.
    const auto half = edges(V(0, 0, 0), V(1, 0, 0), V(0.5, 0.3, 1), V(1.5, 0.3, 1), V(0, 0, -2));
    expect_conservative(half, xi, 1.0, half.ccd(xi, 1.0));
    // Collinear, end to end: b slides into a's end at t = 0.5 (less ξ).
    const auto collinear = edges(V(0, 0, 0), V(1, 0, 0), V(2, 0, 0), V(3, 0, 0), V(-2, 0, 0));
    EXPECT_TRUE(std::isfinite(expect_conservative(collinear, xi, 1.0, collinear.ccd(xi, 1.0))));
  }
  // Parallel edges sliding along each other at a constant gap 0.2 > ξ = 0.1: no collision.
  const auto slide = edges(V(0, 0, 0), V(1, 0, 0), V(0, 0, 0.2), V(1, 0, 0.2), V(5, 0, 0));
  const auto r = slide.ccd(0.1, 1.0);
  expect_conservative(slide, 0.1, 1.0, r);
  EXPECT_FALSE(r.may_collide);
}

TEST(ContactCcd, VertexOnTrianglePlaneAtStart) {
  // Outside the triangle in its plane, moving towards its hypotenuse (x + y = 1): contact at
  // t* = 0.2.
  const auto in_plane = point_over_triangle(V(0.6, 0.6, 0), V(-0.5, -0.5, 0));
  const auto r = in_plane.ccd(0.0, 1.0);
  EXPECT_NEAR(expect_conservative(in_plane, 0.0, 1.0, r), 0.2, 1e-9);
  EXPECT_GT(r.toi, 0.0);
  // Outside in the plane, leaving it: no collision.
  const auto leaving = point_over_triangle(V(0.6, 0.6, 0), V(0, 0, 1));
  const auto r_leave = leaving.ccd(0.0, 1.0);
  expect_conservative(leaving, 0.0, 1.0, r_leave);
  EXPECT_FALSE(r_leave.may_collide);
  // Inside the triangle at t = 0 (distance 0): a collision at 0, whichever way it moves.
  for (const V& dp : {V(0, 0, 1), V(0, 0, -1), V(0.1, 0.1, 0), V(0, 0, 0)}) {
    const auto inside = point_over_triangle(V(0.2, 0.2, 0), dp);
    const auto r_in = inside.ccd(0.0, 1.0);
    EXPECT_TRUE(r_in.may_collide);
    EXPECT_EQ(r_in.toi, 0.0);
  }
  // The triangle sweeping through a point on its plane at t = 0, on its edge or just off it by
  // ±float epsilon (the IPC Toolkit's "Zhongshi's case").
  for (const double qy : {-1.2e-7, 0.0, 1.2e-7}) {
    MovingStencil s;
    s.kind = StencilKind::kPointTriangle;
    s.set(0, V(0, qy, 0), kZero);
    s.set(1, V(0, 0, 0), V(0, 0, 1));
    s.set(2, V(0, 1, 0), V(0, 0, 1));
    s.set(3, V(1, 0, 0), V(0, 0, 1));
    expect_conservative(s, 0.0, 1.0, s.ccd(0.0, 1.0));
  }
}

TEST(ContactCcd, ZeroTimeOfImpactWhenTouchingOrWithinThicknessAtStart) {
  const double xi = 1e-3;
  // Touching (distance 0) and within ξ (distance ξ/2), for all four stencils, moving apart.
  for (const double gap : {0.0, 0.5 * xi}) {
    SCOPED_TRACE(gap);
    MovingStencil pp;
    pp.kind = StencilKind::kPointPoint;
    pp.set(0, V(0, 0, gap), V(0, 0, 1));
    pp.set(1, V(0, 0, 0), kZero);
    MovingStencil pe;
    pe.kind = StencilKind::kPointEdge;
    pe.set(0, V(0.5, 0, gap), V(0, 0, 1));
    pe.set(1, V(0, 0, 0), kZero);
    pe.set(2, V(1, 0, 0), kZero);
    const auto pt = point_over_triangle(V(0.2, 0.2, gap), V(0, 0, 1));
    const auto ee = edges(V(0, 0, 0), V(1, 0, 0), V(0.5, -1, gap), V(0.5, 1, gap), V(0, 0, 1));
    for (const auto& s : {pp, pe, pt, ee}) {
      const auto r = s.ccd(xi, 1.0);
      EXPECT_TRUE(r.may_collide);
      EXPECT_EQ(r.toi, 0.0);
      EXPECT_EQ(r.iterations, 0);
    }
  }
  // Just beyond ξ and approaching: toi > 0 but before the contact.
  const auto close = point_over_triangle(V(0.2, 0.2, xi * (1 + 1e-9)), V(0, 0, -1));
  const auto r = close.ccd(xi, 1.0);
  expect_conservative(close, xi, 1.0, r);
  EXPECT_TRUE(r.may_collide);
}

TEST(ContactCcd, NearMissesAndNearHitsWithin1e9) {
  for (const double xi : {0.0, 1e-3}) {
    for (const double delta : {1e-9, -1e-9}) {
      SCOPED_TRACE(testing::Message() << "xi " << xi << " delta " << delta);
      // Head on: the point stops at ξ + δ above the triangle.
      const auto head_on = point_over_triangle(V(0.2, 0.2, 1), V(0, 0, -(1 - xi - delta)));
      const double t1 = expect_conservative(head_on, xi, 1.0, head_on.ccd(xi, 1.0));
      EXPECT_EQ(std::isfinite(t1), delta < 0);
      // Passing the triangle's edge x = 0 on the outside (δ > 0) or just inside it (δ < 0).
      const auto past_edge = point_over_triangle(V(-xi - delta, 0.5, 1), V(0, 0, -2));
      const double t2 = expect_conservative(past_edge, xi, 1.0, past_edge.ccd(xi, 1.0));
      EXPECT_EQ(std::isfinite(t2), delta < 0);
      // Crossing edges, b passing a at ξ + δ.
      const auto cross =
          edges(V(0, 0, 0), V(1, 0, 0), V(0.5, -1, 1), V(0.5, 1, 1), V(0, 0, -(1 - xi - delta)));
      const double t3 = expect_conservative(cross, xi, 1.0, cross.ccd(xi, 1.0));
      EXPECT_EQ(std::isfinite(t3), delta < 0);
    }
  }
}

TEST(ContactCcd, VeryLargeAndVerySmallDisplacements) {
  const auto head_on = point_over_triangle(V(0.2, 0.2, 1), V(0.1, 0.1, -2));
  const auto cross = edges(V(0, 0, 0), V(1, 0, 0), V(0.5, -1, 1), V(0.5, 1, 1), V(0.2, 0, -2));
  for (const double scale : {1e3, 1e-8}) {
    SCOPED_TRACE(scale);
    for (const auto& s : {scaled(head_on, scale), scaled(cross, scale)}) {
      const double xi = 1e-3 * scale;
      const auto r = s.ccd(xi, 1.0);
      const double t_star = expect_conservative(s, xi, 1.0, r);
      ASSERT_TRUE(std::isfinite(t_star));
      EXPECT_GE(r.toi, 0.5 * t_star);  // scale-free: the same toi as at scale 1
    }
  }
  // A common translation of 10³ with a small relative motion: the mean displacement is
  // removed, so l_p sees only the relative motion and few steps are needed.
  auto carried = point_over_triangle(V(0.2, 0.2, 1), V(0, 0, -2));
  for (int i = 0; i < 4; ++i) carried.dx.segment<3>(3 * i) += V(1e3, -1e3, 5e2);
  const auto r = carried.ccd(0.0, 1.0);
  const double t_star = expect_conservative(carried, 0.0, 1.0, r);
  EXPECT_NEAR(t_star, 0.5, 1e-9);
  EXPECT_GE(r.toi, 0.25);
  EXPECT_LT(r.iterations, 200);
  // A step of 10³ that ends far away on the other side (tunnelling): caught.
  const auto tunnel = point_over_triangle(V(0.2, 0.2, 1), V(0, 0, -1e3));
  const auto r_tunnel = tunnel.ccd(0.0, 1.0);
  expect_conservative(tunnel, 0.0, 1.0, r_tunnel);
  EXPECT_TRUE(r_tunnel.may_collide);
}

/// A point at height d₀ over the triangle gliding 0.8 along it while sinking 2 d₀: it reaches
/// the plane at t* = 0.5 inside the triangle. Each step is ≈ η·gap/l_p, so the count grows as
/// 1/d₀, and below d₀ ≈ 10⁻⁶ the cap stops the loop.
MovingStencil adversarial_glide(double d0) {
  return point_over_triangle(V(0.05, 0.05, d0), V(0.8, 0, -2 * d0));
}

/// l_p of the point–triangle stencil: |Δp| + max|Δt_k| after removing the mean displacement.
double point_triangle_lp(const MovingStencil& s) {
  V mean = kZero;
  for (int i = 0; i < 4; ++i) mean += s.dx.segment<3>(3 * i);
  mean /= 4;
  double tri = 0.0;
  for (int i = 1; i < 4; ++i) tri = std::max(tri, (s.dx.segment<3>(3 * i) - mean).norm());
  return (s.dx.head<3>() - mean).norm() + tri;
}

TEST(ContactCcd, AdversarialSmallInitialDistances) {
  const AdditiveCcdOptions options;
  for (const double d0 : {1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8}) {
    SCOPED_TRACE(d0);
    const auto s = adversarial_glide(d0);
    const auto r = s.ccd(0.0, 1.0, options);
    const double t_star = expect_conservative(s, 0.0, 1.0, r);
    EXPECT_NEAR(t_star, 0.5, 1e-6);
    EXPECT_TRUE(r.may_collide);
    EXPECT_GT(r.toi, 0.0);
    if (r.capped) {
      // The safe answer at the cap is at least N η (1 − η) g(d₀) / l_p.
      const double eta = options.conservative_rescaling;
      EXPECT_GE(r.toi, options.max_iterations * eta * (1 - eta) * d0 / point_triangle_lp(s));
      EXPECT_EQ(r.iterations, options.max_iterations);
    } else {
      EXPECT_GE(r.toi, 0.25);
    }
  }
  EXPECT_FALSE(adversarial_glide(1e-3).ccd(0.0, 1.0, options).capped);
  EXPECT_TRUE(adversarial_glide(1e-8).ccd(0.0, 1.0, options).capped);
}

TEST(ContactCcd, CapReturnsTheLargestTimeProvenSafe) {
  const auto s = adversarial_glide(1e-3);
  AdditiveCcdOptions options;
  double previous = 0.0;
  for (const long cap : {1L, 2L, 10L, 100L}) {
    options.max_iterations = cap;
    const auto r = s.ccd(0.0, 1.0, options);
    expect_conservative(s, 0.0, 1.0, r);
    EXPECT_TRUE(r.capped);
    EXPECT_TRUE(r.may_collide);
    EXPECT_GT(r.toi, previous);  // more iterations prove more
    previous = r.toi;
  }
}

TEST(ContactCcd, DegeneratingEdgesAndTriangles) {
  // Edge a shrinks to the point (0, 0, 0) at t = 1 while b falls onto it at x = 0.25.
  MovingStencil shrink;
  shrink.kind = StencilKind::kEdgeEdge;
  shrink.set(0, V(0, 0, 0), kZero);
  shrink.set(1, V(1, 0, 0), V(-1, 0, 0));
  shrink.set(2, V(0.25, -1, 1), V(0, 0, -2));
  shrink.set(3, V(0.25, 1, 1), V(0, 0, -2));
  EXPECT_NEAR(expect_conservative(shrink, 0.0, 1.0, shrink.ccd(0.0, 1.0)), 0.5, 1e-9);
  // Edge a of zero length throughout (a point) hit by b.
  auto point_edge = shrink;
  point_edge.set(1, V(0, 0, 0), kZero);
  point_edge.set(2, V(0, -1, 1), V(0, 0, -2));
  point_edge.set(3, V(0, 1, 1), V(0, 0, -2));
  EXPECT_NEAR(expect_conservative(point_edge, 0.0, 1.0, point_edge.ccd(0.0, 1.0)), 0.5, 1e-9);
  // Both edges collapse as they meet.
  auto both = shrink;
  both.set(3, V(0.25, 1, 1), V(0, -1, -2));
  expect_conservative(both, 0.0, 1.0, both.ccd(0.0, 1.0));
  // A triangle flattening into a segment (t2 onto the segment t0t1) as a point falls on it.
  MovingStencil flat;
  flat.kind = StencilKind::kPointTriangle;
  flat.set(0, V(0.3, 0.05, 1), V(0, 0, -2));
  flat.set(1, V(0, 0, 0), kZero);
  flat.set(2, V(1, 0, 0), kZero);
  flat.set(3, V(0, 1, 0), V(0.5, -1, 0));
  expect_conservative(flat, 0.0, 1.0, flat.ccd(0.0, 1.0));
  // A triangle that is a segment from the start.
  auto segment = flat;
  segment.set(3, V(0.5, 0, 0), kZero);
  segment.set(0, V(0.3, 0, 1), V(0, 0, -2));
  EXPECT_NEAR(expect_conservative(segment, 0.0, 1.0, segment.ccd(0.0, 1.0)), 0.5, 1e-9);
}

TEST(ContactCcd, RepeatedCcdFromTheTimeOfImpact) {
  const auto head_on = point_over_triangle(V(0.2, 0.2, 1), V(0.1, 0.1, -2));
  const auto cross = edges(V(0, 0, 0), V(1, 0, 0), V(0.5, -1, 1), V(0.5, 1, 1), V(0.2, 0, -2));
  for (const double xi : {0.0, 1e-3}) {
    for (const auto& s : {head_on, cross, adversarial_glide(1e-2)}) {
      const double t_star = first_contact_time(s, xi, 1.0);
      ASSERT_TRUE(std::isfinite(t_star));
      // CCD from the configuration at the previous toi over the rest of the step: never a
      // collision at 0, and the times add up to no more than t*.
      double t = 0.0;
      for (int repeat = 0; repeat < 6; ++repeat) {
        const auto from = s.at(t);
        const auto r = from.ccd(xi, 1.0 - t);
        expect_conservative(from, xi, 1.0 - t, r);
        EXPECT_TRUE(r.may_collide);
        EXPECT_GT(r.toi, 0.0) << "repeat " << repeat << " from t = " << t;
        t += r.toi;
        EXPECT_LE(t, t_star);
      }
    }
  }
  // A collision at 0 stays one.
  const auto inside = point_over_triangle(V(0.2, 0.2, 0), V(0, 0, -1));
  const auto r = inside.ccd(0.0, 1.0);
  EXPECT_EQ(r.toi, 0.0);
  EXPECT_EQ(inside.at(r.toi).ccd(0.0, 1.0).toi, 0.0);
}

TEST(ContactCcd, RandomTrajectoriesHaveNoFalseNegatives) {
  std::mt19937 rng(20210801);
  std::uniform_real_distribution<double> unit(0.0, 1.0), sym(-1.0, 1.0);
  const auto random_v = [&](auto& dist) { return V(dist(rng), dist(rng), dist(rng)); };
  int colliding = 0, reported = 0, total = 0;
  for (const auto kind : {StencilKind::kPointPoint, StencilKind::kPointEdge,
                          StencilKind::kPointTriangle, StencilKind::kEdgeEdge}) {
    for (int trial = 0; trial < 750; ++trial) {
      MovingStencil s;
      s.kind = kind;
      for (int i = 0; i < s.num_vertices(); ++i) s.set(i, random_v(unit), random_v(sym));
      const double xi = trial % 3 == 0 ? 0.0 : trial % 3 == 1 ? 1e-3 : 0.05;
      SCOPED_TRACE(testing::Message() << "kind " << int(kind) << " trial " << trial);
      const auto r = s.ccd(xi, 1.0);
      colliding += std::isfinite(expect_conservative(s, xi, 1.0, r));
      reported += r.may_collide;
      ++total;
    }
  }
  // The sample has teeth: many trajectories do collide, and most misses are reported as such.
  EXPECT_GT(colliding, total / 20);
  EXPECT_LT(reported, total);
}

TEST(ContactCcd, RejectsInvalidInput) {
  const auto s = point_over_triangle(V(0.2, 0.2, 1), V(0, 0, -2));
  AdditiveCcdOptions bad;
  bad.conservative_rescaling = 1.0;
  EXPECT_THROW(s.ccd(0.0, 1.0, bad), std::invalid_argument);
  bad = {};
  bad.max_iterations = 0;
  EXPECT_THROW(s.ccd(0.0, 1.0, bad), std::invalid_argument);
  EXPECT_THROW(s.ccd(-1.0, 1.0), std::invalid_argument);
  EXPECT_THROW(s.ccd(0.0, std::numeric_limits<double>::infinity()), std::invalid_argument);
  auto nan = s;
  nan.dx[2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(nan.ccd(0.0, 1.0), std::invalid_argument);
  auto overflow = s;
  overflow.dx[2] = 1e308;
  EXPECT_THROW(overflow.ccd(0.0, 10.0), std::invalid_argument);
}

}  // namespace
}  // namespace mlshell
