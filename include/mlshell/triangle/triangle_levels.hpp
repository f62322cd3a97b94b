// A triangle-mesh shell as a hierarchy: for now its one level (decimation hierarchies with the
// nonlinear shell prolongation of paper 2 eq. 4–9 come later and add coarser levels here).
#pragma once

#include <memory>

#include "mlshell/levels.hpp"
#include "mlshell/triangle/triangle_discretization.hpp"

namespace mlshell {

class TriangleLevels final : public Levels {
 public:
  /// Partitions the mesh with METIS over the ranks of `comm`.
  TriangleLevels(MPI_Comm comm, TriangleMesh mesh);
  int num_levels() const override { return 1; }
  const TriangleDiscretization& discretization(int) const override { return *disc_; }
  const ParallelLayout& layout(int) const override { return *layout_; }
  /// There is no coarser level yet: always throws std::logic_error.
  const LevelTransfer& transfer(int l) const override;

 private:
  std::unique_ptr<TriangleDiscretization> disc_;
  std::unique_ptr<ParallelLayout> layout_;
};

}  // namespace mlshell
