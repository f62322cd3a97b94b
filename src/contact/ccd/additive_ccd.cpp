// Additive CCD: the loop of additive_ccd.hpp's file comment (Li et al. 2021, Algorithm 1), one
// template for the four stencils.
#include "mlshell/contact/ccd/additive_ccd.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "mlshell/contact/distance/edge_edge.hpp"
#include "mlshell/contact/distance/point_edge.hpp"
#include "mlshell/contact/distance/point_point.hpp"
#include "mlshell/contact/distance/point_triangle.hpp"

namespace mlshell {

void AdditiveCcdOptions::validate() const {
  if (!(conservative_rescaling > 0.0 && conservative_rescaling < 1.0))
    throw std::invalid_argument("additive CCD: conservative_rescaling must lie in (0, 1), got " +
                                std::to_string(conservative_rescaling));
  if (max_iterations < 1)
    throw std::invalid_argument("additive CCD: max_iterations must be ≥ 1, got " +
                                std::to_string(max_iterations));
}

namespace {

/// g(d) = (d − ξ²) / (√d + ξ), the gap D − ξ without cancellation.
double gap(double d, double thickness) {
  return (d - thickness * thickness) / (std::sqrt(d) + thickness);
}

/// The loop of the file comment for a stencil of N vertices whose first `split` belong to one
/// primitive and the rest to the other; `distance` maps stacked positions to d.
template <int N, class Distance>
CcdResult additive_ccd(const Eigen::Matrix<double, 3 * N, 1>& x0,
                       const Eigen::Matrix<double, 3 * N, 1>& dx_in, int split, double thickness,
                       double t_max, const AdditiveCcdOptions& options, Distance distance) {
  options.validate();
  if (!(std::isfinite(thickness) && thickness >= 0.0))
    throw std::invalid_argument("additive CCD: the thickness must be finite and ≥ 0, got " +
                                std::to_string(thickness));
  if (!(std::isfinite(t_max) && t_max >= 0.0))
    throw std::invalid_argument("additive CCD: t_max must be finite and ≥ 0, got " +
                                std::to_string(t_max));
  if (!x0.allFinite() || !dx_in.allFinite() || !(x0 + t_max * dx_in).allFinite())
    throw std::invalid_argument("additive CCD: positions and displacements must be finite");

  CcdResult result;
  const double d0 = distance(x0);
  if (!std::isfinite(d0))
    throw std::invalid_argument("additive CCD: the squared distance at t = 0 overflows");
  if (d0 <= thickness * thickness) {  // touching or closer at t = 0
    result.may_collide = true;
    result.toi = 0.0;
    return result;
  }

  // Step 1: remove the mean displacement; l_p = max over one primitive + max over the other.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int i = 0; i < N; ++i) mean += dx_in.template segment<3>(3 * i);
  mean /= N;
  Eigen::Matrix<double, 3 * N, 1> dx = dx_in;
  double max_a = 0.0, max_b = 0.0;
  for (int i = 0; i < N; ++i) {
    dx.template segment<3>(3 * i) -= mean;
    const double n = dx.template segment<3>(3 * i).norm();
    (i < split ? max_a : max_b) = std::max(i < split ? max_a : max_b, n);
  }
  const double lp = max_a + max_b;
  result.toi = t_max;
  if (lp == 0.0 || t_max == 0.0) return result;  // a rigid translation, or no time to move

  // Step 2: conservative advancement.
  const double eta = options.conservative_rescaling;
  const double stop_gap = (1.0 - eta) * gap(d0, thickness);
  double t = 0.0, g = gap(d0, thickness);
  for (long it = 0; it < options.max_iterations; ++it) {
    const double tl = eta * g / lp;
    if (t + tl >= t_max) return result;  // [0, t_max] ⊂ [0, t + t_l] is proven safe
    const double d = distance(x0 + (t + tl) * dx);
    ++result.iterations;
    if (!std::isfinite(d))
      throw std::invalid_argument("additive CCD: the squared distance overflows along the step");
    const double g_next = gap(d, thickness);
    // A gap ≤ 0 contradicts the step's bound (rounding): stop at the last t proven safe.
    if (!(g_next > 0.0) || (t > 0.0 && g_next < stop_gap)) {
      result.may_collide = true;
      result.toi = t;
      return result;
    }
    t += tl;
    g = g_next;
  }
  result.may_collide = true;  // capped: t is proven safe, what lies beyond is not
  result.capped = true;
  result.toi = t;
  return result;
}

Eigen::Vector3d at(const auto& x, int i) { return x.template segment<3>(3 * i); }

}  // namespace

CcdResult point_point_ccd(const Vector6& x0, const Vector6& dx, double thickness, double t_max,
                          const AdditiveCcdOptions& options) {
  return additive_ccd<2>(x0, dx, 1, thickness, t_max, options,
                         [](const Vector6& x) { return point_point_distance(at(x, 0), at(x, 1)); });
}

CcdResult point_edge_ccd(const Vector9& x0, const Vector9& dx, double thickness, double t_max,
                         const AdditiveCcdOptions& options) {
  return additive_ccd<3>(x0, dx, 1, thickness, t_max, options, [](const Vector9& x) {
    return point_edge_distance(at(x, 0), at(x, 1), at(x, 2));
  });
}

CcdResult point_triangle_ccd(const Vector12& x0, const Vector12& dx, double thickness, double t_max,
                             const AdditiveCcdOptions& options) {
  return additive_ccd<4>(x0, dx, 1, thickness, t_max, options, [](const Vector12& x) {
    return point_triangle_distance(at(x, 0), at(x, 1), at(x, 2), at(x, 3));
  });
}

CcdResult edge_edge_ccd(const Vector12& x0, const Vector12& dx, double thickness, double t_max,
                        const AdditiveCcdOptions& options) {
  return additive_ccd<4>(x0, dx, 2, thickness, t_max, options, [](const Vector12& x) {
    return edge_edge_distance(at(x, 0), at(x, 1), at(x, 2), at(x, 3));
  });
}

}  // namespace mlshell
