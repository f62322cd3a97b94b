// Paper eq. (3.3)–(3.4): the orthotropic woven-cloth energy density.
#include <cmath>

#include "mlshell/material.hpp"

namespace mlshell {

ClydeOrthotropicMaterial::ClydeOrthotropicMaterial(const ClydeMaterial& p) : p_(p) {
  // First zero of φ_j' on u ≥ 0 (j = 2, argument Ẽ11 Ẽ22, may also be negative: check both
  // directions down to u = −0.99).
  for (int j = 0; j < 4; ++j) {
    limit_[j] = INFINITY;
    double f, df, ddf;
    auto increasing = [&](double u) {
      phi(j, u, f, df, ddf);
      return df > 0.0;
    };
    // Coarse scan up to u = 100 (strain 10), then bisection to the first zero of φ_j'.
    for (double u = 1e-3; u <= 100.0; u *= 1.01) {
      if (increasing(u)) continue;
      double lo = u / 1.01, hi = u;
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        (increasing(mid) ? lo : hi) = mid;
      }
      limit_[j] = lo;
      break;
    }
  }
}

void ClydeOrthotropicMaterial::phi(int j, double u, double& f, double& df, double& ddf) const {
  // φ(u) = Σ μ/α ((1+u)^α − 1), φ' = Σ μ (1+u)^(α−1), φ'' = Σ μ (α−1) (1+u)^(α−2).
  const double l = std::log1p(u);
  f = df = ddf = 0.0;
  const auto& mu = p_.mu[j];
  const auto& alpha = p_.alpha[j];
  for (size_t i = 0; i < mu.size(); ++i) {
    const double a = alpha[i];
    if (a == 1.0) {  // linear term: exact for any u (log1p would fail for u <= -1)
      f += mu[i] * u;
      df += mu[i];
      continue;
    }
    f += mu[i] / a * std::expm1(a * l);
    const double p1 = std::exp((a - 1.0) * l);
    df += mu[i] * p1;
    ddf += mu[i] * (a - 1.0) * p1 / (1.0 + u);
  }
}

double ClydeOrthotropicMaterial::energy_density(const Strain3& e, Eigen::Vector3d* grad,
                                                Eigen::Matrix3d* hess) const {
  const double e11 = e[0], e22 = e[1], e12 = e[2];
  const auto& k = p_.k;
  // Arguments u_j and their derivatives in e: u1 = e11², u2 = e11 e22, u3 = e22², u4 = e12².
  const double u[4] = {e11 * e11, e11 * e22, e22 * e22, e12 * e12};
  for (int j = 0; j < 4; ++j)
    if (std::abs(u[j]) > limit_[j]) return INFINITY;  // outside the fitted domain
  double f[4], d[4], dd[4];
  phi(0, e11 * e11, f[0], d[0], dd[0]);
  phi(1, e11 * e22, f[1], d[1], dd[1]);
  phi(2, e22 * e22, f[2], d[2], dd[2]);
  phi(3, e12 * e12, f[3], d[3], dd[3]);
  const double c[4] = {0.5 * k[0], k[1], 0.5 * k[2], k[3]};
  if (grad) {
    (*grad)[0] = c[0] * d[0] * 2.0 * e11 + c[1] * d[1] * e22;
    (*grad)[1] = c[2] * d[2] * 2.0 * e22 + c[1] * d[1] * e11;
    (*grad)[2] = c[3] * d[3] * 2.0 * e12;
  }
  if (hess) {
    Eigen::Matrix3d& H = *hess;
    H.setZero();
    H(0, 0) = c[0] * (dd[0] * 4.0 * e11 * e11 + 2.0 * d[0]) + c[1] * dd[1] * e22 * e22;
    H(1, 1) = c[2] * (dd[2] * 4.0 * e22 * e22 + 2.0 * d[2]) + c[1] * dd[1] * e11 * e11;
    H(0, 1) = H(1, 0) = c[1] * (dd[1] * e11 * e22 + d[1]);
    H(2, 2) = c[3] * (dd[3] * 4.0 * e12 * e12 + 2.0 * d[3]);
  }
  const double psi = c[0] * f[0] + c[1] * f[1] + c[2] * f[2] + c[3] * f[3];
  // A strain energy density is non-negative; where the fit gives ψ < 0 it is outside its domain.
  return psi >= 0.0 ? psi : INFINITY;
}

}  // namespace mlshell
