// The limit surface sampled on a (k+1)×(k+1) grid per element, for output (ParaView, OBJ).
#pragma once

#include <vector>

#include "mlshell/discretization.hpp"
#include "mlshell/output_files.hpp"

namespace mlshell {

class SurfaceSampler {
 public:
  SurfaceSampler(const Discretization& disc, int samples_per_face);
  /// Points of the deformed limit surface for natural-order displacements `u` (3 per control
  /// point; empty: the reference surface), with their displacements and the grid's quads.
  SurfaceSample sample(const std::vector<double>& u) const;

 private:
  const Discretization& disc_;
  std::vector<PointBasis> basis_;
  std::vector<std::int64_t> quads_;
};

}  // namespace mlshell
