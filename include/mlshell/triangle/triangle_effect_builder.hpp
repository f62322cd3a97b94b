// Builds the energy terms of exactly the effects a scene lists, on a triangle-mesh level.
#pragma once

#include <memory>

#include "mlshell/level_problem.hpp"
#include "mlshell/scene.hpp"
#include "mlshell/subdivision/selection.hpp"
#include "mlshell/triangle/triangle_discretization.hpp"

namespace mlshell {

/// The elastic term (membrane + hinges), the proximal term of a quasistatic integrator, and one
/// term per scene effect (two for a clamp: its penalty and its hinges). Throws SceneError for
/// selections that select nothing, for pressure on an open surface and for pressure on a closed
/// surface oriented inwards (V(X) ≤ 0). `penalty_h`: the mesh size of the penalties β = h^-σ
/// (0: the mesh's own); a coarse level of a hierarchy takes the finest level's, so that all
/// levels discretise one functional (as subdivision levels do, multilevel_problem.hpp).
std::unique_ptr<LevelProblem> build_triangle_problem(const Scene& scene,
                                                     const TriangleDiscretization& disc,
                                                     const ParallelLayout& layout,
                                                     const CageFrame& frame,
                                                     double penalty_h = 0.0);

/// The triangle mesh of a scene's `geometry: {mesh: ...}`; throws MeshError for a bad mesh.
TriangleMesh build_triangle_mesh(const TriangleMeshSpec& spec);

}  // namespace mlshell
