// κ b_ξ(d(x)) and κ m(x) b_ξ(d(x)) with their derivatives (see barrier_pair_energy.hpp).
#include "mlshell/contact/barrier/barrier_pair_energy.hpp"

#include <cmath>
#include <limits>

#include "mlshell/psd_projection.hpp"

namespace mlshell {

template <int N>
double barrier_pair_energy(double kappa, const ContactBarrier& barrier, double d,
                           const Eigen::Matrix<double, N, 1>& grad_d,
                           const Eigen::Matrix<double, N, N>& hess_d,
                           Eigen::Matrix<double, N, 1>* grad, Eigen::Matrix<double, N, N>* hess,
                           bool project) {
  const double b = barrier.value(d);
  if (!std::isfinite(b)) return std::numeric_limits<double>::infinity();
  const double db = barrier.first_derivative(d);
  if (grad) *grad = kappa * db * grad_d;
  if (hess) {
    *hess = kappa * (barrier.second_derivative(d) * grad_d * grad_d.transpose() + db * hess_d);
    if (project) {
      if constexpr (N == 6)
        project_to_psd(*hess);
      else
        project_stencil_hessian_to_psd(*hess);  // distances see only differences
    }
  }
  return kappa * b;
}

template double barrier_pair_energy<6>(double, const ContactBarrier&, double, const Vector6&,
                                       const Matrix6&, Vector6*, Matrix6*, bool);
template double barrier_pair_energy<9>(double, const ContactBarrier&, double, const Vector9&,
                                       const Matrix9&, Vector9*, Matrix9*, bool);
template double barrier_pair_energy<12>(double, const ContactBarrier&, double, const Vector12&,
                                        const Matrix12&, Vector12*, Matrix12*, bool);

double mollified_barrier_pair_energy(double kappa, const ContactBarrier& barrier, double d,
                                     const Vector12& grad_d, const Matrix12& hess_d, double m,
                                     const Vector12& grad_m, const Matrix12& hess_m, Vector12* grad,
                                     Matrix12* hess, bool project) {
  const double b = barrier.value(d);
  if (!std::isfinite(b)) return std::numeric_limits<double>::infinity();
  const double db = barrier.first_derivative(d);
  if (grad) *grad = kappa * (b * grad_m + m * db * grad_d);
  if (hess) {
    const Matrix12 cross = grad_m * grad_d.transpose();
    *hess =
        kappa * (b * hess_m + db * (cross + cross.transpose()) +
                 m * (barrier.second_derivative(d) * grad_d * grad_d.transpose() + db * hess_d));
    if (project) project_stencil_hessian_to_psd(*hess);
  }
  return kappa * m * b;
}

}  // namespace mlshell
