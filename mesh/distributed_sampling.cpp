// Sampling distributed displacements for parallel frame output (see distributed_sampling.hpp).
#include "mlshell/distributed_sampling.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>
#include <vector>

namespace mlshell {

DistributedSampling::DistributedSampling(const SurfaceSampling& part, const ParallelLayout& layout)
    : comm_(layout.comm()), cell_size_(part.cell_size()), num_cells_(part.place().total_cells) {
  // The parts must follow each other in rank order and cover the whole.
  const SurfaceSampling::Place& place = part.place();
  const std::int64_t mine[2] = {part.num_points(), part.num_cells()};
  std::int64_t before[2] = {0, 0};
  MPI_Exscan(mine, before, 2, MPI_INT64_T, MPI_SUM, comm_);
  int rank;
  MPI_Comm_rank(comm_, &rank);
  if (rank == 0) before[0] = before[1] = 0;  // MPI_Exscan leaves rank 0's undefined
  std::int64_t total[2];
  MPI_Allreduce(mine, total, 2, MPI_INT64_T, MPI_SUM, comm_);
  int ok = before[0] == place.first_point && before[1] == place.first_cell &&
           total[0] == place.total_points && total[1] == place.total_cells;
  MPI_Allreduce(MPI_IN_PLACE, &ok, 1, MPI_INT, MPI_LAND, comm_);
  if (!ok)
    throw std::invalid_argument(
        "DistributedSampling: the ranks' sampling parts do not follow each other in rank order");
  const PetscInt rows = static_cast<PetscInt>(part.num_points()), owned = layout.num_owned_points();
  const auto& offsets = part.offsets();
  const auto& nodes = part.nodes();
  const auto& w = part.weights();
  // This rank's rows of W as CSR (columns sorted, repeated nodes merged), handed over whole.
  std::vector<PetscInt> ia(rows + 1, 0), ja;
  std::vector<PetscScalar> va;
  std::vector<std::pair<PetscInt, double>> row;
  for (PetscInt s = 0; s < rows; ++s) {
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
    ia[s + 1] = static_cast<PetscInt>(ja.size());
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
  std::copy(part.reference().begin(), part.reference().end(), x);
  PetscCallAbort(comm_, VecRestoreArray(reference_, &x));
  cells_.assign(part.cells().begin(), part.cells().end());
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
