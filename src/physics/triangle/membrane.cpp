// Neo-Hookean and St. Venant–Kirchhoff membrane energies of one triangle with closed-form
// gradients and Hessians (see membrane.hpp).
//
// Frame. ψ depends on M = Ā⁻¹A only through tr M, det M and tr M² (tr G² = ¼ tr(M − I)²), which
// are similarity invariants. With the Cholesky factor Ā⁻¹ = L Lᵀ (L lower triangular),
//   M = L Lᵀ A  ~  C = Lᵀ A L = Fᵀ F,   F = D L = [f₁, f₂] (3×2),
// the deformation gradient in an orthonormal rest frame, so ψ is evaluated from C with the rest
// metric I. This avoids the cancellation of Ā⁻¹A in the edge basis, whose round-off grows like
// 1/sin² of the smallest rest angle (1e6 at aspect ratio 1e-3), to 1/sin: f₁ = L₁₁ d₁ + L₂₁ d₂,
// f₂ = L₂₂ d₂ with d₁ = x1 − x0, d₂ = x2 − x0, and L₂₂ = √det Ā⁻¹ / L₁₁ uses the accurate
// det Ā⁻¹ = 1/(2 Ā_t)² (not the cancelling Ā⁻¹₁₁Ā⁻¹₂₂ − (Ā⁻¹₁₂)²), and
// det C = det M = det Ā⁻¹ |d₁ × d₂|².
//
// Derivatives. ψ is a function of the three independent entries c = (C₁₁, C₂₂, C₁₂) of the
// symmetric C (C₁₂ = C₂₁ counted once, so ∂ψ/∂c₃ = 2 S₁₂ for S = ∂ψ/∂C as a symmetric matrix).
// With C₁₁ = f₁·f₁, C₂₂ = f₂·f₂, C₁₂ = f₁·f₂ the Jacobian J = ∂c/∂(f₁, f₂) (3×6) has rows
// (2f₁ᵀ, 0), (0, 2f₂ᵀ), (f₂ᵀ, f₁ᵀ), and ∇²C₁₁ = 2I on (f₁, f₁), ∇²C₂₂ = 2I on (f₂, f₂),
// ∇²C₁₂ = I on (f₁, f₂) and (f₂, f₁). Hence in (f₁, f₂):
//   g₆ = Jᵀ ∇_c ψ,   H₆ = Jᵀ ∇_c²ψ J + Σ_k (∂ψ/∂c_k) ∇²c_k.
// Finally F = Σ_i x_i W_iᵀ is linear in x with the 3×2 weights W (rows x0, x1, x2)
//   W = [[−L₁₁ − L₂₁, −L₂₂], [L₁₁, 0], [L₂₁, L₂₂]],
// so ∂/∂x_i = Σ_a W_ia ∂/∂f_a and the (i, j) block of the Hessian is Σ_ab W_ia W_jb H₆(a, b).
#include "mlshell/triangle/membrane.hpp"

#include <Eigen/Dense>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace mlshell {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Zero area to round-off: sin of the angle between the edges at x0 below 64 ε.
constexpr double kCollapse = 64.0 * std::numeric_limits<double>::epsilon();

/// ψ, ∇_c ψ and ∇_c²ψ in c = (C₁₁, C₂₂, C₁₂).
struct MetricEnergy {
  double psi = 0.0;
  Eigen::Vector3d g = Eigen::Vector3d::Zero();
  Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
};

/// F = D L in the orthonormal rest frame, C = FᵀF, det C (from the cross product, free of the
/// cancellation in C₁₁C₂₂ − C₁₂²), and the weights W of F(x).
struct Deformed {
  Eigen::Vector3d f1, f2;
  Eigen::Matrix2d C;
  double det_C = 0.0;
  bool collapsed = false;  ///< |d₁ × d₂| ≤ 64 ε |d₁| |d₂|: zero area to round-off
  Eigen::Matrix<double, 3, 2> W;
};

/// The Cholesky factor L of Ā⁻¹ = L Lᵀ (entries L₁₁, L₂₁, L₂₂), with det Ā⁻¹ = 1/(2 Ā_t)²; false
/// if Ā⁻¹ is not positive definite.
bool rest_frame(const TriangleRest& rest, double& L11, double& L21, double& L22) {
  const double det = 1.0 / (4.0 * rest.area * rest.area);
  const double b11 = rest.metric_inverse(0, 0);
  if (!(rest.area > 0.0) || !(b11 > 0.0) || !std::isfinite(det) || !std::isfinite(b11))
    return false;
  L11 = std::sqrt(b11);
  L21 = rest.metric_inverse(1, 0) / L11;
  L22 = std::sqrt(det) / L11;
  return std::isfinite(L21) && std::isfinite(L22);
}

Deformed deformed(double L11, double L21, double L22, const Eigen::Vector3d& x0,
                  const Eigen::Vector3d& x1, const Eigen::Vector3d& x2) {
  Deformed d;
  const Eigen::Vector3d d1 = x1 - x0, d2 = x2 - x0;
  d.f1 = L11 * d1 + L21 * d2;
  d.f2 = L22 * d2;
  d.C << d.f1.dot(d.f1), d.f1.dot(d.f2), d.f1.dot(d.f2), d.f2.dot(d.f2);
  // det C = det Ā⁻¹ |d₁ × d₂|² = (L₁₁L₂₂)² |d₁ × d₂|²: an exactly collinear triangle gives 0.
  const double cross = d1.cross(d2).norm();
  d.det_C = (L11 * L22 * cross) * (L11 * L22 * cross);
  d.collapsed = !(cross > kCollapse * d1.norm() * d2.norm());
  d.W << -L11 - L21, -L22, L11, 0.0, L21, L22;
  return d;
}

// Neo-Hookean in c, with t = tr C, L = ln det C (= tr M, ln det M):
//   ∇t = (1, 1, 0),  ∇L = (C₂₂, C₁₁, −2C₁₂)/det C,
//   ∇²L = H_Δ/det C − ∇L ∇Lᵀ,  H_Δ = ∇²(C₁₁C₂₂ − C₁₂²) = [[0, 1, 0], [1, 0, 0], [0, 0, −2]],
//   ψ = μ/2 (t − 2 − L) + λ/8 L²,
//   ∇ψ = μ/2 (∇t − ∇L) + λ/4 L ∇L,
//   ∇²ψ = (λ/4 L − μ/2) ∇²L + λ/4 ∇L ∇Lᵀ.
MetricEnergy neo_hookean_density(const Deformed& d, double mu, double lambda, bool derivatives) {
  MetricEnergy e;
  const double t = d.C.trace();
  const double L = std::log(d.det_C);
  e.psi = 0.5 * mu * (t - 2.0 - L) + 0.125 * lambda * L * L;
  if (!derivatives) return e;
  const Eigen::Vector3d dL = Eigen::Vector3d(d.C(1, 1), d.C(0, 0), -2.0 * d.C(0, 1)) / d.det_C;
  Eigen::Matrix3d H_det;
  H_det << 0, 1, 0, 1, 0, 0, 0, 0, -2;
  const Eigen::Matrix3d ddL = H_det / d.det_C - dL * dL.transpose();
  e.g = 0.5 * mu * (Eigen::Vector3d(1.0, 1.0, 0.0) - dL) + 0.25 * lambda * L * dL;
  e.H = (0.25 * lambda * L - 0.5 * mu) * ddL + 0.25 * lambda * dL * dL.transpose();
  return e;
}

// St. Venant–Kirchhoff in c, with G = ½ (C − I) (similar to ½ (M − I)):
//   ψ = μ tr(G²) + λ/2 (tr G)² = μ (G₁₁² + G₂₂² + 2G₁₂²) + λ/2 (G₁₁ + G₂₂)²,
//   S = ∂ψ/∂C = μ G + λ/2 (tr G) I,   ∇ψ = (S₁₁, S₂₂, 2S₁₂),
//   d²ψ = μ/2 tr(dC dC) + λ/4 (tr dC)²:  ∇²ψ = μ/2 diag(1, 1, 2) + λ/4 (1, 1, 0)(1, 1, 0)ᵀ.
MetricEnergy stvk_density(const Deformed& d, double mu, double lambda, bool derivatives) {
  MetricEnergy e;
  const Eigen::Matrix2d G = 0.5 * (d.C - Eigen::Matrix2d::Identity());
  const double trG = G.trace();
  e.psi = mu * G.squaredNorm() + 0.5 * lambda * trG * trG;
  if (!derivatives) return e;
  e.g << mu * G(0, 0) + 0.5 * lambda * trG, mu * G(1, 1) + 0.5 * lambda * trG, 2.0 * mu * G(0, 1);
  const Eigen::Vector3d one(1.0, 1.0, 0.0);
  e.H = 0.5 * mu * Eigen::Vector3d(1.0, 1.0, 2.0).asDiagonal();
  e.H += 0.25 * lambda * one * one.transpose();
  return e;
}

/// The chain rule c → (f₁, f₂) → (x0, x1, x2) of the file comment, times `scale` = τ Ā_t.
void to_positions(const Deformed& d, const MetricEnergy& e, double scale, Vector9* g9,
                  Matrix9* H9) {
  const Eigen::Vector3d gf[2] = {2.0 * e.g[0] * d.f1 + e.g[2] * d.f2,   // ∂ψ/∂f₁
                                 2.0 * e.g[1] * d.f2 + e.g[2] * d.f1};  // ∂ψ/∂f₂
  if (g9)
    for (int i = 0; i < 3; ++i)
      g9->segment<3>(3 * i) = scale * (d.W(i, 0) * gf[0] + d.W(i, 1) * gf[1]);
  if (!H9) return;
  Eigen::Matrix<double, 3, 6> J;
  J << 2.0 * d.f1.transpose(), Eigen::RowVector3d::Zero(), Eigen::RowVector3d::Zero(),
      2.0 * d.f2.transpose(), d.f2.transpose(), d.f1.transpose();
  Eigen::Matrix<double, 6, 6> H6 = J.transpose() * e.H * J;
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  H6.block<3, 3>(0, 0) += 2.0 * e.g[0] * I;
  H6.block<3, 3>(3, 3) += 2.0 * e.g[1] * I;
  H6.block<3, 3>(0, 3) += e.g[2] * I;
  H6.block<3, 3>(3, 0) += e.g[2] * I;
  H6 *= scale;
  for (int i = 0; i < 3; ++i) {
    for (int j = i; j < 3; ++j) {
      Eigen::Matrix3d block = Eigen::Matrix3d::Zero();
      for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b) block += (d.W(i, a) * d.W(j, b)) * H6.block<3, 3>(3 * a, 3 * b);
      H9->block<3, 3>(3 * i, 3 * j) = block;
      if (j != i) H9->block<3, 3>(3 * j, 3 * i) = block.transpose();
    }
  }
}

bool finite(const Eigen::Vector3d& x0, const Eigen::Vector3d& x1, const Eigen::Vector3d& x2) {
  return x0.allFinite() && x1.allFinite() && x2.allFinite();
}

/// Evaluates a density at x, applies the chain rule into locals, and writes the outputs only if
/// the energy and every derivative asked for are finite (+infinity otherwise).
template <class Density>
double evaluate(const TriangleRest& rest, const MembraneParameters& params,
                const Eigen::Vector3d& x0, const Eigen::Vector3d& x1, const Eigen::Vector3d& x2,
                bool barrier, Density density, Vector9* grad, Matrix9* hess) {
  double L11 = 0.0, L21 = 0.0, L22 = 0.0;
  if (!finite(x0, x1, x2) || !rest_frame(rest, L11, L21, L22)) return kInfinity;
  const Deformed d = deformed(L11, L21, L22, x0, x1, x2);
  if (barrier && (d.collapsed || !(d.det_C > 0.0))) return kInfinity;
  const double scale = params.thickness * rest.area;
  const MetricEnergy e = density(d, grad || hess);
  const double energy = scale * e.psi;
  if (!std::isfinite(energy)) return kInfinity;
  if (!grad && !hess) return energy;
  Vector9 g;
  Matrix9 H;
  to_positions(d, e, scale, grad ? &g : nullptr, hess ? &H : nullptr);
  if ((grad && !g.allFinite()) || (hess && !H.allFinite())) return kInfinity;
  if (grad) *grad = g;
  if (hess) *hess = H;
  return energy;
}

}  // namespace

// Ā = D̄ᵀD̄ and Ā⁻¹ = adj(Ā)/det Ā with det Ā = |(X1 − X0) × (X2 − X0)|² = (2 Ā_t)².
TriangleRest TriangleRest::from(const Eigen::Vector3d& X0, const Eigen::Vector3d& X1,
                                const Eigen::Vector3d& X2) {
  if (!finite(X0, X1, X2)) throw std::invalid_argument("TriangleRest: rest position is not finite");
  const Eigen::Vector3d E1 = X1 - X0, E2 = X2 - X0;
  const Eigen::Vector3d n = E1.cross(E2);
  const double twice_area = n.norm();
  if (!(twice_area > kCollapse * E1.norm() * E2.norm()))
    throw std::invalid_argument("TriangleRest: degenerate (zero-area) rest triangle");
  const double det = n.squaredNorm();
  TriangleRest r;
  r.metric_inverse << E2.dot(E2), -E1.dot(E2), -E1.dot(E2), E1.dot(E1);
  r.metric_inverse /= det;
  r.area = 0.5 * twice_area;
  if (!r.metric_inverse.allFinite() || !(det > 0.0) || !std::isfinite(r.area))
    throw std::invalid_argument("TriangleRest: rest metric is not invertible in double");
  return r;
}

// τ Ā_t [μ/2 (tr M − 2 − ln det M) + λ/8 ln²(det M)],  M = Ā⁻¹ DᵀD ~ C = FᵀF.
double neo_hookean_membrane(const TriangleRest& rest, const MembraneParameters& params,
                            const Eigen::Vector3d& x0, const Eigen::Vector3d& x1,
                            const Eigen::Vector3d& x2, Vector9* grad, Matrix9* hess) {
  const auto density = [&](const Deformed& d, bool derivatives) {
    return neo_hookean_density(d, params.mu, params.lambda, derivatives);
  };
  return evaluate(rest, params, x0, x1, x2, true, density, grad, hess);
}

// τ Ā_t [μ tr(G²) + λ/2 (tr G)²],  G = ½ (Ā⁻¹ DᵀD − I) ~ ½ (FᵀF − I).
double stvk_membrane(const TriangleRest& rest, const MembraneParameters& params,
                     const Eigen::Vector3d& x0, const Eigen::Vector3d& x1,
                     const Eigen::Vector3d& x2, Vector9* grad, Matrix9* hess) {
  const auto density = [&](const Deformed& d, bool derivatives) {
    return stvk_density(d, params.mu, params.lambda, derivatives);
  };
  return evaluate(rest, params, x0, x1, x2, false, density, grad, hess);
}

}  // namespace mlshell
