// Sampling distributed displacements for parallel frame output (see distributed_sampling.hpp).
#include "mlshell/distributed_sampling.hpp"

#include <algorithm>
#include <utility>
#include <vector>

namespace mlshell {

namespace {

/// [begin, end) of this rank's share of n items split into contiguous slices (PETSc's split).
void slice_of(MPI_Comm comm, PetscInt n, PetscInt* begin, PetscInt* end) {
  PetscInt local = PETSC_DECIDE;
  PetscCallAbort(comm, PetscSplitOwnership(comm, &local, &n));
  PetscInt last;
  MPI_Scan(&local, &last, 1, MPIU_INT, MPI_SUM, comm);
  *begin = last - local;
  *end = last;
}

}  // namespace

DistributedSampling::DistributedSampling(const SurfaceSampling& sampling,
                                         const ParallelLayout& layout)
    : comm_(layout.comm()), cell_size_(sampling.cell_size()), num_cells_(sampling.num_cells()) {
  PetscInt first, last;
  slice_of(comm_, static_cast<PetscInt>(sampling.num_points()), &first, &last);
  const PetscInt rows = last - first, owned = layout.num_owned_points();
  const auto& offsets = sampling.offsets();
  const auto& nodes = sampling.nodes();
  const auto& w = sampling.weights();
  // This rank's rows of W as CSR (columns sorted, repeated nodes merged), handed over whole.
  std::vector<PetscInt> ia(rows + 1, 0), ja;
  std::vector<PetscScalar> va;
  std::vector<std::pair<PetscInt, double>> row;
  for (PetscInt s = first; s < last; ++s) {
    row.clear();
    for (std::int64_t k = offsets[s]; k < offsets[s + 1]; ++k)
      row.emplace_back(layout.petsc_of(nodes[k]), w[k]);
    std::sort(row.begin(), row.end());
    for (std::size_t k = 0; k < row.size(); ++k) {
      if (k > 0 && row[k].first == row[k - 1].first) {
        va.back() += row[k].second;
        continue;
      }
      ja.push_back(row[k].first);
      va.push_back(row[k].second);
    }
    ia[s - first + 1] = static_cast<PetscInt>(ja.size());
  }
  PetscCallAbort(comm_, MatCreate(comm_, &weights_));
  PetscCallAbort(comm_, MatSetSizes(weights_, rows, owned, PETSC_DETERMINE, PETSC_DETERMINE));
  PetscCallAbort(comm_, MatSetType(weights_, MATAIJ));
  PetscCallAbort(comm_, MatSeqAIJSetPreallocationCSR(weights_, ia.data(), ja.data(), va.data()));
  PetscCallAbort(comm_, MatMPIAIJSetPreallocationCSR(weights_, ia.data(), ja.data(), va.data()));
  PetscCallAbort(comm_, MatCreateMAIJ(weights_, 3, &components_));

  PetscCallAbort(comm_, VecCreate(comm_, &reference_));
  PetscCallAbort(comm_, VecSetSizes(reference_, 3 * rows, PETSC_DETERMINE));
  PetscCallAbort(comm_, VecSetBlockSize(reference_, 3));
  PetscCallAbort(comm_, VecSetType(reference_, VECSTANDARD));
  PetscScalar* x;
  PetscCallAbort(comm_, VecGetArray(reference_, &x));
  std::copy(sampling.reference().begin() + 3 * first, sampling.reference().begin() + 3 * last, x);
  PetscCallAbort(comm_, VecRestoreArray(reference_, &x));

  PetscInt cell_first, cell_last;
  slice_of(comm_, static_cast<PetscInt>(sampling.num_cells()), &cell_first, &cell_last);
  cells_.assign(sampling.cells().begin() + cell_size_ * cell_first,
                sampling.cells().begin() + cell_size_ * cell_last);
}

DistributedSampling::~DistributedSampling() {
  MatDestroy(&components_);
  MatDestroy(&weights_);
  VecDestroy(&reference_);
}

PetscErrorCode DistributedSampling::sample(Vec u, Vec* geometry, Vec* displacement) const {
  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(reference_, displacement));
  PetscCall(VecDuplicate(reference_, geometry));
  PetscCall(MatMult(components_, u, *displacement));
  PetscCall(VecWAXPY(*geometry, 1.0, reference_, *displacement));
  PetscCall(PetscObjectSetName((PetscObject)*geometry, "geometry"));
  PetscCall(PetscObjectSetName((PetscObject)*displacement, "displacement"));
  PetscFunctionReturn(0);
}

PetscErrorCode DistributedSampling::topology(IS* cells) const {
  PetscFunctionBeginUser;
  PetscCall(ISCreateGeneral(comm_, static_cast<PetscInt>(cells_.size()), cells_.data(),
                            PETSC_COPY_VALUES, cells));
  PetscCall(ISSetBlockSize(*cells, cell_size_));
  PetscCall(PetscObjectSetName((PetscObject)*cells, "topology"));
  PetscFunctionReturn(0);
}

}  // namespace mlshell
