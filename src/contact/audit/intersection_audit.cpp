// CGAL's self-intersection test on a Surface_mesh of the given positions (exact predicates,
// inexact constructions: the test needs predicates only). The one translation unit of the
// audit that includes CGAL.
#include "mlshell/contact/audit/intersection_audit.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <iterator>
#include <stdexcept>
#include <string>

namespace mlshell {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Mesh = CGAL::Surface_mesh<Kernel::Point_3>;
using Face = Mesh::Face_index;

/// The surface as a Surface_mesh; `offset` is added to the vertex indices of `triangles`
/// (points already in `mesh` before these).
void add_surface(Mesh& mesh, const std::vector<Point3>& points,
                 const std::vector<Triangle>& triangles) {
  const auto first = static_cast<Mesh::size_type>(mesh.number_of_vertices());
  for (const Point3& p : points) mesh.add_vertex(Kernel::Point_3(p.x(), p.y(), p.z()));
  for (size_t t = 0; t < triangles.size(); ++t) {
    const Triangle& tri = triangles[t];
    const Face f = mesh.add_face(Mesh::Vertex_index(first + tri[0]),
                                 Mesh::Vertex_index(first + tri[1]),
                                 Mesh::Vertex_index(first + tri[2]));
    if (f == Mesh::null_face())
      throw std::invalid_argument("intersection audit: triangle " + std::to_string(t) +
                                  " does not fit a manifold surface");
  }
}

std::vector<std::pair<Face, Face>> intersecting(const Mesh& mesh) {
  std::vector<std::pair<Face, Face>> pairs;
  CGAL::Polygon_mesh_processing::self_intersections(mesh, std::back_inserter(pairs));
  return pairs;
}

}  // namespace

IntersectionReport self_intersections(const std::vector<Point3>& points,
                                      const std::vector<Triangle>& triangles, int max_examples) {
  Mesh mesh;
  add_surface(mesh, points, triangles);
  IntersectionReport report;
  for (const auto& [a, b] : intersecting(mesh)) {
    ++report.pairs;
    if (static_cast<int>(report.examples.size()) < max_examples)
      report.examples.push_back({static_cast<int>(a), static_cast<int>(b)});
  }
  return report;
}

IntersectionReport intersections_between(const std::vector<Point3>& points_a,
                                         const std::vector<Triangle>& triangles_a,
                                         const std::vector<Point3>& points_b,
                                         const std::vector<Triangle>& triangles_b,
                                         int max_examples) {
  // One mesh of both surfaces (faces of a first, Surface_mesh numbers faces in order), pairs
  // with one face of each.
  Mesh mesh;
  add_surface(mesh, points_a, triangles_a);
  add_surface(mesh, points_b, triangles_b);
  const int na = static_cast<int>(triangles_a.size());
  IntersectionReport report;
  for (auto [f, g] : intersecting(mesh)) {
    int a = static_cast<int>(f), b = static_cast<int>(g);
    if ((a < na) == (b < na)) continue;  // within one surface
    if (a >= na) std::swap(a, b);
    ++report.pairs;
    if (static_cast<int>(report.examples.size()) < max_examples)
      report.examples.push_back({a, b - na});
  }
  return report;
}

}  // namespace mlshell
