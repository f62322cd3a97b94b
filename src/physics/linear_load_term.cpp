// Dead loads: gravity, surface, line and point forces (linear in the displacement).
#include <algorithm>

#include "mlshell/effects.hpp"

namespace mlshell {

LinearLoadTerm::LinearLoadTerm(std::string name, std::vector<double> local_force, double ramp_time)
    : EnergyTerm(std::move(name)), force_(std::move(local_force)), ramp_time_(ramp_time) {}

double LinearLoadTerm::scale() const {
  return ramp_time_ > 0.0 ? std::clamp(time_ / ramp_time_, 0.0, 1.0) : 1.0;
}

PetscErrorCode LinearLoadTerm::add(const std::vector<double>& u, CompensatedSum& energy,
                                   std::vector<double>* grad, Mat) const {
  PetscFunctionBeginUser;
  const double s = scale();
  for (size_t i = 0; i < force_.size(); ++i) {
    if (force_[i] == 0.0) continue;
    energy.add(-s * force_[i] * u[i]);
    if (grad) (*grad)[i] -= s * force_[i];
  }
  PetscFunctionReturn(0);
}

}  // namespace mlshell
