// Hyperelastic energy densities ψ(Ẽ) of the shell material, as functions of the reduced
// Green–Lagrange strain Ẽ = Oᵀ E O in the orthonormal material frame (o1 = warp, o2 = weft).
// Strain vector order: (Ẽ11, Ẽ22, Ẽ12) with tensor (not engineering) shear Ẽ12.
#pragma once

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <memory>
#include <vector>

#include "mlshell/scene.hpp"
#include "mlshell/shell/response_function.hpp"

namespace mlshell {

using Strain3 = Eigen::Vector3d;

/// Where one material point's strain lies in a fitted model (end-of-step reports).
struct MaterialPointStatus {
  bool beyond_fit = false;        ///< an argument of some φ_j lies in its continuation
  bool coupling_limited = false;  ///< the coupling limit changed the energy here
};

/// Counts over material points (every Gauss point in the plane and through the thickness).
struct MaterialReport {
  long points = 0;
  long beyond_fit = 0;                   ///< points with an argument in a φ_j continuation
  long coupling_limited = 0;             ///< points where the coupling limit acts
  long negative = 0;                     ///< points with ψ < 0
  double min_energy_density = INFINITY;  ///< min ψ (Pa)
  void add(const MaterialPointStatus& s, double psi) {
    ++points;
    beyond_fit += s.beyond_fit;
    coupling_limited += s.coupling_limited;
    negative += psi < 0.0;
    if (psi < min_energy_density) min_energy_density = psi;
  }
};

class Material {
 public:
  virtual ~Material() = default;
  /// ψ (Pa) at strain e; fills ∂ψ/∂e and ∂²ψ/∂e² when the pointers are non-null. Finite and C²
  /// for every finite strain.
  virtual double energy_density(const Strain3& e, Eigen::Vector3d* grad,
                                Eigen::Matrix3d* hess) const = 0;
  virtual MaterialPointStatus status(const Strain3& e) const { return {}; }
  /// Rounding errors in ψ, in units of ε ψ: more than 1 where ψ is a sum of large terms of
  /// both signs (the mu of Table 1 reach 4,618 for φ'(0) = 1). Used for the error estimate of f.
  virtual double rounding_factor() const { return 1.0; }
};

/// Orthotropic woven-cloth material of Clyde, Teran and Tamstorf (paper eq. 3.3):
///   ψ = A + C + B + k4 φ4(Ẽ12²),  A = k1/2 φ1(Ẽ11²),  B = k3/2 φ3(Ẽ22²),  C = k2 φ2(Ẽ11 Ẽ22),
/// with the response functions φ_j of eq. (3.4), continued beyond their fitted range
/// (response_function.hpp).
///
/// Coupling limit. Table 1's fit, completed with Σ_i μ_ji = 1, is not positive: φ1' and φ3'
/// soften to about 0.35 by 3 % strain while C = k2 Ẽ11 Ẽ22 stays bilinear, so ψ has a negative
/// well (ψ_min = −0.0205 MPa near Ẽ = (±0.115, ∓0.11, 0); free cloth collapses into it). With
/// the limit enabled (preset `denim`), C is replaced by C·s(ρ), where
///   ρ = |C| / (θ_b 2√(AB)) = k2 |φ2(w)/w| / (θ_b √(k1 k3 r1(u1) r3(u3))),   r_j(u) = φ_j(u)/u,
/// (u1 = Ẽ11², u3 = Ẽ22², w = Ẽ11 Ẽ22; the second form is smooth where Ẽ11 or Ẽ22 vanishes), and
///   s = 1 for ρ ≤ x0 = θ_o/θ_b,  s = [x0 + (1 − x0) tanh((ρ − x0)/(1 − x0))] / ρ beyond,
/// which is C² at ρ = x0. Hence |C s| < θ_b 2√(AB) and, by Cauchy–Schwarz,
///   ψ ≥ (1 − θ_b)(A + B) + k4 φ4 > 0 for every Ẽ ≠ 0.
/// The coupling vanishes when Ẽ11 or Ẽ22 does, so the uniaxial warp, weft and shear responses
/// are exactly Table 1's, and at small strain ρ = k2/(θ_b √(k1 k3)) = 0.763 < x0 = 0.833 for
/// denim (θ_o = 0.75, θ_b = 0.9), so the tangent at Ẽ = 0 is Table 1's too.
class ClydeOrthotropicMaterial final : public Material {
 public:
  /// Throws std::invalid_argument if a φ_j cannot be continued (ResponseFunction).
  explicit ClydeOrthotropicMaterial(const ClydeMaterial& p);
  double energy_density(const Strain3& e, Eigen::Vector3d* grad,
                        Eigen::Matrix3d* hess) const override;
  MaterialPointStatus status(const Strain3& e) const override;
  /// max_j Σ_i |μ_ji| / φ_j'(0): the cancellation in φ_j at small strain.
  double rounding_factor() const override;
  /// φ_j (j = 0..3 for φ1..φ4), as used (continued).
  const ResponseFunction& phi(int j) const { return phi_[j]; }

 private:
  /// The coupling factor s(ρ) with its gradient and Hessian in (Ẽ11, Ẽ22), given φ1(Ẽ11²),
  /// φ2(Ẽ11 Ẽ22), φ3(Ẽ22²); false if s = 1.
  bool coupling_factor(double e11, double e22, const PhiValue p[3], double& s, Eigen::Vector2d& ds,
                       Eigen::Matrix2d& dds, bool derivatives) const;
  ClydeMaterial p_;
  std::vector<ResponseFunction> phi_;
};

/// Isotropic St. Venant–Kirchhoff in plane stress:
///   ψ = E/(2(1−ν²)) [ (1−ν) Ẽ:Ẽ + ν (tr Ẽ)² ].
class IsotropicSvkMaterial final : public Material {
 public:
  IsotropicSvkMaterial(double youngs_modulus, double poisson_ratio);
  double energy_density(const Strain3& e, Eigen::Vector3d* grad,
                        Eigen::Matrix3d* hess) const override;

 private:
  Eigen::Matrix3d C_;  // ψ = ½ eᵀ C e with e = (Ẽ11, Ẽ22, Ẽ12)
};

std::unique_ptr<Material> make_material(const MaterialSpec& spec);

}  // namespace mlshell
