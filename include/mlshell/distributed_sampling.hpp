// A SurfaceSampling applied to distributed displacements, for writing frames in parallel: the
// sample displacements are W u, with W the sampling's weights as a PETSc matrix (MAIJ over the
// three components) whose rows are the samples in natural order, split into contiguous parts
// over the ranks (each rank samples only its own part where the discretization can). Each rank
// then holds, and writes to the HDF5 file, its own part of the points and cells
// (XdmfSeries::add_frame with a FrameData): nothing is gathered to rank 0, and the datasets are
// the ones a serial run writes.
#pragma once

#include <petscis.h>
#include <petscmat.h>

#include <vector>

#include "mlshell/discretization.hpp"
#include "mlshell/parallel_layout.hpp"

namespace mlshell {

class DistributedSampling {
 public:
  /// `part`: this rank's part of a sampling of the layout's discretization
  /// (Discretization::sampling_part with this rank and the communicator's size). Collective;
  /// throws std::invalid_argument if the parts do not follow each other in rank order.
  DistributedSampling(const SurfaceSampling& part, const ParallelLayout& layout);
  ~DistributedSampling();
  DistributedSampling(const DistributedSampling&) = delete;
  DistributedSampling& operator=(const DistributedSampling&) = delete;

  /// New vectors (block size 3, named "geometry" and "displacement") holding this rank's
  /// slice of the sample points X + W u and of their displacements W u; u is a layout vector.
  PetscErrorCode sample(Vec u, Vec* geometry, Vec* displacement) const;
  /// A new IS (block size cell_size, named "topology") of this rank's slice of the cells.
  PetscErrorCode topology(IS* cells) const;
  int cell_size() const { return cell_size_; }
  /// Cells on all ranks together.
  std::int64_t num_cells() const { return num_cells_; }

 private:
  MPI_Comm comm_;
  Mat weights_ = nullptr, components_ = nullptr;  // W (samples × points) and W ⊗ I₃
  Vec reference_ = nullptr;                       // X, this rank's samples
  std::vector<PetscInt> cells_;                   // this rank's cells
  int cell_size_;
  std::int64_t num_cells_;
};

}  // namespace mlshell
