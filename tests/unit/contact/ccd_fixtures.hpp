// Helpers of the CCD tests: a stencil moving along x₀ + t Δx, its squared distance at t by the
// distance kernels, and a brute-force reference for the first time it comes within ξ (dense
// samples, a golden-section search around every sampled local minimum, then bisection).
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <limits>

#include "mlshell/contact/ccd/additive_ccd.hpp"
#include "mlshell/contact/distance/edge_edge.hpp"
#include "mlshell/contact/distance/point_edge.hpp"
#include "mlshell/contact/distance/point_point.hpp"
#include "mlshell/contact/distance/point_triangle.hpp"

namespace mlshell::test {

enum class StencilKind { kPointPoint, kPointEdge, kPointTriangle, kEdgeEdge };

/// A stencil's vertices at t = 0 and their displacements, stacked in x0/dx's first 3·n entries
/// (n = 2, 3, 4 vertices by kind; the rest is unused).
struct MovingStencil {
  StencilKind kind = StencilKind::kPointTriangle;
  Vector12 x0 = Vector12::Zero();
  Vector12 dx = Vector12::Zero();

  int num_vertices() const {
    return kind == StencilKind::kPointPoint ? 2 : kind == StencilKind::kPointEdge ? 3 : 4;
  }
  Eigen::Vector3d vertex(int i, double t) const {
    return x0.segment<3>(3 * i) + t * dx.segment<3>(3 * i);
  }
  void set(int i, const Eigen::Vector3d& position, const Eigen::Vector3d& displacement) {
    x0.segment<3>(3 * i) = position;
    dx.segment<3>(3 * i) = displacement;
  }
  /// The squared distance at t, by the kernels of distance/.
  double squared_distance(double t) const {
    const auto v = [&](int i) { return vertex(i, t); };
    switch (kind) {
      case StencilKind::kPointPoint:
        return point_point_distance(v(0), v(1));
      case StencilKind::kPointEdge:
        return point_edge_distance(v(0), v(1), v(2));
      case StencilKind::kPointTriangle:
        return point_triangle_distance(v(0), v(1), v(2), v(3));
      case StencilKind::kEdgeEdge:
        return edge_edge_distance(v(0), v(1), v(2), v(3));
    }
    return 0.0;
  }
  /// Additive CCD of the stencil over [0, t_max].
  CcdResult ccd(double thickness, double t_max, const AdditiveCcdOptions& options = {}) const {
    switch (kind) {
      case StencilKind::kPointPoint:
        return point_point_ccd(x0.head<6>(), dx.head<6>(), thickness, t_max, options);
      case StencilKind::kPointEdge:
        return point_edge_ccd(x0.head<9>(), dx.head<9>(), thickness, t_max, options);
      case StencilKind::kPointTriangle:
        return point_triangle_ccd(x0, dx, thickness, t_max, options);
      case StencilKind::kEdgeEdge:
        return edge_edge_ccd(x0, dx, thickness, t_max, options);
    }
    return {};
  }
  /// The configuration at t as a stencil with the same displacement.
  MovingStencil at(double t) const {
    MovingStencil s = *this;
    s.x0 = x0 + t * dx;
    return s;
  }
};

/// The first t ∈ [0, t_max] with squared_distance(t) ≤ ξ², or +∞ if the reference finds none:
/// n + 1 samples; around each sampled local minimum a golden-section search of its two cells
/// (so a dip between samples is found); then bisection between the last sample above ξ² and the
/// first point found at or below it (60 halvings).
inline double first_contact_time(const MovingStencil& s, double thickness, double t_max,
                                 int n = 4000) {
  const double xi2 = thickness * thickness;
  const auto f = [&](double t) { return s.squared_distance(t); };
  const auto bisect = [&](double lo, double hi) {  // f(lo) > ξ² ≥ f(hi)
    for (int k = 0; k < 60; ++k) {
      const double mid = 0.5 * (lo + hi);
      (f(mid) <= xi2 ? hi : lo) = mid;
    }
    return hi;
  };
  if (f(0.0) <= xi2) return 0.0;
  double prev = f(0.0), prev_t = 0.0;
  for (int i = 1; i <= n; ++i) {
    const double t = t_max * i / n, v = f(t);
    if (v <= xi2) return bisect(prev_t, t);
    const double next = i < n ? f(t_max * (i + 1) / n) : std::numeric_limits<double>::infinity();
    if (v <= prev && v <= next) {  // a sampled local minimum: search [t − h, t + h]
      double a = prev_t, b = std::min(t_max, t_max * (i + 1) / n);
      const double r = 0.5 * (std::sqrt(5.0) - 1.0);
      for (int k = 0; k < 80; ++k) {
        const double c = b - r * (b - a), d = a + r * (b - a);
        if (f(c) <= xi2) return bisect(prev_t, c);
        if (f(d) <= xi2) return bisect(prev_t, d);
        (f(c) < f(d) ? b : a) = f(c) < f(d) ? d : c;
      }
    }
    prev = v, prev_t = t;
  }
  return std::numeric_limits<double>::infinity();
}

/// Checks a CCD result against the reference, one-sidedly: a collision the reference finds at
/// t* is reported with toi ≤ t*, every sampled configuration in [0, toi] is farther than ξ, and
/// a reported miss has toi = t_max. Returns t* (+∞ for none).
inline double expect_conservative(const MovingStencil& s, double thickness, double t_max,
                                  const CcdResult& r) {
  EXPECT_TRUE(std::isfinite(r.toi));
  EXPECT_GE(r.toi, 0.0);
  EXPECT_LE(r.toi, t_max);
  const double t_star = first_contact_time(s, thickness, t_max);
  if (std::isfinite(t_star)) {
    EXPECT_TRUE(r.may_collide) << "false negative: the trajectory reaches ξ at t* = " << t_star;
    EXPECT_LE(r.toi, t_star);
  }
  if (!r.may_collide) EXPECT_EQ(r.toi, t_max);
  if (r.toi > 0.0) {
    int closer = 0;
    for (int i = 0; i <= 1000; ++i)
      if (s.squared_distance(r.toi * i / 1000) <= thickness * thickness) ++closer;
    EXPECT_EQ(closer, 0) << "configurations in [0, toi] within ξ; toi = " << r.toi;
  }
  return t_star;
}

}  // namespace mlshell::test
