// The exact intersection audit (issue 47; paper 2 §3, footnote 1: no preview or result ever
// interpenetrates): which triangles of a surface, or of two surfaces, intersect, decided with
// CGAL's exact predicates (Polygon_mesh_processing::self_intersections), not with a tolerance.
// Triangles that share a vertex or an edge of the mesh count only where they meet beyond it.
// Every written frame of a contact scene is audited (and any scene's with
// -mlshell_audit_intersections); so is the input.
#pragma once

#include <array>
#include <vector>

#include "mlshell/triangle/triangle_mesh.hpp"

namespace mlshell {

struct IntersectionReport {
  long pairs = 0;                             ///< intersecting triangle pairs
  std::vector<std::array<int, 2>> examples;   ///< the first few, as triangle indices
};

/// The triangles of one surface (`triangles` over `points`) that intersect each other.
IntersectionReport self_intersections(const std::vector<Point3>& points,
                                      const std::vector<Triangle>& triangles,
                                      int max_examples = 5);

/// The triangles of surface a that intersect triangles of surface b (no shared vertices);
/// examples are (a's triangle, b's triangle).
IntersectionReport intersections_between(const std::vector<Point3>& points_a,
                                         const std::vector<Triangle>& triangles_a,
                                         const std::vector<Point3>& points_b,
                                         const std::vector<Triangle>& triangles_b,
                                         int max_examples = 5);

}  // namespace mlshell
