// κ_min, the initial κ and its doubling (see adaptive_stiffness.hpp).
#include "mlshell/contact/barrier/adaptive_stiffness.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace mlshell {

namespace {
void require_positive(double value, const char* name) {
  if (!(std::isfinite(value) && value > 0.0))
    throw std::invalid_argument(std::string("barrier stiffness: ") + name + " " +
                                std::to_string(value) + " must be finite and > 0");
}
}  // namespace

double min_barrier_stiffness(const ContactBarrier& barrier, double bbox_diagonal,
                             double average_mass, double scale) {
  require_positive(bbox_diagonal, "bounding-box diagonal");
  require_positive(average_mass, "average nodal mass");
  require_positive(scale, "scale");
  const double probe_gap = std::min(1e-8 * bbox_diagonal, 0.5 * barrier.gap);
  const double d0 = (barrier.thickness + probe_gap) * (barrier.thickness + probe_gap);
  return scale * average_mass / (4.0 * d0 * barrier.second_derivative(d0));
}

double initial_barrier_stiffness(const ContactBarrier& barrier, double bbox_diagonal,
                                 double average_mass, double barrier_dot_energy_gradient,
                                 double barrier_gradient_squared_norm, double* max_stiffness,
                                 double scale) {
  const double kappa_min = min_barrier_stiffness(barrier, bbox_diagonal, average_mass, scale);
  const double kappa_max = 100.0 * kappa_min;
  if (max_stiffness) *max_stiffness = kappa_max;
  double kappa = 1.0;
  if (barrier_gradient_squared_norm > 0.0)
    kappa = -barrier_dot_energy_gradient / barrier_gradient_squared_norm;
  if (!std::isfinite(kappa)) kappa = kappa_min;
  return std::clamp(kappa, kappa_min, kappa_max);
}

double initial_barrier_stiffness(const ContactBarrier& barrier, double bbox_diagonal,
                                 double average_mass,
                                 const Eigen::Ref<const Eigen::VectorXd>& grad_energy,
                                 const Eigen::Ref<const Eigen::VectorXd>& grad_barrier,
                                 double* max_stiffness, double scale) {
  if (grad_energy.size() != grad_barrier.size())
    throw std::invalid_argument("initial_barrier_stiffness: gradients of sizes " +
                                std::to_string(grad_energy.size()) + " and " +
                                std::to_string(grad_barrier.size()));
  return initial_barrier_stiffness(barrier, bbox_diagonal, average_mass,
                                   grad_barrier.dot(grad_energy), grad_barrier.squaredNorm(),
                                   max_stiffness, scale);
}

double update_barrier_stiffness(double prev_min_distance, double min_distance, double max_stiffness,
                                double stiffness, double bbox_diagonal, double thickness,
                                double epsilon) {
  const double reach = thickness + epsilon * bbox_diagonal;
  const double near = reach * reach;
  if (prev_min_distance < near && min_distance < near && min_distance < prev_min_distance)
    return std::min(max_stiffness, 2.0 * stiffness);
  return stiffness;
}

}  // namespace mlshell
