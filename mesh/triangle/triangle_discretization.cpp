// Stencils, adjacency and output sampling of a triangle-mesh level.
#include "mlshell/triangle/triangle_discretization.hpp"

#include <algorithm>
#include <numeric>

namespace mlshell {


TriangleDiscretization::TriangleDiscretization(TriangleMesh mesh)
    : mesh_(std::move(mesh)), topology_(std::make_unique<TriangleTopology>(mesh_)) {
  elements_.resize(mesh_.num_triangles());
  std::iota(elements_.begin(), elements_.end(), 0);
  stencils_.resize(mesh_.num_triangles());
  for (int f = 0; f < mesh_.num_triangles(); ++f) {
    const Triangle& t = mesh_.triangles[f];
    stencils_[f].assign(t.begin(), t.end());
  }
  for (const Hinge& h : topology_->hinges()) {
    stencils_[h.faces[0]].push_back(h.v[3]);
    stencils_[h.faces[1]].push_back(h.v[2]);
  }
  double sum = 0.0;
  for (const TriangleEdge& e : topology_->edges())
    sum += (mesh_.points[e.v[1]] - mesh_.points[e.v[0]]).norm();
  mesh_size_ = sum / static_cast<double>(topology_->num_edges());
}

std::vector<int> TriangleDiscretization::neighbours(int face) const {
  std::vector<int> out;
  for (int g : topology_->neighbours(face))
    if (g >= 0) out.push_back(g);
  return out;
}

// The mesh with its displacements: one output point per vertex, one cell per triangle.
std::unique_ptr<SurfaceSampling> TriangleDiscretization::sampling(int) const {
  const auto n = static_cast<std::int64_t>(mesh_.points.size());
  std::vector<double> reference;
  std::vector<std::int64_t> offsets(n + 1), cells;
  std::vector<int> nodes(n);
  for (std::int64_t i = 0; i < n; ++i) {
    reference.insert(reference.end(), mesh_.points[i].data(), mesh_.points[i].data() + 3);
    offsets[i + 1] = i + 1;
    nodes[i] = static_cast<int>(i);
  }
  for (const Triangle& t : mesh_.triangles) cells.insert(cells.end(), t.begin(), t.end());
  return std::make_unique<SurfaceSampling>(std::move(reference), std::move(offsets),
                                           std::move(nodes), std::vector<double>(n, 1.0),
                                           std::move(cells), 3);
}

}  // namespace mlshell
