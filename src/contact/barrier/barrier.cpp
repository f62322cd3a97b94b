// The clamped log barrier and its thickness offset (see barrier.hpp).
#include "mlshell/contact/barrier/barrier.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace mlshell {

namespace {
constexpr double kInf = std::numeric_limits<double>::infinity();
}

double barrier(double d, double dhat) {
  if (d <= 0.0) return kInf;
  if (d >= dhat) return 0.0;
  const double r = d - dhat;
  return -r * r * std::log(d / dhat);
}

double barrier_first_derivative(double d, double dhat) {
  if (d <= 0.0) return -kInf;
  if (d >= dhat) return 0.0;
  return (dhat - d) * (2.0 * std::log(d / dhat) - dhat / d + 1.0);
}

double barrier_second_derivative(double d, double dhat) {
  if (d <= 0.0) return kInf;
  if (d >= dhat) return 0.0;
  const double q = (d - dhat) / d;
  return -2.0 * std::log(d / dhat) - 4.0 * q + q * q;
}

ContactBarrier ContactBarrier::from(double thickness, double gap) {
  if (!(std::isfinite(thickness) && thickness >= 0.0))
    throw std::invalid_argument("contact barrier: thickness " + std::to_string(thickness) +
                                " must be finite and >= 0");
  if (!(std::isfinite(gap) && gap > 0.0))
    throw std::invalid_argument("contact barrier: activation gap " + std::to_string(gap) +
                                " must be finite and > 0");
  return ContactBarrier{thickness, gap};
}

double ContactBarrier::activation_squared_distance() const {
  return (thickness + gap) * (thickness + gap);
}

// b_ξ(d) = b(d − ξ², 2ξĝ + ĝ²).
double ContactBarrier::value(double d) const {
  return barrier(d - thickness * thickness, (2.0 * thickness + gap) * gap);
}

double ContactBarrier::first_derivative(double d) const {
  return barrier_first_derivative(d - thickness * thickness, (2.0 * thickness + gap) * gap);
}

double ContactBarrier::second_derivative(double d) const {
  return barrier_second_derivative(d - thickness * thickness, (2.0 * thickness + gap) * gap);
}

}  // namespace mlshell
