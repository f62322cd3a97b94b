// The limit surface sampled on a (k+1)×(k+1) grid per element, for output (ParaView, OBJ).
#pragma once

#include <vector>

#include "mlshell/output_files.hpp"
#include "mlshell/subdivision/subdivision_discretization.hpp"

namespace mlshell {

class SurfaceSampler final : public SurfaceSampling {
 public:
  SurfaceSampler(const SubdivisionDiscretization& disc, int samples_per_face);
  /// Points of the deformed limit surface for natural-order displacements `u` (3 per control
  /// point; empty: the reference surface), with their displacements and the grid's quads.
  SurfaceSample sample(const std::vector<double>& u) const override;

 private:
  const SubdivisionDiscretization& disc_;
  std::vector<PointBasis> basis_;
  std::vector<std::int64_t> cells_;
};

}  // namespace mlshell
