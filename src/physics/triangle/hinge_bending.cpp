// Dihedral angle of a hinge, its closed-form gradient and Hessian, and the hinge bending energy
// w (θ − θ̄)² (see hinge_bending.hpp).
//
// Gradient of θ. Let wing k ∈ {1, 2} have the opposite vertex x_p (p = 2, 3), r = x_p − x0, the
// unnormalised normal n_k (n₁ = e × r, n₂ = r × e), the unit normal N_k, the height
// h_k = |n_k|/ℓ of x_p over the hinge (ℓ = |e|), and w_k = n_k/|n_k|² = N_k/(ℓ h_k).
// θ depends on x only through N₁ and N₂ (ê ∝ N₁ × N₂ away from θ = 0, π). Moving a vertex of
// wing k within its plane leaves N_k unchanged; moving vertex i by δ along N_k turns the wing
// about the side opposite i by δ/h_i (h_i the height of i), dN_k = −(δ/h_i) m_i with m_i the
// in-plane unit vector from that side toward i. Only the part of dN_k along the wing's direction
// away from the hinge m_k turns N_k about ê (the part along ê is second order in θ), and turning
// N₁ (N₂) by α about ê changes θ by −α (+α). In the wing's plane coordinates x0 = (0, 0),
// x1 = (ℓ, 0), x_p = (a, h_k) this gives, for either wing,
//   ∂θ/∂x_p = −ℓ w_k,   ∂θ/∂x0 = −(e·(x_p − x1))/ℓ w_k,   ∂θ/∂x1 = (e·(x_p − x0))/ℓ w_k,
// summed over the two wings at x0 and x1. These hold for every θ, ±π included: no θ, no
// division by sin θ, no acos.
//
// Hessian of θ. Write ∂θ/∂x_v = Σ_k c_{v,k} w_k with c_p = −ℓ, c_0 = −s/ℓ, c_1 = t/ℓ,
// s = e·(r − e), t = e·r. Then
//   ∂²θ/∂x_v∂x_u = Σ_k [ w_k (∇_u c_{v,k})ᵀ + c_{v,k} (I − 2 N_k N_kᵀ)/|n_k|² ∂n_k/∂x_u ],
// using d(n/|n|²) = (I − 2 N Nᵀ) dn/|n|² and, with σ = +1 (wing 1), −1 (wing 2), n_k = σ e × r:
//   ∂n_k/∂x0 = σ [r − e]×,   ∂n_k/∂x1 = −σ [r]×,   ∂n_k/∂x_p = σ [e]×,
//   ∇s = (e − r, r − 2e, e),  ∇t = (−r − e, r, e),  ∇ℓ = (−ê, ê, 0)   at (x0, x1, x_p),
//   ∇c_0 = −∇s/ℓ + s ∇ℓ/ℓ²,  ∇c_1 = ∇t/ℓ − t ∇ℓ/ℓ²,  ∇c_p = −∇ℓ.
// The result is symmetric in exact arithmetic; it is symmetrised to remove the round-off.
#include "mlshell/triangle/hinge_bending.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "mlshell/cross_matrix.hpp"

namespace mlshell {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kPi = std::numbers::pi;

// θ = atan2((n₁ × n₂)·ê, n₁·n₂), with atan2's −π mapped to π so that θ ∈ (−π, π].
double angle_of(const Eigen::Vector3d& e, const Eigen::Vector3d& n1, const Eigen::Vector3d& n2) {
  const double theta = std::atan2(n1.cross(n2).dot(e) / e.norm(), n1.dot(n2));
  return theta == -kPi ? kPi : theta;
}

}  // namespace

// std::remainder is exact and gives [−π, π].
double wrap_angle(double d) {
  const double r = std::remainder(d, 2.0 * kPi);
  return r <= -kPi ? r + 2.0 * kPi : r;
}

// θ with ∇θ and ∇²θ (either may be null) by the formulas of the file comment.
bool dihedral_angle_derivatives(const Eigen::Vector3d x[4], double& theta, Vector12* g,
                                Matrix12* H) {
  const Eigen::Vector3d e = x[1] - x[0];
  const double l2 = e.squaredNorm();
  const Eigen::Vector3d n[2] = {e.cross(x[2] - x[0]), (x[3] - x[0]).cross(e)};
  if (!(l2 > 0.0) || !(n[0].squaredNorm() > 0.0) || !(n[1].squaredNorm() > 0.0)) return false;
  theta = angle_of(e, n[0], n[1]);
  if (!g && !H) return true;
  const double l = std::sqrt(l2);
  const Eigen::Vector3d e_hat = e / l;
  if (g) g->setZero();
  if (H) H->setZero();
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  for (int k = 0; k < 2; ++k) {
    const int p = 2 + k;
    const int vertex[3] = {0, 1, p};
    const double sigma = k == 0 ? 1.0 : -1.0;
    const Eigen::Vector3d r = x[p] - x[0];
    const double n2 = n[k].squaredNorm();
    const Eigen::Vector3d w = n[k] / n2;
    const double s = e.dot(r - e), t = e.dot(r);
    const double c[3] = {-s / l, t / l, -l};
    if (g)
      for (int v = 0; v < 3; ++v) g->segment<3>(3 * vertex[v]) += c[v] * w;
    if (!H) continue;
    const Eigen::Vector3d grad_s[3] = {e - r, r - 2.0 * e, e};
    const Eigen::Vector3d grad_t[3] = {-r - e, r, e};
    const Eigen::Vector3d grad_l[3] = {-e_hat, e_hat, Eigen::Vector3d::Zero()};
    const Eigen::Matrix3d dn[3] = {sigma * cross_matrix(r - e), -sigma * cross_matrix(r),
                                   sigma * cross_matrix(e)};
    const Eigen::Vector3d N = n[k] / std::sqrt(n2);
    const Eigen::Matrix3d dw = (I - 2.0 * N * N.transpose()) / n2;  // ∂w/∂n
    for (int u = 0; u < 3; ++u) {
      const Eigen::Vector3d grad_c[3] = {-grad_s[u] / l + s * grad_l[u] / l2,
                                         grad_t[u] / l - t * grad_l[u] / l2, -grad_l[u]};
      const Eigen::Matrix3d dw_u = dw * dn[u];
      for (int v = 0; v < 3; ++v)
        H->block<3, 3>(3 * vertex[v], 3 * vertex[u]) += w * grad_c[v].transpose() + c[v] * dw_u;
    }
  }
  if (H) *H = 0.5 * (*H + H->transpose()).eval();
  return true;
}

double dihedral_angle(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1,
                      const Eigen::Vector3d& x2, const Eigen::Vector3d& x3) {
  const Eigen::Vector3d x[4] = {x0, x1, x2, x3};
  double theta = 0.0;
  return dihedral_angle_derivatives(x, theta, nullptr, nullptr) ? theta : 0.0;
}

// k = E τ³ / (24 (1 − ν²)).
double hinge_stiffness(double E, double nu, double thickness) {
  return E * thickness * thickness * thickness / (24.0 * (1.0 - nu * nu));
}

// θ̄ = θ(X) and w = 3 |ē|² / (Ā₁ + Ā₂) · k with Ā_k = ½ |n̄_k|.
HingeRest HingeRest::from(const Eigen::Vector3d& X0, const Eigen::Vector3d& X1,
                          const Eigen::Vector3d& X2, const Eigen::Vector3d& X3, double stiffness) {
  if (!X0.allFinite() || !X1.allFinite() || !X2.allFinite() || !X3.allFinite())
    throw std::invalid_argument("HingeRest: rest position is not finite");
  const Eigen::Vector3d e = X1 - X0, r1 = X2 - X0, r2 = X3 - X0;
  const double eps = std::numeric_limits<double>::epsilon();
  const double a1 = e.cross(r1).norm(), a2 = r2.cross(e).norm();  // twice the areas
  if (!(e.norm() > 0.0) || !(a1 > 64.0 * eps * e.norm() * r1.norm()) ||
      !(a2 > 64.0 * eps * e.norm() * r2.norm()))
    throw std::invalid_argument("HingeRest: degenerate rest hinge (zero edge or area)");
  HingeRest rest;
  rest.angle = dihedral_angle(X0, X1, X2, X3);
  rest.weight = 3.0 * e.squaredNorm() / (0.5 * (a1 + a2)) * stiffness;
  return rest;
}

// w Δ² with Δ = wrap(θ − θ̄):  ∇ = 2 w Δ ∇θ,  ∇² = 2 w (∇θ ∇θᵀ + Δ ∇²θ).
double hinge_bending(const HingeRest& rest, const Eigen::Vector3d& x0, const Eigen::Vector3d& x1,
                     const Eigen::Vector3d& x2, const Eigen::Vector3d& x3, Vector12* grad,
                     Matrix12* hess) {
  const Eigen::Vector3d x[4] = {x0, x1, x2, x3};
  for (const auto& xi : x)
    if (!xi.allFinite()) return kInfinity;
  double theta = 0.0;
  Vector12 dtheta;
  Matrix12 ddtheta;
  if (!dihedral_angle_derivatives(x, theta, (grad || hess) ? &dtheta : nullptr,
                                  hess ? &ddtheta : nullptr))
    return kInfinity;
  const double delta = wrap_angle(theta - rest.angle);
  const double energy = rest.weight * delta * delta;
  if (!std::isfinite(energy)) return kInfinity;
  if (!grad && !hess) return energy;
  const Vector12 g = 2.0 * rest.weight * delta * dtheta;
  Matrix12 H;
  if (hess) H = 2.0 * rest.weight * (dtheta * dtheta.transpose() + delta * ddtheta);
  if ((grad && !g.allFinite()) || (hess && !H.allFinite())) return kInfinity;
  if (grad) *grad = g;
  if (hess) *hess = H;
  return energy;
}

}  // namespace mlshell
