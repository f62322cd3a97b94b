// Vertex patches of a level: for every point a rank owns, the point and its neighbours across
// the faces around it (a Catmull–Clark control point's 3×3 block of control points, ghosts
// included; a triangle vertex's one-ring). Every member is a local point of the rank
// (ParallelLayout makes those no local element reaches ghosts), so the patches, and the
// smoother, do not depend on the partition. They are the
// subdomains of the vertex-patch smoother (PC "vpatch", vertex_patch_pc.hpp): the near-null
// modes of thin shells that point smoothers cannot reduce and the coarse levels cannot
// represent (boundary slopes against the ghost ring, inextensional bending) are local to such
// patches (Arnold, Falk and Winther 2000 for the analogous H(div) case; Schöberl's patch
// smoothers for thin structures).
//
// A matrix made by ParallelLayout::create_matrix carries its layout's patches, so that the PC
// can find them from the operator alone (attach_vertex_patches / vertex_patches_of).
#pragma once

#include <petscmat.h>

#include <memory>
#include <vector>

namespace mlshell {

struct VertexPatches {
  /// PETSc block (point) index of each local point of the rank, owned ones first.
  std::vector<PetscInt> blocks;
  /// One patch per owned point: local point indices (into `blocks`), the centre first.
  std::vector<std::vector<int>> patches;
};

/// Attaches `patches` to `A` (shared, kept alive by the matrix).
PetscErrorCode attach_vertex_patches(Mat A, std::shared_ptr<const VertexPatches> patches);
/// The patches attached to `A`, or null if none were.
PetscErrorCode vertex_patches_of(Mat A, const VertexPatches** patches);
/// Attaches the patches of `from` (if it has any) to `to` as well: a matrix on the same layout
/// with another pattern (e.g. a proxy energy's Galerkin Hessian).
PetscErrorCode share_vertex_patches(Mat from, Mat to);

}  // namespace mlshell
