// The limit surface sampled on a k×k grid of quadrilaterals per element, for output (ParaView,
// OBJ, limit_surface.csv).
#pragma once

#include <memory>

#include "mlshell/subdivision/subdivision_discretization.hpp"

namespace mlshell {

/// The elements' k×k grids as one watertight surface: every sample point once (corners and
/// edges shared by elements are not repeated; V + E(k−1) + F(k−1)² points over the elements'
/// V vertices, E edges and F faces) with its limit basis, and k² quadrilaterals per element (in
/// element order, u fastest). Of part `part` of `parts` of the elements (split as slice_range
/// splits) only: the points those elements own and their cells, a slice of the whole sampling.
std::unique_ptr<SurfaceSampling> sample_limit_surface(const SubdivisionDiscretization& disc,
                                                      int samples_per_face, int part = 0,
                                                      int parts = 1);

/// Each element's own (k+1)² grid points (in element order, u fastest), shared points repeated,
/// and its k² quadrilaterals: the rows of -mlshell_limit_csv, which the accuracy study
/// integrates element by element.
std::unique_ptr<SurfaceSampling> sample_element_grids(const SubdivisionDiscretization& disc,
                                                      int samples_per_face);

}  // namespace mlshell
