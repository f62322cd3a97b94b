// Reverse subdivision Q_{l+1}^l (private to mesh/; see SubdivisionHierarchy::reverse_subdivision).
#pragma once

#include <opensubdiv/far/topologyRefiner.h>

#include <vector>

#include "mlshell/subdivision/subdivision_hierarchy.hpp"

namespace mlshell {

/// Q for one refinement: `refiner` holds the coarse kept mesh as level 0 and its uniform
/// refinement as level 1; `fine_kept[i]` is the kept fine index of refined vertex i (or -1).
SubdivisionMatrix build_reverse_subdivision(const OpenSubdiv::Far::TopologyRefiner& refiner,
                                            const QuadMesh& coarse,
                                            const std::vector<int>& fine_kept, int num_fine);

}  // namespace mlshell
