// Pressure work on a closed triangle surface (see triangle_effects.hpp).
#include <algorithm>

#include "mlshell/triangle/enclosed_volume.hpp"
#include "mlshell/triangle/triangle_effects.hpp"

namespace mlshell {

PressureTerm::PressureTerm(const TriangleDiscretization& disc, const ParallelLayout& layout,
                           double pressure, double ramp_time)
    : EnergyTerm("pressure"), pressure_(pressure), ramp_time_(ramp_time) {
  for (int v : layout.local_points()) reference_.push_back(disc.points()[v]);
  const auto& X = disc.points();
  for (int f : layout.local_elements()) {
    const Triangle& t = disc.mesh().triangles[f];
    elements_.push_back({layout.local_of(t[0]), layout.local_of(t[1]), layout.local_of(t[2])});
    reference_volume_ += triangle_volume(X[t[0]], X[t[1]], X[t[2]], nullptr, nullptr);
  }
}

double PressureTerm::scale() const {
  return ramp_time_ > 0.0 ? std::clamp(time_ / ramp_time_, 0.0, 1.0) : 1.0;
}

PetscErrorCode PressureTerm::add(const std::vector<double>& u, CompensatedSum& energy,
                                 std::vector<double>* grad, Mat hess) const {
  PetscFunctionBeginUser;
  const double p = scale() * pressure_;
  Vector9 g;
  Matrix9 H;
  std::vector<PetscInt> nodes(3);
  for (const auto& e : elements_) {
    Eigen::Vector3d x[3];
    for (int k = 0; k < 3; ++k)
      x[k] = reference_[e[k]] + Eigen::Vector3d(u[3 * e[k]], u[3 * e[k] + 1], u[3 * e[k] + 2]);
    const double v = triangle_volume(x[0], x[1], x[2], grad ? &g : nullptr, hess ? &H : nullptr);
    energy.add(-p * v);
    nodes.assign(e.begin(), e.end());
    if (grad) {
      g *= -p;
      add_local_gradient(nodes, g.data(), *grad);
    }
    if (hess) {
      H *= -p;  // indefinite: a projected Newton solver projects the elastic terms only
      PetscCall(add_local_hessian(hess, nodes, H.data()));
    }
  }
  energy.add(p * reference_volume_);
  PetscFunctionReturn(0);
}

}  // namespace mlshell
