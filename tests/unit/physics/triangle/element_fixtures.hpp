// Helpers shared by the triangle-kernel tests: central finite differences of an element
// energy's gradient and Hessian, random rotations, and stacking of positions.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <random>
#include <string>

namespace mlshell::test {

/// A uniformly random rotation (from a normalised Gaussian quaternion).
inline Eigen::Matrix3d random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Quaterniond q(n(rng), n(rng), n(rng), n(rng));
  q.normalize();
  return q.toRotationMatrix();
}

/// Central differences with step h of f(x, grad*, hess*) → energy, against its analytic gradient
/// and Hessian at x:
///   |FD(E) − ∇E| ≤ tol (|∇E| + |∇²E| length),   |FD(∇E) − ∇²E| ≤ tol |∇²E|,
/// i.e. tolerances relative to the term's own magnitude (|∇²E| length is the gradient scale
/// for a displacement of the element size, so that ∇E = 0 at rest is tested too). Also checks
/// that the Hessian is symmetric.
template <int N, class Energy>
void expect_derivatives(Energy f, const Eigen::Matrix<double, N, 1>& x, double length,
                        const std::string& where, double tol = 1e-6) {
  using Vector = Eigen::Matrix<double, N, 1>;
  using Matrix = Eigen::Matrix<double, N, N>;
  Vector g;
  Matrix H;
  const double E = f(x, &g, &H);
  ASSERT_TRUE(std::isfinite(E)) << where;
  const double h = 1e-6 * length;
  Vector fd_g;
  Matrix fd_H;
  for (int i = 0; i < N; ++i) {
    Vector xp = x, xm = x;
    xp[i] += h;
    xm[i] -= h;
    Vector gp, gm;
    const double Ep = f(xp, &gp, nullptr), Em = f(xm, &gm, nullptr);
    fd_g[i] = (Ep - Em) / (2 * h);
    fd_H.col(i) = (gp - gm) / (2 * h);
  }
  EXPECT_LE((fd_g - g).norm(), tol * (g.norm() + H.norm() * length))
      << where << "\n analytic " << g.transpose() << "\n fd       " << fd_g.transpose();
  EXPECT_LE((fd_H - H).norm(), tol * H.norm()) << where << " |H| = " << H.norm() << "\n analytic\n"
                                               << H << "\n fd\n"
                                               << fd_H;
  EXPECT_LE((H - H.transpose()).norm(), 1e-13 * H.norm()) << where;
}

inline Eigen::Matrix<double, 9, 1> stack(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                         const Eigen::Vector3d& c) {
  Eigen::Matrix<double, 9, 1> x;
  x << a, b, c;
  return x;
}

inline Eigen::Matrix<double, 12, 1> stack(const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
  Eigen::Matrix<double, 12, 1> x;
  x << a, b, c, d;
  return x;
}

}  // namespace mlshell::test
