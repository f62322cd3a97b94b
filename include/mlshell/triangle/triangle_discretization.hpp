// An unstructured triangle mesh as one level of a shell (paper 2 §3): the vertices carry the
// dofs, the triangles are the elements (membrane), and the interior edges are the hinges
// (bending) whose four vertices couple two neighbouring triangles. A triangle's stencil is
// therefore its own three vertices and the vertex opposite each of its edges: every hinge lies
// in the stencil of both of its triangles, so whichever rank owns a hinge's first triangle has
// all of the hinge's vertices.
#pragma once

#include <memory>
#include <vector>

#include "mlshell/discretization.hpp"
#include "mlshell/triangle/triangle_mesh.hpp"

namespace mlshell {

class TriangleDiscretization final : public Discretization {
 public:
  /// `mesh` must pass validate_triangle_mesh.
  explicit TriangleDiscretization(TriangleMesh mesh);

  std::string kind() const override { return "triangle"; }
  int num_points() const override { return mesh_.num_points(); }
  const std::vector<Point3>& points() const override { return mesh_.points; }
  int num_faces() const override { return mesh_.num_triangles(); }
  const std::vector<int>& elements() const override { return elements_; }
  std::vector<int> stencil(int face) const override { return stencils_[face]; }
  std::vector<int> corners(int face) const override {
    const Triangle& t = mesh_.triangles[face];
    return {t.begin(), t.end()};
  }
  std::vector<int> neighbours(int face) const override;
  std::vector<std::vector<int>> boundary_loops() const override {
    return topology_->boundary_loops();
  }
  /// Mean edge length.
  double mesh_size() const override { return mesh_size_; }
  /// The mesh itself, displaced (`samples` is ignored: the elements are flat).
  std::unique_ptr<SurfaceSampling> sampling(int samples) const override;

  const TriangleMesh& mesh() const { return mesh_; }
  const TriangleTopology& topology() const { return *topology_; }

 private:
  TriangleMesh mesh_;
  std::unique_ptr<TriangleTopology> topology_;
  std::vector<int> elements_;
  std::vector<std::vector<int>> stencils_;
  double mesh_size_ = 0.0;
};

}  // namespace mlshell
