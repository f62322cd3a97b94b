// PC "vpatch": additive Schwarz over the vertex patches of a level (vertex_patches.hpp) with
// exact, dense patch solves. As the preconditioner of Steihaug–Toint CG it is the smoother of
// RMTR's scalable configuration (`-tao_rmtr_smoother_pc vpatch`, petsc-options/rmtr-patch.yaml):
// no factorisation above the coarsest level, V-cycles independent of the resolution. Any KSP
// may use it (-pc_type vpatch) on a matrix made by ParallelLayout::create_matrix.
//
//   M⁻¹ r = Σ_i R_iᵀ |A_i|⁻¹ R_i r   (formula and positivity: vertex_patch_pc.cpp)
//
// Cost per setup: one dense Cholesky factorisation of 3k × 3k per owned point (k = 9 control
// points of a regular Catmull–Clark patch, 7 vertices of a regular triangle one-ring): linear in
// the number of points, as is its memory (the packed factor, 3k(3k + 1)/2 doubles per point).
#pragma once

#include <petscpc.h>

namespace mlshell {

/// Registers the PC type "vpatch" with PETSc (idempotent).
PetscErrorCode register_vertex_patch_pc();

}  // namespace mlshell
