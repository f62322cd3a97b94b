// Hyperelastic energy densities ψ(Ẽ) of the shell material, as functions of the reduced
// Green–Lagrange strain Ẽ = Oᵀ E O in the orthonormal material frame (o1 = warp, o2 = weft).
// Strain vector order: (Ẽ11, Ẽ22, Ẽ12) with tensor (not engineering) shear Ẽ12.
#pragma once

#include <array>
#include <memory>

#include <Eigen/Core>

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
class ClydeOrthotropicMaterial final : public Material {
 public:
  explicit ClydeOrthotropicMaterial(const ClydeMaterial& p) : p_(p) {}
  double energy_density(const Strain3& e, Eigen::Vector3d* grad,
                        Eigen::Matrix3d* hess) const override;
  /// φ_j and its first two derivatives at u.
  void phi(int j, double u, double& f, double& df, double& ddf) const;

 private:
  ClydeMaterial p_;
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
