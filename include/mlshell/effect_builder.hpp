// Builds the energy terms of exactly the effects a scene lists, on one discretization.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <optional>

#include "mlshell/level_problem.hpp"
#include "mlshell/prescribed_motion.hpp"
#include "mlshell/scene.hpp"
#include "mlshell/subdivision/selection.hpp"

namespace mlshell {

/// The elastic term plus one term per scene effect. Throws SceneError for selections that
/// select nothing on this discretization.
///
/// `penalty_mesh_size` is the h of the penalty β = h^-σ (paper eq. 3.6), 0 for disc's own. β is
/// a parameter of the penalised functional ψ̃, not of its discretisation: every level of a
/// hierarchy must use the finest level's h, or the coarse levels minimise a different
/// functional (β_l = h_l^-σ is 2^σ = 32 times softer per level for σ = 5) and RMTR's coarse
/// corrections, which then slide along the boundary, are rejected by the fine level.
///
/// `scale` (PenaltyScale), null for disc's own, is for the same reason the finest level's on
/// every level.
struct PenaltyScale;
std::unique_ptr<LevelProblem> build_level_problem(const Scene& scene,
                                                  const SubdivisionDiscretization& disc,
                                                  const ParallelLayout& layout,
                                                  const CageFrame& frame,
                                                  double penalty_mesh_size = 0.0,
                                                  const PenaltyScale* scale = nullptr);

/// The scales that make the default penalty dimensionally consistent: the membrane stiffness
/// Y·τ of the material (N/m; Y = max(k1, k3) for the woven cloth, E/(1 − ν²) for St.
/// Venant–Kirchhoff) and the size L of the reference surface (m; the largest side of its
/// bounding box, over the corners of the elements; each rank evaluates those of the elements it
/// owns).
struct PenaltyScale {
  double membrane_stiffness = 0.0, length = 0.0;
  static PenaltyScale of(const MaterialSpec& material, const SubdivisionDiscretization& disc,
                         const ParallelLayout& layout);
  /// Yτ of any material model.
  static double membrane_stiffness_of(const MaterialSpec& material);
};

/// Calls `build(effect, name)` for each of the scene's effects in order, which adds the effect's
/// terms to `problem`; tags them with the effect's index (EnergyTerm::effect_index) and prefixes
/// a SceneError it throws with the scene entry, `<file>: effects[i].<name><where>: `.
void add_effect_terms(const Scene& scene, LevelProblem& problem, const std::string& where,
                      const std::function<void(const Effect&, const std::string&)>& build);

/// The placement φ_t of a Dirichlet condition's or clamp's motion at each time t (the identity
/// without one): R(s(t) θ) about the rotation's centre, then the translation s(t) T.
PrescribedMotion motion_function(const std::optional<Motion>& motion);

/// The membrane stiffness of the paper's denim in its stiffer (weft) direction, k3·τ =
/// 9.03 MPa × 0.66 mm: the reference that gives its scenes β = h^-σ.
constexpr double kPaperMembraneStiffness = 9.03e6 * 0.66e-3;

/// β = the explicit penalty, or by default (paper eq. 3.6 made dimensionally consistent)
///   β = (Yτ / Yτ_paper) · (1 m / L) · (h / L)^-σ   [N/m²],
/// which is the paper's h^-σ for its 1 m denim (Yτ = Yτ_paper, L = 1 m) and keeps the ratio of
/// the penalty to the membrane stiffness fixed when a problem is scaled in size or stiffness.
double penalty_parameter(std::optional<double> penalty, double sigma, double mesh_size,
                         const PenaltyScale& scale);

}  // namespace mlshell
