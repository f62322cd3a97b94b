// The single level of a triangle-mesh shell (see triangle_levels.hpp).
#include "mlshell/triangle/triangle_levels.hpp"

#include <stdexcept>

namespace mlshell {

TriangleLevels::TriangleLevels(MPI_Comm comm, TriangleMesh mesh)
    : disc_(std::make_unique<TriangleDiscretization>(std::move(mesh))),
      layout_(std::make_unique<ParallelLayout>(comm, *disc_)) {}

const LevelTransfer& TriangleLevels::transfer(int) const {
  throw std::logic_error("a triangle-mesh shell has one level: no transfers (yet)");
}

}  // namespace mlshell
