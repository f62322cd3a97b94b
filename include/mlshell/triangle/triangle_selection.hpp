// Resolving a scene's `where:` selections on a triangle mesh: curve selections become vertex
// sets (with the boundary edges among them), point selections the nearest vertex.
//   boundary            every boundary vertex          boundary(loop k)  one boundary loop
//   boundary(<side>)    a side of a generated rectangle (within 1e-9 of its size)
//   {box: ...}          every vertex in the box (interior ones too)
//   group(name)         an OBJ `g name` group
//   {at: [x, y, z]}, corner(...), point(u, v)   the nearest vertex
#pragma once

#include <array>
#include <string>
#include <vector>

#include "mlshell/scene.hpp"
#include "mlshell/subdivision/selection.hpp"
#include "mlshell/triangle/triangle_discretization.hpp"

namespace mlshell {

/// Sorted vertex indices; throws SceneError naming `where` if the selection is empty.
std::vector<int> select_vertices(const TriangleDiscretization& disc, const CurveSelection& sel,
                                 const CageFrame& frame, const std::string& where);

/// The nearest vertex to the selected point.
int select_vertex(const TriangleDiscretization& disc, const PointSelection& sel,
                  const CageFrame& frame, const std::string& where);

/// Boundary edges (v0 → v1 in their triangle's direction) whose two vertices are selected.
std::vector<std::array<int, 2>> selected_boundary_edges(const TriangleDiscretization& disc,
                                                        const std::vector<int>& vertices);

}  // namespace mlshell
