// What a failed step says: the scene's energy scale, which bounds how far a solve's energy may
// fall before mlshell calls the problem unbounded (StepSolver::set_energy_scale), and the likely
// causes and remedies of a failed step, named from what the scene has.
//
// Energy scale (J), for any units and size:
//   S = Y τ A                                  membrane: the elastic energy of unit strain
//     + (Σ|F|) ℓ                               the loads' work over a distance ℓ
//     + p A ℓ                                  the pressure's work, likewise
//   A: reference surface area; Y: Young's modulus (Clyde: the largest k_j); τ: thickness;
//   Σ|F| = ρ|g|A (gravity) + |f|A (surface) + |f|ℓ (line) + |F| (point);
//   ℓ = L + D + (inertia) ½ (Σ|F| / ρA) T²: the size L of the surface (its bounding-box
//   diagonal), plus the largest prescribed motion D (Motion::reach of radius L: |T| plus the
//   chord 2L|sin(θ/2)| of a rotation), plus the distance the loads alone could
//   carry the shell in the scene's time T = steps × dt.
#pragma once

#include <string>

#include "mlshell/discretization.hpp"
#include "mlshell/scene.hpp"

namespace mlshell {

struct EnergyScale {
  double elastic = 0.0;   ///< Y τ A
  double loads = 0.0;     ///< (Σ|F|) ℓ of gravity, surface, line and point loads
  double pressure = 0.0;  ///< p A ℓ
  double total() const { return elastic + loads + pressure; }
  /// "membrane Y*tau*A 6.3e+01 J, pressure p*A*l 4.4e+04 J" (the nonzero parts).
  std::string describe() const;
};

/// The energy scale of `scene` on a surface of reference area `area` (m²) and size `size` (m).
EnergyScale energy_scale(const Scene& scene, double area, double size);

/// The reference area of the elements' corner polygons (m²): the triangles of a triangle mesh,
/// the control polygons of a subdivision surface's elements (close to its limit surface's).
double reference_area(const Discretization& disc);
/// The diagonal of the reference points' bounding box (m).
double reference_size(const Discretization& disc);

/// Likely causes of a solve whose energy fell without bound, one "  - ...\n" line each, naming
/// only what the scene has (never empty).
std::string unbounded_energy_causes(const Scene& scene);
/// Remedies for a step that did not converge, as "more iterations (-tao_max_it), another
/// solver (-tao_type) or ...": a step size only where it matters (inertia: dt; quasistatic
/// ramps or motions: load steps), and the scene's own likely causes. `snes`: SNES options.
std::string not_converged_remedies(const Scene& scene, bool snes);

}  // namespace mlshell
