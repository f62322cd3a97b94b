// Paper eq. (3.3): the orthotropic woven-cloth energy density, with the coupling limit that
// makes it positive (material.hpp derives it).
#include <algorithm>
#include <cmath>

#include "mlshell/shell/material.hpp"

namespace mlshell {

ClydeOrthotropicMaterial::ClydeOrthotropicMaterial(const ClydeMaterial& p) : p_(p) {
  for (int j = 0; j < 4; ++j) phi_.emplace_back(p.mu[j], p.alpha[j], /*signed=*/j == 1, j + 1);
}

bool ClydeOrthotropicMaterial::coupling_factor(double e11, double e22, const PhiValue p[3],
                                               double& s, Eigen::Vector2d& ds, Eigen::Matrix2d& dds,
                                               bool derivatives) const {
  const CouplingLimit& lim = p_.coupling_limit;
  s = 1.0;
  if (!lim.enabled) return false;
  const auto& k = p_.k;
  const double w = e11 * e22;
  const PhiValue r1 = phi_[0].ratio(e11 * e11, &p[0]), r3 = phi_[2].ratio(e22 * e22, &p[2]),
                 q = phi_[1].ratio(w, &p[1]);
  if (q.f == 0.0) return false;
  // ln ρ = ln κ + ln|q(w)| − ½ ln r1(u1) − ½ ln r3(u3),  κ = k2 / (θ_b √(k1 k3)).
  const double rho =
      k[1] / (lim.bound * std::sqrt(k[0] * k[2])) * std::abs(q.f) / std::sqrt(r1.f * r3.f);
  const double x0 = lim.onset / lim.bound;
  if (!(rho > x0)) return false;
  const double width = 1.0 - x0, th = std::tanh((rho - x0) / width), sech2 = 1.0 - th * th;
  const double sat = x0 + width * th;
  s = sat / rho;
  if (!derivatives) return true;
  const double ds_rho = (sech2 - s) / rho;
  const double dds_rho = (-2.0 * th * sech2 / width - 2.0 * ds_rho) / rho;
  const double Lu1 = -0.5 * r1.df / r1.f, Lu3 = -0.5 * r3.df / r3.f, Lw = q.df / q.f;
  const double Lu1u1 = -0.5 * (r1.ddf / r1.f - (r1.df / r1.f) * (r1.df / r1.f));
  const double Lu3u3 = -0.5 * (r3.ddf / r3.f - (r3.df / r3.f) * (r3.df / r3.f));
  const double Lww = q.ddf / q.f - Lw * Lw;
  const Eigen::Vector2d dL(2.0 * e11 * Lu1 + e22 * Lw, 2.0 * e22 * Lu3 + e11 * Lw);
  Eigen::Matrix2d ddL;
  ddL(0, 0) = 4.0 * e11 * e11 * Lu1u1 + 2.0 * Lu1 + e22 * e22 * Lww;
  ddL(1, 1) = 4.0 * e22 * e22 * Lu3u3 + 2.0 * Lu3 + e11 * e11 * Lww;
  ddL(0, 1) = ddL(1, 0) = w * Lww + Lw;
  // ρ = e^L: ∇ρ = ρ ∇L, ∇²ρ = ρ (∇²L + ∇L ∇Lᵀ); then s(ρ) by the chain rule.
  const Eigen::Vector2d drho = rho * dL;
  const Eigen::Matrix2d ddrho = rho * (ddL + dL * dL.transpose());
  ds = ds_rho * drho;
  dds = dds_rho * drho * drho.transpose() + ds_rho * ddrho;
  return true;
}

double ClydeOrthotropicMaterial::energy_density(const Strain3& e, Eigen::Vector3d* grad,
                                                Eigen::Matrix3d* hess) const {
  const double e11 = e[0], e22 = e[1], e12 = e[2];
  const auto& k = p_.k;
  const PhiValue p1 = phi_[0](e11 * e11), p2 = phi_[1](e11 * e22), p3 = phi_[2](e22 * e22),
                 p4 = phi_[3](e12 * e12);
  // Coupling C = k2 φ2(w) and its derivatives in (Ẽ11, Ẽ22).
  const double C = k[1] * p2.f;
  const Eigen::Vector2d dw(e22, e11);
  const Eigen::Vector2d dC = k[1] * p2.df * dw;
  Eigen::Matrix2d ddC = k[1] * p2.ddf * dw * dw.transpose();
  ddC(0, 1) += k[1] * p2.df;
  ddC(1, 0) += k[1] * p2.df;
  double s;
  Eigen::Vector2d ds = Eigen::Vector2d::Zero();
  Eigen::Matrix2d dds = Eigen::Matrix2d::Zero();
  const PhiValue p123[3] = {p1, p2, p3};
  const bool limited = coupling_factor(e11, e22, p123, s, ds, dds, grad || hess);
  const double psi = 0.5 * k[0] * p1.f + 0.5 * k[2] * p3.f + k[3] * p4.f + C * s;
  if (grad) {
    Eigen::Vector2d g = s * dC;
    if (limited) g += C * ds;
    (*grad)[0] = k[0] * p1.df * e11 + g[0];
    (*grad)[1] = k[2] * p3.df * e22 + g[1];
    (*grad)[2] = 2.0 * k[3] * p4.df * e12;
  }
  if (hess) {
    Eigen::Matrix2d h = s * ddC;
    if (limited) h += dC * ds.transpose() + ds * dC.transpose() + C * dds;
    Eigen::Matrix3d& H = *hess;
    H.setZero();
    // d²/de² [k/2 φ(e²)] = k (2 e² φ'' + φ').
    H(0, 0) = k[0] * (2.0 * e11 * e11 * p1.ddf + p1.df) + h(0, 0);
    H(1, 1) = k[2] * (2.0 * e22 * e22 * p3.ddf + p3.df) + h(1, 1);
    H(0, 1) = H(1, 0) = h(0, 1);
    H(2, 2) = 2.0 * k[3] * (2.0 * e12 * e12 * p4.ddf + p4.df);
  }
  return psi;
}

double ClydeOrthotropicMaterial::rounding_factor() const {
  double factor = 1.0;
  for (int j = 0; j < 4; ++j) {
    double sum = 0.0, abs_sum = 0.0;
    for (double m : p_.mu[j]) {
      sum += m;
      abs_sum += std::abs(m);
    }
    factor = std::max(factor, abs_sum / sum);
  }
  return factor;
}

MaterialPointStatus ClydeOrthotropicMaterial::status(const Strain3& e) const {
  MaterialPointStatus st;
  st.beyond_fit = phi_[0].continued(e[0] * e[0]) || phi_[1].continued(e[0] * e[1]) ||
                  phi_[2].continued(e[1] * e[1]) || phi_[3].continued(e[2] * e[2]);
  double s;
  Eigen::Vector2d ds;
  Eigen::Matrix2d dds;
  const PhiValue p[3] = {phi_[0](e[0] * e[0]), phi_[1](e[0] * e[1]), phi_[2](e[1] * e[1])};
  st.coupling_limited = coupling_factor(e[0], e[1], p, s, ds, dds, false);
  return st;
}

}  // namespace mlshell
