// Paper eq. (3.4): the response functions φ_j of the woven-cloth material, continued beyond
// their fitted range (see response_function.hpp).
#include "mlshell/shell/response_function.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace mlshell {

ResponseFunction::ResponseFunction(std::vector<double> mu, std::vector<double> alpha,
                                   bool signed_argument, int index)
    : mu_(std::move(mu)), alpha_(std::move(alpha)) {
  const std::string name = "phi_" + std::to_string(index);
  for (double a : alpha_) linear_ = linear_ && a == 1.0;
  // Taylor coefficients φ^(n)(0) = Σ μ (α−1)(α−2)···(α−n+1), n = 1..6.
  double c[7] = {};
  for (size_t i = 0; i < mu_.size(); ++i) {
    double p = mu_[i];
    for (int n = 1; n <= 6; ++n) {
      c[n] += p;
      p *= alpha_[i] - n;
    }
  }
  for (int n = 1; n <= 4; ++n) taylor_[n] = c[n];
  if (!(c[1] > 0.0))
    throw std::invalid_argument(name + "'(0) = sum of its mu = " + std::to_string(c[1]) +
                                ": must be positive (the small-strain stiffness is k times it)");
  // Below this |u|, r = φ/u comes from the series (truncated after u^5/5!, relative error 1e-16).
  taylor_limit_ = 1e-3;
  if (c[6] != 0.0)
    taylor_limit_ = std::min(taylor_limit_, std::pow(720e-16 * c[1] / std::abs(c[6]), 0.2));
  taylor_[0] = c[5];  // the u⁴/5! term

  upper_.u = INFINITY;
  lower_.u = -INFINITY;
  if (linear_) return;  // exact everywhere, nothing to continue
  if (signed_argument) {
    upper_ = make_continuation(kMaxArgument);
    lower_ = make_continuation(-0.5);
    upper_.a = lower_.a = 0.0;  // quadratic Taylor continuation on both sides
    return;
  }
  // First zero of φ' on (0, kMaxArgument], on a 1 % geometric grid from 1e-9.
  std::vector<double> grid, slope;
  for (double u = 1e-9; u < kMaxArgument; u *= 1.01) {
    grid.push_back(u);
    slope.push_back(fitted(u).df);
    if (slope.back() <= 0.0) break;
  }
  if (slope.back() > 0.0) {
    upper_ = make_continuation(kMaxArgument);
    return;
  }
  // The last maximum of φ' before the zero: φ'' changes sign from + to − there.
  const size_t m = std::max_element(slope.begin(), slope.end()) - slope.begin();
  if (m == 0)
    throw std::invalid_argument(name +
                                "' falls from u = 0 to zero at u = " + std::to_string(grid.back()) +
                                " without rising first: the fit has no range to continue from");
  double lo = grid[m - 1], hi = grid[m + 1];
  if (fitted(lo).ddf > 0.0 && fitted(hi).ddf < 0.0) {
    for (int it = 0; it < 200 && hi - lo > 1e-15 * hi; ++it) {
      const double mid = 0.5 * (lo + hi);
      (fitted(mid).ddf > 0.0 ? lo : hi) = mid;
    }
  } else {
    lo = grid[m];
  }
  upper_ = make_continuation(lo);
}

ResponseFunction::Continuation ResponseFunction::make_continuation(double u) const {
  Continuation c;
  c.u = u;
  c.at = fitted(u);
  // The slope φ'_s + φ''_s t + ½ a t² must stay positive for t ≥ 0: its minimum is
  // φ'_s − φ''_s²/(2a) = φ'_s / 2 with this a (none needed when φ'' ≥ 0).
  if (c.at.ddf < 0.0) c.a = c.at.ddf * c.at.ddf / c.at.df;
  return c;
}

PhiValue ResponseFunction::extend(const Continuation& c, double t) {
  PhiValue v;
  v.f = c.at.f + t * (c.at.df + t * (0.5 * c.at.ddf + t * c.a / 6.0));
  v.df = c.at.df + t * (c.at.ddf + 0.5 * c.a * t);
  v.ddf = c.at.ddf + c.a * t;
  return v;
}

PhiValue ResponseFunction::fitted(double u) const {
  // (u+1)^α − 1 = expm1(α log1p(u)): the exponents reach −12 802. One log1p per argument and
  // one expm1 per term: (u+1)^(α−1) = (1 + expm1(α l))/(1 + u).
  PhiValue v;
  const double l = std::log1p(u), inverse = 1.0 / (1.0 + u);
  for (size_t i = 0; i < mu_.size(); ++i) {
    const double a = alpha_[i];
    if (a == 1.0) {  // linear term: exact for any u
      v.f += mu_[i] * u;
      v.df += mu_[i];
      continue;
    }
    const double power_m1 = std::expm1(a * l);
    v.f += mu_[i] / a * power_m1;
    const double p1 = (1.0 + power_m1) * inverse;
    v.df += mu_[i] * p1;
    v.ddf += mu_[i] * (a - 1.0) * p1 * inverse;
  }
  return v;
}

PhiValue ResponseFunction::operator()(double u) const {
  if (u > upper_.u) return extend(upper_, u - upper_.u);
  if (u < lower_.u) return extend(lower_, u - lower_.u);
  return fitted(u);
}

PhiValue ResponseFunction::ratio(double u, const PhiValue* at) const {
  PhiValue r;
  if (std::abs(u) < taylor_limit_) {
    // φ/u = Σ_{n≥1} φ^(n)(0) u^{n−1}/n!
    const double* c = taylor_;
    r.f = c[1] + u * (c[2] / 2 + u * (c[3] / 6 + u * (c[4] / 24 + u * c[0] / 120)));
    r.df = c[2] / 2 + u * (c[3] / 3 + u * (c[4] / 8 + u * c[0] / 30));
    r.ddf = c[3] / 3 + u * (c[4] / 4 + u * c[0] / 10);
    return r;
  }
  // r = φ/u, r' = (φ' − r)/u, r'' = (φ'' − 2r')/u.
  const PhiValue p = at ? *at : (*this)(u);
  r.f = p.f / u;
  r.df = (p.df - r.f) / u;
  r.ddf = (p.ddf - 2.0 * r.df) / u;
  return r;
}

}  // namespace mlshell
