// Penalty Dirichlet and clamp conditions (paper eq. 3.6): β/2 ‖P(u − d(t))‖² on curves and
// points, plus β_r/2 ‖∂_ν u‖² (the slope across the boundary) for clamps.
#include <algorithm>
#include <cmath>

#include "mlshell/effects.hpp"

namespace mlshell {

PenaltyTerm::PenaltyTerm(std::string name, std::vector<PenaltySample> samples,
                         std::array<bool, 3> components,
                         std::function<Eigen::Vector3d(double)> motion)
    : EnergyTerm(std::move(name)),
      samples_(std::move(samples)),
      components_(components),
      motion_(std::move(motion)) {}

double PenaltyTerm::max_violation(const std::vector<double>& u) const {
  const Eigen::Vector3d d = motion_(time_);
  double worst = 0.0;
  for (const PenaltySample& s : samples_) {
    Eigen::Vector3d r = Eigen::Vector3d::Zero();
    for (size_t i = 0; i < s.nodes.size(); ++i)
      for (int c = 0; c < 3; ++c) r[c] += s.value[i] * u[3 * s.nodes[i] + c];
    for (int c = 0; c < 3; ++c) r[c] = components_[c] ? r[c] - d[c] : 0.0;
    worst = std::max(worst, r.norm());
  }
  return worst;
}

PetscErrorCode PenaltyTerm::add(const std::vector<double>& u, CompensatedSum& energy,
                                std::vector<double>* grad, Mat hess) const {
  PetscFunctionBeginUser;
  const Eigen::Vector3d d = motion_(time_);
  std::vector<double> ge, He;
  for (const PenaltySample& s : samples_) {
    const int n = static_cast<int>(s.nodes.size());
    double r[3] = {0, 0, 0}, t[3] = {0, 0, 0};
    for (int i = 0; i < n; ++i)
      for (int c = 0; c < 3; ++c) {
        r[c] += s.value[i] * u[3 * s.nodes[i] + c];
        if (!s.conormal.empty()) t[c] += s.conormal[i] * u[3 * s.nodes[i] + c];
      }
    for (int c = 0; c < 3; ++c) {
      r[c] = components_[c] ? r[c] - d[c] : 0.0;
      energy.add(0.5 * s.weight * r[c] * r[c] + 0.5 * s.rotation_weight * t[c] * t[c]);
    }
    if (grad) {
      ge.assign(3 * n, 0.0);
      for (int i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c)
          ge[3 * i + c] = s.weight * r[c] * s.value[i] +
                          (s.conormal.empty() ? 0.0 : s.rotation_weight * t[c] * s.conormal[i]);
      add_local_gradient(s.nodes, ge.data(), *grad);
    }
    if (hess) {
      He.assign(9 * n * n, 0.0);
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
          for (int c = 0; c < 3; ++c)
            He[(3 * i + c) * 3 * n + 3 * j + c] =
                (components_[c] ? s.weight * s.value[i] * s.value[j] : 0.0) +
                (s.conormal.empty() ? 0.0 : s.rotation_weight * s.conormal[i] * s.conormal[j]);
      PetscCall(add_local_hessian(hess, s.nodes, He.data()));
    }
  }
  PetscFunctionReturn(0);
}

}  // namespace mlshell
