// Stencils, adjacency and output sampling of a triangle-mesh level.
#include "mlshell/triangle/triangle_discretization.hpp"

#include <algorithm>
#include <numeric>

namespace mlshell {

namespace {

/// The mesh with its displacements: one output point per vertex, one cell per triangle.
class TriangleSampling final : public SurfaceSampling {
 public:
  explicit TriangleSampling(const TriangleMesh& mesh) : mesh_(mesh) {
    for (const Triangle& t : mesh.triangles) cells_.insert(cells_.end(), t.begin(), t.end());
  }
  SurfaceSample sample(const std::vector<double>& u) const override {
    SurfaceSample s;
    s.cell_size = 3;
    s.cells = cells_;
    s.points.reserve(3 * mesh_.points.size());
    s.displacement.assign(3 * mesh_.points.size(), 0.0);
    for (size_t i = 0; i < mesh_.points.size(); ++i)
      for (int c = 0; c < 3; ++c) {
        const double d = u.empty() ? 0.0 : u[3 * i + c];
        s.points.push_back(mesh_.points[i][c] + d);
        s.displacement[3 * i + c] = d;
      }
    return s;
  }

 private:
  const TriangleMesh& mesh_;
  std::vector<std::int64_t> cells_;
};

}  // namespace

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

std::unique_ptr<SurfaceSampling> TriangleDiscretization::sampling(int) const {
  return std::make_unique<TriangleSampling>(mesh_);
}

}  // namespace mlshell
