// The limit surface sampled on a (k+1)×(k+1) grid per element, for output (ParaView, OBJ).
#pragma once

#include <memory>

#include "mlshell/subdivision/subdivision_discretization.hpp"

namespace mlshell {

/// Each element's (k+1)² grid points (in element order, u fastest) with their limit basis, and
/// the grid's k² quadrilaterals per element; of part `part` of `parts` of the elements (split
/// as slice_range splits) only, a slice of the whole sampling.
std::unique_ptr<SurfaceSampling> sample_limit_surface(const SubdivisionDiscretization& disc,
                                                      int samples_per_face, int part = 0,
                                                      int parts = 1);

}  // namespace mlshell
