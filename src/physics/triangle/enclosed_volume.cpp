// Signed volume contribution of one triangle with gradient and Hessian (see enclosed_volume.hpp).
#include "mlshell/triangle/enclosed_volume.hpp"

#include <Eigen/Dense>

#include "mlshell/cross_matrix.hpp"

namespace mlshell {

// V_t = x0·(x1 × x2)/6, a trilinear form, symmetric under cyclic permutation of (x0, x1, x2).
//   ∇: (x1 × x2, x2 × x0, x0 × x1)/6.
//   ∇² (block (i, j) = ∂(∂V/∂x_i)/∂x_j, with d(a × b) = [a]× db − [b]× da):
//     (0,1) = −[x2]×/6, (0,2) = [x1]×/6, (1,2) = −[x0]×/6, (j,i) = (i,j)ᵀ, diagonal blocks 0.
double triangle_volume(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1,
                       const Eigen::Vector3d& x2, Vector9* grad, Matrix9* hess) {
  constexpr double kSixth = 1.0 / 6.0;
  if (grad) {
    grad->segment<3>(0) = kSixth * x1.cross(x2);
    grad->segment<3>(3) = kSixth * x2.cross(x0);
    grad->segment<3>(6) = kSixth * x0.cross(x1);
  }
  if (hess) {
    hess->setZero();
    const Eigen::Matrix3d H01 = -kSixth * cross_matrix(x2), H02 = kSixth * cross_matrix(x1),
                          H12 = -kSixth * cross_matrix(x0);
    hess->block<3, 3>(0, 3) = H01;
    hess->block<3, 3>(3, 0) = H01.transpose();
    hess->block<3, 3>(0, 6) = H02;
    hess->block<3, 3>(6, 0) = H02.transpose();
    hess->block<3, 3>(3, 6) = H12;
    hess->block<3, 3>(6, 3) = H12.transpose();
  }
  return kSixth * x0.dot(x1.cross(x2));
}

}  // namespace mlshell
