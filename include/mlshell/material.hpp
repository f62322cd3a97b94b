// Hyperelastic energy densities ψ(Ẽ) of the shell material, as functions of the reduced
// Green–Lagrange strain Ẽ = Oᵀ E O in the orthonormal material frame (o1 = warp, o2 = weft).
// Strain vector order: (Ẽ11, Ẽ22, Ẽ12) with tensor (not engineering) shear Ẽ12.
#pragma once

#include <Eigen/Core>
#include <array>
#include <memory>

#include "mlshell/scene.hpp"

namespace mlshell {

using Strain3 = Eigen::Vector3d;

class Material {
 public:
  virtual ~Material() = default;
  /// ψ (Pa) at strain e; fills ∂ψ/∂e and ∂²ψ/∂e² when the pointers are non-null.
  virtual double energy_density(const Strain3& e, Eigen::Vector3d* grad,
                                Eigen::Matrix3d* hess) const = 0;
};

/// Orthotropic woven-cloth material of Clyde, Teran and Tamstorf (paper eq. 3.3–3.4):
///   ψ = k1/2 φ1(Ẽ11²) + k2 φ2(Ẽ11 Ẽ22) + k3/2 φ3(Ẽ22²) + k4 φ4(Ẽ12²),
///   φ_j(u) = Σ_i μ_ji/α_ji ((u+1)^α_ji − 1).
/// (u+1)^α − 1 is evaluated as expm1(α log1p(u)): the exponents reach −12 802.
///
/// Domain of validity: a fitted φ_j need not be monotone. Table 1's φ_3 (denim weft) has
/// φ_3' < 0 beyond u ≈ 0.10 (|Ẽ22| ≈ 0.32) and φ_3 → −∞, because its largest exponent
/// (α_34 = 30.07) has a negative coefficient. The energy would be unbounded below and a solver
/// can run away into that region. The model is therefore defined only where every φ_j' > 0:
/// u_j ≤ u_j^max, the first zero of φ_j', and where ψ ≥ 0 (the linear φ_2 = Ẽ11 Ẽ22 term lets
/// the fit go negative at large compression-tension strains). Outside, ψ = +∞, so trial points
/// there are rejected (it acts as a strain limit at the edge of the fitted range).
class ClydeOrthotropicMaterial final : public Material {
 public:
  explicit ClydeOrthotropicMaterial(const ClydeMaterial& p);
  /// u_j^max (infinity if φ_j' stays positive).
  double argument_limit(int j) const { return limit_[j]; }
  double energy_density(const Strain3& e, Eigen::Vector3d* grad,
                        Eigen::Matrix3d* hess) const override;
  /// φ_j and its first two derivatives at u.
  void phi(int j, double u, double& f, double& df, double& ddf) const;

 private:
  ClydeMaterial p_;
  std::array<double, 4> limit_;
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
