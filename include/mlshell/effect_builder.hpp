// Builds the energy terms of exactly the effects a scene lists, on one discretization.
#pragma once

#include <memory>

#include "mlshell/level_problem.hpp"
#include "mlshell/scene.hpp"
#include "mlshell/selection.hpp"

namespace mlshell {

/// The elastic term plus one term per scene effect. Throws SceneError for selections that
/// select nothing on this discretization.
std::unique_ptr<LevelProblem> build_level_problem(const Scene& scene, const Discretization& disc,
                                                  const ParallelLayout& layout,
                                                  const CageFrame& frame);

/// β = explicit penalty or h^-σ.
double penalty_parameter(std::optional<double> penalty, double sigma, double mesh_size);

}  // namespace mlshell
