// METIS partition of the elements and the PETSc objects that move data between ranks.
#include "mlshell/parallel_layout.hpp"

#include <metis.h>

#include <algorithm>
#include <numeric>
#include <set>
#include <stdexcept>

#include "mlshell/element_matrix_assembly.hpp"

namespace mlshell {

namespace {

/// METIS k-way partition of the elements' dual graph (faces sharing an edge).
std::vector<int> partition_elements(const Discretization& disc, int parts) {
  std::vector<int> owner(disc.num_faces(), 0);
  if (parts == 1) return owner;
  const auto& elements = disc.elements();
  std::vector<int> index_of(disc.num_faces(), -1);
  for (size_t e = 0; e < elements.size(); ++e) index_of[elements[e]] = static_cast<int>(e);
  std::vector<idx_t> xadj{0}, adjncy;
  for (int f : elements) {
    for (int g : disc.neighbours(f))
      if (index_of[g] >= 0) adjncy.push_back(index_of[g]);
    xadj.push_back(static_cast<idx_t>(adjncy.size()));
  }
  idx_t n = static_cast<idx_t>(elements.size()), ncon = 1, nparts = parts, objval = 0;
  std::vector<idx_t> part(n, 0);
  idx_t options[METIS_NOPTIONS];
  METIS_SetDefaultOptions(options);
  options[METIS_OPTION_SEED] = 7;  // deterministic partitions
  options[METIS_OPTION_NUMBERING] = 0;
  if (n >= parts) {
    const int status =
        METIS_PartGraphKway(&n, &ncon, xadj.data(), adjncy.data(), nullptr, nullptr, nullptr,
                            &nparts, nullptr, nullptr, options, &objval, part.data());
    if (status != METIS_OK) throw std::runtime_error("METIS failed to partition the elements");
  }
  for (idx_t e = 0; e < n; ++e) owner[elements[e]] = static_cast<int>(part[e]);
  return owner;
}

/// The faces each point is a corner of (every face, the ghost ring's included).
std::vector<std::vector<int>> faces_around_points(const Discretization& disc) {
  std::vector<std::vector<int>> faces_of(disc.num_points());
  for (int f = 0; f < disc.num_faces(); ++f)
    for (int v : disc.corners(f)) faces_of[v].push_back(f);
  return faces_of;
}

}  // namespace

ParallelLayout::ParallelLayout(MPI_Comm comm, const Discretization& disc)
    : ParallelLayout(comm, disc, partition_elements(disc, [comm] {
                       int size;
                       MPI_Comm_size(comm, &size);
                       return size;
                     }())) {}  // METIS gives the same partition on every rank (same input, seed)

ParallelLayout::ParallelLayout(MPI_Comm comm, const Discretization& disc,
                               std::vector<int> face_owner)
    : comm_(comm), disc_(disc), face_owner_(std::move(face_owner)) {
  MPI_Comm_rank(comm, &rank_);
  MPI_Comm_size(comm, &size_);
  const int np = disc.num_points();
  // A point belongs to the lowest rank among the elements it is a corner of, so ownership
  // follows the element partition; points that are corners of no element (the ghost ring) go to
  // the lowest rank whose element stencils use them.
  std::vector<int> point_owner(np, size_), stencil_owner(np, size_);
  std::vector<char> local(np, 0);
  for (int f : disc.elements()) {
    const int r = face_owner_[f];
    for (int v : disc.corners(f)) point_owner[v] = std::min(point_owner[v], r);
    for (int v : disc.stencil(f)) {
      stencil_owner[v] = std::min(stencil_owner[v], r);
      if (r == rank_) local[v] = 1;
    }
    if (r == rank_) local_elements_.push_back(f);
  }
  for (int v = 0; v < np; ++v)
    if (point_owner[v] == size_) point_owner[v] = stencil_owner[v];
  // The vertex patch of an owned point (vertex_patches) is every corner of its faces: ghosts too,
  // where no local element's stencil reaches them (ghost-ring points at the partition's edge), so
  // that the patches, and PC vpatch with them, do not depend on the partition.
  {
    const auto faces_of = faces_around_points(disc);
    for (int v = 0; v < np; ++v)
      if (point_owner[v] == rank_)
        for (int f : faces_of[v])
          for (int w : disc.corners(f)) local[w] = 1;
  }
  // PETSc numbering: rank by rank, natural order within a rank.
  petsc_of_natural_.assign(np, -1);
  int next = 0;
  for (int r = 0; r < size_; ++r) {
    if (r == rank_) first_owned_ = next;
    for (int v = 0; v < np; ++v)
      if (point_owner[v] == r) petsc_of_natural_[v] = next++;
  }
  if (next != np) throw std::logic_error("ParallelLayout: a control point is in no stencil");
  for (int v = 0; v < np; ++v)
    if (point_owner[v] == rank_) local_points_.push_back(v);
  num_owned_ = static_cast<int>(local_points_.size());
  for (int v = 0; v < np; ++v)
    if (local[v] && point_owner[v] != rank_) local_points_.push_back(v);
  local_of_natural_.assign(np, -1);
  for (size_t i = 0; i < local_points_.size(); ++i)
    local_of_natural_[local_points_[i]] = static_cast<int>(i);

  std::vector<PetscInt> blocks(local_points_.size());
  for (size_t i = 0; i < local_points_.size(); ++i) blocks[i] = petsc_of_natural_[local_points_[i]];
  PetscCallAbort(comm, ISLocalToGlobalMappingCreate(comm, 3, static_cast<PetscInt>(blocks.size()),
                                                    blocks.data(), PETSC_COPY_VALUES, &l2g_));
  PetscCallAbort(comm, VecCreateMPI(comm, 3 * num_owned_, PETSC_DETERMINE, &global_template_));
  PetscCallAbort(comm, VecSetBlockSize(global_template_, 3));
  PetscCallAbort(comm, VecCreateSeq(PETSC_COMM_SELF, 3 * num_local_points(), &local_work_));
  IS from;
  PetscCallAbort(comm, ISCreateBlock(PETSC_COMM_SELF, 3, static_cast<PetscInt>(blocks.size()),
                                     blocks.data(), PETSC_COPY_VALUES, &from));
  PetscCallAbort(comm, VecScatterCreate(global_template_, from, local_work_, nullptr, &to_local_));
  PetscCallAbort(comm, ISDestroy(&from));
  // Natural order on rank 0.
  std::vector<PetscInt> natural_blocks;
  if (rank_ == 0) natural_blocks.assign(petsc_of_natural_.begin(), petsc_of_natural_.end());
  PetscCallAbort(comm, VecCreateSeq(PETSC_COMM_SELF, rank_ == 0 ? 3 * np : 0, &natural_work_));
  IS nat;
  PetscCallAbort(comm,
                 ISCreateBlock(PETSC_COMM_SELF, 3, static_cast<PetscInt>(natural_blocks.size()),
                               natural_blocks.data(), PETSC_COPY_VALUES, &nat));
  PetscCallAbort(comm,
                 VecScatterCreate(global_template_, nat, natural_work_, nullptr, &to_natural_));
  PetscCallAbort(comm, ISDestroy(&nat));
}

ParallelLayout::~ParallelLayout() {
  MatDestroy(&first_matrix_);
  ISLocalToGlobalMappingDestroy(&l2g_);
  VecDestroy(&local_work_);
  VecDestroy(&global_template_);
  VecDestroy(&natural_work_);
  VecScatterDestroy(&to_local_);
  VecScatterDestroy(&to_natural_);
}

PetscErrorCode ParallelLayout::create_vector(Vec* v) const {
  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(global_template_, v));
  PetscCall(VecZeroEntries(*v));
  PetscFunctionReturn(0);
}

std::shared_ptr<const ParallelLayout::BlockPattern> ParallelLayout::block_pattern(
    const std::vector<std::array<int, 2>>& extra) const {
  if (pattern_ && pattern_->extra == extra) return pattern_;
  // Block rows owned here: count coupled blocks, on- and off-diagonal, over every element
  // (any rank's) whose stencil contains the row.
  auto p = std::make_shared<BlockPattern>();
  p->extra = extra;
  const int np = disc_.num_points();
  auto& coupled = p->columns;
  coupled.resize(num_owned_);
  std::vector<int> owned_index(np, -1);
  for (int i = 0; i < num_owned_; ++i) owned_index[local_points_[i]] = i;
  // The elements around each owned row (CSR), then each row's distinct stencil points: a
  // point appears in up to 16 stencils around a row, so marking beats sorting the repeats.
  const auto& elements = disc_.elements();
  std::vector<std::vector<int>> stencils(elements.size());
  std::vector<int> start(num_owned_ + 1, 0), around;
  for (size_t e = 0; e < elements.size(); ++e) {
    stencils[e] = disc_.stencil(elements[e]);
    for (int v : stencils[e])
      if (owned_index[v] >= 0) ++start[owned_index[v] + 1];
  }
  for (int i = 0; i < num_owned_; ++i) start[i + 1] += start[i];
  around.resize(start.back());
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (size_t e = 0; e < elements.size(); ++e)
      for (int v : stencils[e])
        if (owned_index[v] >= 0) around[fill[owned_index[v]]++] = static_cast<int>(e);
  }
  std::vector<int> seen(np, -1);
  for (int i = 0; i < num_owned_; ++i)
    for (int k = start[i]; k < start[i + 1]; ++k)
      for (int w : stencils[around[k]])
        if (seen[w] != i) {
          seen[w] = i;
          coupled[i].push_back(petsc_of_natural_[w]);
        }
  for (const auto& [a, b] : extra) {
    if (owned_index[a] >= 0) coupled[owned_index[a]].push_back(petsc_of_natural_[b]);
    if (owned_index[b] >= 0) coupled[owned_index[b]].push_back(petsc_of_natural_[a]);
  }
  // Ghost rows: the stencils of the rank's own elements and the extra pairs with a ghost end.
  const int num_local = static_cast<int>(local_points_.size());
  auto& ghost = p->ghost_columns;
  ghost.assign(num_local - num_owned_, {});
  for (int f : local_elements_) {
    const std::vector<int> stencil = disc_.stencil(f);
    for (int v : stencil)
      if (local_of_natural_[v] >= num_owned_)
        for (int w : stencil)
          ghost[local_of_natural_[v] - num_owned_].push_back(petsc_of_natural_[w]);
  }
  for (const auto& [a, b] : extra)
    if (local_of_natural_[a] >= 0 && local_of_natural_[b] >= 0) {
      if (local_of_natural_[a] >= num_owned_)
        ghost[local_of_natural_[a] - num_owned_].push_back(petsc_of_natural_[b]);
      if (local_of_natural_[b] >= num_owned_)
        ghost[local_of_natural_[b] - num_owned_].push_back(petsc_of_natural_[a]);
    }
  for (auto* rows : {&coupled, &ghost})
    for (auto& c : *rows) {
      std::sort(c.begin(), c.end());
      c.erase(std::unique(c.begin(), c.end()), c.end());
    }
  pattern_ = std::move(p);
  return pattern_;
}

PetscErrorCode ParallelLayout::create_matrix(Mat* A,
                                             const std::vector<std::array<int, 2>>& extra) const {
  PetscFunctionBeginUser;
  const auto pattern = block_pattern(extra);
  // Collective: the extra pairs may be each rank's own (a rank's rows only), so one rank may
  // still have the earlier pattern while another does not.
  int same = first_matrix_ && first_pattern_ == pattern;
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &same, 1, MPI_INT, MPI_LAND, comm_));
  const bool duplicate = same;
  if (duplicate) {
    // The pattern of an earlier matrix: PETSc 3.18's SeqAIJ copies its row and column indices
    // (MAT_SHARE_NONZERO_PATTERN or not), which is still cheaper than building them.
    PetscCall(MatDuplicate(first_matrix_, MAT_SHARE_NONZERO_PATTERN, A));
    PetscCall(MatZeroEntries(*A));
    PetscCall(attach_block_columns(*A, vertex_patches()->blocks, pattern->ghost_columns));
  } else {
    // Every element block is in the pattern from the start: add_element_matrix's fast path.
    PetscCall(create_prefilled_block_matrix(comm_, first_owned_, pattern->columns,
                                            vertex_patches()->blocks, pattern->ghost_columns, A));
  }
  PetscCall(MatSetLocalToGlobalMapping(*A, l2g_, l2g_));
  PetscCall(MatSetOption(*A, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  PetscCall(MatSetOption(*A, MAT_SYMMETRIC, PETSC_TRUE));
  PetscCall(MatSetOption(*A, MAT_SYMMETRY_ETERNAL, PETSC_TRUE));
  Vec coordinates;
  MatNullSpace rigid;
  PetscCall(create_coordinates(&coordinates));
  PetscCall(MatNullSpaceCreateRigidBody(coordinates, &rigid));
  PetscCall(MatSetNearNullSpace(*A, rigid));
  PetscCall(MatNullSpaceDestroy(&rigid));
  PetscCall(VecDestroy(&coordinates));
  PetscCall(attach_vertex_patches(*A, vertex_patches()));
  if (!duplicate) {
    // Later matrices of this pattern duplicate this one's structure.
    PetscCall(MatDestroy(&first_matrix_));
    PetscCall(PetscObjectReference((PetscObject)*A));
    first_matrix_ = *A;
    first_pattern_ = pattern;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ParallelLayout::create_point_matrix(Mat* M) const {
  PetscFunctionBeginUser;
  PetscCall(create_prefilled_point_matrix(comm_, first_owned_, block_pattern({})->columns, M));
  const auto& blocks = vertex_patches()->blocks;  // PETSc point index of each local point
  ISLocalToGlobalMapping l2g;
  PetscCall(ISLocalToGlobalMappingCreate(comm_, 1, static_cast<PetscInt>(blocks.size()),
                                         blocks.data(), PETSC_COPY_VALUES, &l2g));
  PetscCall(MatSetLocalToGlobalMapping(*M, l2g, l2g));
  PetscCall(ISLocalToGlobalMappingDestroy(&l2g));
  PetscCall(MatSetOption(*M, MAT_NEW_NONZERO_ALLOCATION_ERR, PETSC_TRUE));
  PetscFunctionReturn(0);
}

// Neighbours across the faces around a point: the corners of every face (ghost faces
// included) that has the point as a corner.
std::shared_ptr<const VertexPatches> ParallelLayout::vertex_patches() const {
  if (patches_) return patches_;
  auto p = std::make_shared<VertexPatches>();
  p->blocks.resize(local_points_.size());
  for (size_t i = 0; i < local_points_.size(); ++i)
    p->blocks[i] = petsc_of_natural_[local_points_[i]];
  const auto faces_of = faces_around_points(disc_);
  p->patches.resize(num_owned_);
  for (int i = 0; i < num_owned_; ++i) {
    const int v = local_points_[i];
    std::set<int> members;
    for (int f : faces_of[v])
      for (int w : disc_.corners(f))
        if (w != v) members.insert(local_of_natural_[w]);  // local: the constructor sees to it
    p->patches[i].push_back(i);
    p->patches[i].insert(p->patches[i].end(), members.begin(), members.end());
  }
  patches_ = std::move(p);
  return patches_;
}

PetscErrorCode ParallelLayout::create_coordinates(Vec* x) const {
  PetscFunctionBeginUser;
  PetscCall(create_vector(x));
  PetscScalar* a;
  PetscCall(VecGetArray(*x, &a));
  for (int i = 0; i < num_owned_; ++i)
    for (int c = 0; c < 3; ++c) a[3 * i + c] = disc_.points()[local_points_[i]][c];
  PetscCall(VecRestoreArray(*x, &a));
  PetscFunctionReturn(0);
}

PetscErrorCode ParallelLayout::to_local(Vec global, std::vector<double>& local) const {
  PetscFunctionBeginUser;
  PetscCall(VecScatterBegin(to_local_, global, local_work_, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(to_local_, global, local_work_, INSERT_VALUES, SCATTER_FORWARD));
  const PetscScalar* a;
  PetscCall(VecGetArrayRead(local_work_, &a));
  local.assign(a, a + 3 * num_local_points());
  PetscCall(VecRestoreArrayRead(local_work_, &a));
  PetscFunctionReturn(0);
}

PetscErrorCode ParallelLayout::add_to_global(const std::vector<double>& local, Vec global) const {
  PetscFunctionBeginUser;
  PetscScalar* a;
  PetscCall(VecGetArray(local_work_, &a));
  std::copy(local.begin(), local.end(), a);
  PetscCall(VecRestoreArray(local_work_, &a));
  PetscCall(VecScatterBegin(to_local_, local_work_, global, ADD_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(to_local_, local_work_, global, ADD_VALUES, SCATTER_REVERSE));
  PetscFunctionReturn(0);
}

PetscErrorCode ParallelLayout::gather_natural(Vec global, std::vector<double>& natural) const {
  PetscFunctionBeginUser;
  PetscCall(VecScatterBegin(to_natural_, global, natural_work_, INSERT_VALUES, SCATTER_FORWARD));
  PetscCall(VecScatterEnd(to_natural_, global, natural_work_, INSERT_VALUES, SCATTER_FORWARD));
  natural.clear();
  if (rank_ == 0) {
    const PetscScalar* a;
    PetscCall(VecGetArrayRead(natural_work_, &a));
    natural.assign(a, a + 3 * disc_.num_points());
    PetscCall(VecRestoreArrayRead(natural_work_, &a));
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ParallelLayout::scatter_natural(const std::vector<double>& natural,
                                               Vec global) const {
  PetscFunctionBeginUser;
  if (rank_ == 0) {
    PetscCheck(natural.size() == static_cast<size_t>(3 * disc_.num_points()), PETSC_COMM_SELF,
               PETSC_ERR_ARG_SIZ, "natural vector has %zu values, expected %d", natural.size(),
               3 * disc_.num_points());
    PetscScalar* a;
    PetscCall(VecGetArray(natural_work_, &a));
    std::copy(natural.begin(), natural.end(), a);
    PetscCall(VecRestoreArray(natural_work_, &a));
  }
  PetscCall(VecZeroEntries(global));
  PetscCall(VecScatterBegin(to_natural_, natural_work_, global, INSERT_VALUES, SCATTER_REVERSE));
  PetscCall(VecScatterEnd(to_natural_, natural_work_, global, INSERT_VALUES, SCATTER_REVERSE));
  PetscFunctionReturn(0);
}

}  // namespace mlshell
