// Distribution of one discretization over MPI ranks.
//
// Geometry and topology are replicated on every rank (they are small next to the matrices);
// work and vectors are distributed. METIS partitions the elements (dual graph of the interior
// faces); a control point belongs to the lowest rank among the elements whose stencils use it,
// and PETSc numbers the points rank by rank, each rank's points in natural order. Every rank
// assembles its own elements into a local (owned + ghost) array and adds it into the global
// vectors with a reverse scatter, and into block-size-3 AIJ matrices with local block indices.
#pragma once

#include <petscmat.h>

#include <array>
#include <memory>
#include <vector>

#include "mlshell/discretization.hpp"
#include "mlshell/vertex_patches.hpp"

namespace mlshell {

class ParallelLayout {
 public:
  /// Partitions the elements with METIS.
  ParallelLayout(MPI_Comm comm, const Discretization& disc);
  /// Uses the given owner rank of every face (only interior faces' owners matter), e.g. owners
  /// inherited from a finer level so that transfers between levels stay mostly on-rank.
  ParallelLayout(MPI_Comm comm, const Discretization& disc, std::vector<int> face_owner);
  ~ParallelLayout();
  ParallelLayout(const ParallelLayout&) = delete;
  ParallelLayout& operator=(const ParallelLayout&) = delete;

  MPI_Comm comm() const { return comm_; }
  int rank() const { return rank_; }
  int size() const { return size_; }
  /// Elements (natural face indices) this rank assembles, and the owner of any face.
  const std::vector<int>& local_elements() const { return local_elements_; }
  int face_owner(int face) const { return face_owner_[face]; }
  const std::vector<int>& face_owners() const { return face_owner_; }
  /// First PETSc block index owned by this rank.
  int first_owned() const { return first_owned_; }
  /// Local points: owned ones first (PETSc order), then ghosts. Natural indices.
  const std::vector<int>& local_points() const { return local_points_; }
  int num_local_points() const { return static_cast<int>(local_points_.size()); }
  int num_owned_points() const { return num_owned_; }
  /// Local index of a natural point index, or -1 if the point is not local.
  int local_of(int natural) const { return local_of_natural_[natural]; }
  int petsc_of(int natural) const { return petsc_of_natural_[natural]; }

  /// A global vector of displacements (block size 3, PETSc order).
  PetscErrorCode create_vector(Vec* v) const;
  /// A block-size-3 AIJ matrix preallocated for the element stencils and the given extra
  /// point pairs (natural indices, coupled both ways; each rank needs those with an end among its
  /// own points, and may give only those), local-to-global mapping set, with the six
  /// rigid-body modes as near-nullspace (for algebraic multigrid) and the vertex patches (for
  /// PC "vpatch").
  PetscErrorCode create_matrix(Mat* A, const std::vector<std::array<int, 2>>& extra = {}) const;
  /// A scalar AIJ matrix over the points with the element-stencil pattern of create_matrix (one
  /// entry per block, element_matrix_assembly.hpp), local-to-global mapping set: for M in
  /// H += M ⊗ I₃ (add_point_matrix).
  PetscErrorCode create_point_matrix(Mat* M) const;
  /// The vertex patches of the owned points (vertex_patches.hpp); built on first use.
  std::shared_ptr<const VertexPatches> vertex_patches() const;
  /// Reference coordinates of the owned points (block size 3), e.g. for rigid-body modes.
  PetscErrorCode create_coordinates(Vec* x) const;
  /// Global → local (owned + ghost) values.
  PetscErrorCode to_local(Vec global, std::vector<double>& local) const;
  /// Adds local values into a global vector (ADD_VALUES; the global vector is not zeroed).
  PetscErrorCode add_to_global(const std::vector<double>& local, Vec global) const;
  /// All values in natural order on rank 0 (empty on other ranks).
  PetscErrorCode gather_natural(Vec global, std::vector<double>& natural) const;
  /// Sets a global vector from natural-order values given on rank 0.
  PetscErrorCode scatter_natural(const std::vector<double>& natural, Vec global) const;

 private:
  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  const Discretization& disc_;
  std::vector<int> face_owner_, local_elements_, local_points_, local_of_natural_,
      petsc_of_natural_;
  int num_owned_ = 0, first_owned_ = 0;
  ISLocalToGlobalMapping l2g_ = nullptr;
  Vec local_work_ = nullptr, global_template_ = nullptr, natural_work_ = nullptr;
  VecScatter to_local_ = nullptr, to_natural_ = nullptr;
  mutable std::shared_ptr<const VertexPatches> patches_;
  /// The block columns of each owned row for the last `extra` given to create_matrix (every
  /// level makes several matrices of one pattern: Hessians, the mass matrix).
  struct BlockPattern {
    std::vector<std::array<int, 2>> extra;
    std::vector<std::vector<int>> columns;
    /// For each ghost point (local index − owned points), the sorted global block columns its
    /// row gets from this rank's own elements and `extra` pairs: what add_element_matrix
    /// gathers here and sends to the row's owner at assembly.
    std::vector<std::vector<int>> ghost_columns;
  };
  mutable std::shared_ptr<const BlockPattern> pattern_;
  /// The first matrix made with the current pattern (a reference: it may outlive its maker);
  /// create_matrix duplicates its structure.
  mutable Mat first_matrix_ = nullptr;
  mutable std::shared_ptr<const BlockPattern> first_pattern_;
  std::shared_ptr<const BlockPattern> block_pattern(
      const std::vector<std::array<int, 2>>& extra) const;
};

}  // namespace mlshell
