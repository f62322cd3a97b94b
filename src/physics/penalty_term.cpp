// Penalty Dirichlet and clamp conditions (paper eq. 3.6): β/2 ‖P(u − d(X, t))‖² on curves and
// points, plus β_r/2 ‖∂_ν u − (R − I) ∂_ν X‖² (the slope across the boundary, turned with the
// motion) for clamps; in the augmented-Lagrangian mode also −λ·P(u − d(X, t)) with multipliers
// updated between solves. d(X, t) = φ_t(X) − X is the displacement of the rigid motion
// φ_t(X) = R(X − c) + c + T at the sample's reference point X.
#include <algorithm>
#include <cmath>

#include "mlshell/effects.hpp"

namespace mlshell {

PenaltyTerm::PenaltyTerm(std::string name, std::vector<PenaltySample> samples,
                         std::array<bool, 3> components, PrescribedMotion motion)
    : EnergyTerm(std::move(name)),
      samples_(std::move(samples)),
      components_(components),
      motion_(std::move(motion)) {}

Eigen::Vector3d PenaltyTerm::residual(const PenaltySample& s, const std::vector<double>& u,
                                      const RigidPlacement& placement) const {
  const Eigen::Vector3d d = placement.displacement(s.reference);
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  for (size_t i = 0; i < s.nodes.size(); ++i)
    for (int c = 0; c < 3; ++c) r[c] += s.value[i] * u[3 * s.nodes[i] + c];
  for (int c = 0; c < 3; ++c) r[c] = components_[c] ? r[c] - d[c] : 0.0;
  return r;
}

double PenaltyTerm::max_violation(const std::vector<double>& u) const {
  const RigidPlacement placement = motion_(time_);
  double worst = 0.0;
  for (const PenaltySample& s : samples_) worst = std::max(worst, residual(s, u, placement).norm());
  return worst;
}

void PenaltyTerm::update_multipliers(const std::vector<double>& u, double violation) {
  const RigidPlacement placement = motion_(time_);
  for (size_t k = 0; k < samples_.size(); ++k)
    multipliers_[k] -= scale_ * samples_[k].weight * residual(samples_[k], u, placement);
  // Linear convergence at rate ~K/(K + s w) for a structure of stiffness K: stiffen when slow.
  if (violation > 0.25 * last_violation_) scale_ *= 10.0;
  last_violation_ = violation;
}

PetscErrorCode PenaltyTerm::add(const std::vector<double>& u, CompensatedSum& energy,
                                std::vector<double>* grad, Mat hess) const {
  PetscFunctionBeginUser;
  const RigidPlacement placement = motion_(time_);
  std::vector<double> ge, He;
  for (const PenaltySample& s : samples_) {
    const int n = static_cast<int>(s.nodes.size());
    const Eigen::Vector3d d = placement.displacement(s.reference);
    // r = u(ξ) − d, t = ∂_ν u − (R − I) ∂_ν X: the slope's departure from the turned one.
    const Eigen::Vector3d slope =
        s.conormal.empty() ? Eigen::Vector3d::Zero() : placement.turn(s.reference_conormal);
    double r[3] = {0, 0, 0}, t[3] = {-slope[0], -slope[1], -slope[2]};
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) {
        r[c] += s.value[i] * u[3 * s.nodes[i] + c];
        if (!s.conormal.empty()) t[c] += s.conormal[i] * u[3 * s.nodes[i] + c];
      }
    const size_t k = static_cast<size_t>(&s - samples_.data());
    const double* lambda = multipliers_.empty() ? nullptr : multipliers_[k].data();
    for (int c = 0; c < 3; ++c) {
      r[c] = components_[c] ? r[c] - d[c] : 0.0;
      energy.add(0.5 * scale_ * s.weight * r[c] * r[c] + 0.5 * s.rotation_weight * t[c] * t[c]);
      if (lambda) energy.add(-lambda[c] * r[c]);
    }
    if (grad) {
      ge.assign(3 * n, 0.0);
      for (int i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c)
          ge[3 * i + c] =
              (scale_ * s.weight * r[c] - (lambda && components_[c] ? lambda[c] : 0.0)) *
                  s.value[i] +
              (s.conormal.empty() ? 0.0 : s.rotation_weight * t[c] * s.conormal[i]);
      add_local_gradient(s.nodes, ge.data(), *grad);
    }
    if (hess) {
      He.assign(9 * n * n, 0.0);
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
          for (int c = 0; c < 3; ++c)
            He[(3 * i + c) * 3 * n + 3 * j + c] =
                (components_[c] ? scale_ * s.weight * s.value[i] * s.value[j] : 0.0) +
                (s.conormal.empty() ? 0.0 : s.rotation_weight * s.conormal[i] * s.conormal[j]);
      PetscCall(add_local_hessian(hess, s.nodes, He.data()));
    }
  }
  PetscFunctionReturn(0);
}

}  // namespace mlshell
