// Builds the energy terms of exactly the effects a scene lists, on one discretization.
#pragma once

#include <memory>

#include "mlshell/level_problem.hpp"
#include "mlshell/scene.hpp"
#include "mlshell/selection.hpp"

namespace mlshell {

/// The elastic term plus one term per scene effect. Throws SceneError for selections that
/// select nothing on this discretization.
///
/// `penalty_mesh_size` is the h of the penalty β = h^-σ (paper eq. 3.6), 0 for disc's own. β is
/// a parameter of the penalised functional ψ̃, not of its discretisation: every level of a
/// hierarchy must use the finest level's h, or the coarse levels minimise a different
/// functional (β_l = h_l^-σ is 2^σ = 32 times softer per level for σ = 5) and RMTR's coarse
/// corrections, which then slide along the boundary, are rejected by the fine level.
std::unique_ptr<LevelProblem> build_level_problem(const Scene& scene, const Discretization& disc,
                                                  const ParallelLayout& layout,
                                                  const CageFrame& frame,
                                                  double penalty_mesh_size = 0.0);

/// β = explicit penalty or h^-σ.
double penalty_parameter(std::optional<double> penalty, double sigma, double mesh_size);

}  // namespace mlshell
