// Isotropic St. Venant–Kirchhoff material in plane stress (for verification against plate
// theory), and the material factory.
#include "mlshell/shell/material.hpp"

namespace mlshell {

IsotropicSvkMaterial::IsotropicSvkMaterial(double E, double nu) {
  // ψ = c [ (1−ν)(e11² + e22² + 2 e12²) + ν (e11 + e22)² ],  c = E / (2(1−ν²)).
  const double c = E / (2.0 * (1.0 - nu * nu));
  C_ << 2.0 * c, 2.0 * c * nu, 0.0,  //
      2.0 * c * nu, 2.0 * c, 0.0,    //
      0.0, 0.0, 4.0 * c * (1.0 - nu);
}

double IsotropicSvkMaterial::energy_density(const Strain3& e, Eigen::Vector3d* grad,
                                            Eigen::Matrix3d* hess) const {
  const Eigen::Vector3d s = C_ * e;
  if (grad) *grad = s;
  if (hess) *hess = C_;
  return 0.5 * e.dot(s);
}

std::unique_ptr<Material> make_material(const MaterialSpec& spec) {
  if (const auto* c = std::get_if<ClydeMaterial>(&spec.model))
    return std::make_unique<ClydeOrthotropicMaterial>(*c);
  const auto& s = std::get<SvkMaterial>(spec.model);
  return std::make_unique<IsotropicSvkMaterial>(s.youngs_modulus, s.poisson_ratio);
}

}  // namespace mlshell
