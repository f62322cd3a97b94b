// Helpers shared by the contact tests: stacked stencils, the closed-form derivative check of
// element_fixtures.hpp (central differences, tolerances relative to the term's own size), and
// brute-force minima of squared distances over densely sampled primitives.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <functional>
#include <limits>

#include "mlshell/contact/contact_types.hpp"
#include "physics/triangle/element_fixtures.hpp"

namespace mlshell::test {

inline Eigen::Vector3d vertex(const Vector12& x, int i) { return x.segment<3>(3 * i); }

/// min over (s, t) ∈ [0, 1]² of f(s, t) (f = +∞ outside the domain it stands for), by a
/// 101² grid and three zooms of ±2 cells around the best point, each with 41² points; grid
/// lines include the box's sides exactly, so a minimum on the boundary is sampled exactly along
/// it. For a convex quadratic f on unit-sized primitives the result exceeds the minimum by
/// ≲ 10⁻¹⁰.
inline double sampled_min_2d(const std::function<double(double, double)>& f) {
  double best = std::numeric_limits<double>::infinity(), bs = 0.0, bt = 0.0;
  double s0 = 0.0, s1 = 1.0, t0 = 0.0, t1 = 1.0;
  int n = 100;
  for (int level = 0; level < 4; ++level) {
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) {
        const double s = i == n ? s1 : s0 + (s1 - s0) * i / n;
        const double t = j == n ? t1 : t0 + (t1 - t0) * j / n;
        const double v = f(s, t);
        if (v < best) best = v, bs = s, bt = t;
      }
    const double hs = 2.0 * (s1 - s0) / n, ht = 2.0 * (t1 - t0) / n;
    s0 = std::max(0.0, bs - hs), s1 = std::min(1.0, bs + hs);
    t0 = std::max(0.0, bt - ht), t1 = std::min(1.0, bt + ht);
    n = 40;
  }
  return best;
}

/// The same in one parameter s ∈ [0, 1].
inline double sampled_min_1d(const std::function<double(double)>& f) {
  return sampled_min_2d([&](double s, double) { return f(s); });
}

/// Brute-force squared distance from p to the triangle (t0, t1, t2): its interior grid and its
/// three edges sampled separately (the hypotenuse is no grid line).
inline double sampled_point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& t0,
                                              const Eigen::Vector3d& t1,
                                              const Eigen::Vector3d& t2) {
  double best = sampled_min_2d([&](double s, double t) {
    if (s + t > 1.0) return std::numeric_limits<double>::infinity();
    return (t0 + s * (t1 - t0) + t * (t2 - t0) - p).squaredNorm();
  });
  const Eigen::Vector3d t[3] = {t0, t1, t2};
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d &a = t[i], &b = t[(i + 1) % 3];
    best = std::min(best,
                    sampled_min_1d([&](double s) { return (a + s * (b - a) - p).squaredNorm(); }));
  }
  return best;
}

/// Brute-force squared distance between the segments (ea0, ea1) and (eb0, eb1).
inline double sampled_edge_edge_distance(const Eigen::Vector3d& ea0, const Eigen::Vector3d& ea1,
                                         const Eigen::Vector3d& eb0, const Eigen::Vector3d& eb1) {
  return sampled_min_2d([&](double s, double t) {
    return (ea0 + s * (ea1 - ea0) - eb0 - t * (eb1 - eb0)).squaredNorm();
  });
}

}  // namespace mlshell::test
