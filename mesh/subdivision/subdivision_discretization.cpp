// Element stencils and basis tables of one subdivision level.
#include "mlshell/subdivision/subdivision_discretization.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

#include "mlshell/subdivision/surface_sampler.hpp"

namespace mlshell {

GaussRule::GaussRule(int n) {
  // Nodes and weights on [-1, 1], mapped to [0, 1].
  static const std::vector<std::vector<double>> x = {
      {0.0},
      {-0.5773502691896257645, 0.5773502691896257645},
      {-0.7745966692414833770, 0.0, 0.7745966692414833770},
      {-0.8611363115940525752, -0.3399810435848562648, 0.3399810435848562648,
       0.8611363115940525752},
      {-0.9061798459386639928, -0.5384693101056830910, 0.0, 0.5384693101056830910,
       0.9061798459386639928},
      {-0.9324695142031520278, -0.6612093864662645136, -0.2386191860831969086,
       0.2386191860831969086, 0.6612093864662645136, 0.9324695142031520278}};
  static const std::vector<std::vector<double>> w = {
      {2.0},
      {1.0, 1.0},
      {0.5555555555555555556, 0.8888888888888888889, 0.5555555555555555556},
      {0.3478548451374538574, 0.6521451548625461426, 0.6521451548625461426, 0.3478548451374538574},
      {0.2369268850561890875, 0.4786286704993664680, 0.5688888888888888889, 0.4786286704993664680,
       0.2369268850561890875},
      {0.1713244923791703450, 0.3607615730481386076, 0.4679139345726910474, 0.4679139345726910474,
       0.3607615730481386076, 0.1713244923791703450}};
  if (n < 1 || n > 6) throw std::invalid_argument("Gauss rule with 1..6 points only");
  for (int i = 0; i < n; ++i) {
    points.push_back(0.5 * (x[n - 1][i] + 1.0));
    weights.push_back(0.5 * w[n - 1][i]);
  }
}

SubdivisionDiscretization::SubdivisionDiscretization(QuadMesh mesh, int gauss)
    : mesh_(std::move(mesh)),
      gauss_(gauss),
      gauss_n_(gauss),
      irregular_index_(mesh_.num_faces(), -1) {
  if (gauss < 2 || gauss > 6) throw std::invalid_argument("Gauss points per direction: 2..6");
  evaluator_ = std::make_unique<LimitEvaluator>(mesh_);
  const QuadAdjacency adj(mesh_);
  across_.assign(4 * mesh_.num_faces(), -1);
  double edge_sum = 0.0;
  int edge_count = 0;
  for (int f = 0; f < mesh_.num_faces(); ++f) {
    if (mesh_.is_ghost(f)) continue;
    elements_.push_back(f);
    for (int k = 0; k < 4; ++k) {
      const int g = adj.across(f, k);
      if (g < 0 || mesh_.is_ghost(g))
        boundary_edges_.push_back({f, k});
      else
        across_[4 * f + k] = g;
      edge_sum +=
          (mesh_.points[mesh_.quads[f][(k + 1) % 4]] - mesh_.points[mesh_.quads[f][k]]).norm();
      ++edge_count;
    }
  }
  if (elements_.empty()) throw MeshError("the cage has no interior faces");
  mesh_size_ = edge_sum / edge_count;

  const int ng = num_quadrature_points();
  regular_table_.resize(ng * 6 * 16);
  std::array<std::array<double, 16>, 6> w;
  for (int g = 0; g < ng; ++g) {
    bicubic_bspline_basis(gauss_.points[g % gauss_n_], gauss_.points[g / gauss_n_], w);
    for (int d = 0; d < 6; ++d)
      for (int i = 0; i < 16; ++i) regular_table_[(g * 6 + d) * 16 + i] = w[d][i];
  }
  // Faces touching extraordinary vertices: one OpenSubdiv batch for all their Gauss points.
  std::vector<SurfacePoint> points;
  std::vector<int> faces;
  for (int f : elements_)
    if (!evaluator_->is_regular(f)) {
      faces.push_back(f);
      for (int g = 0; g < ng; ++g) points.push_back(quadrature_point(f, g));
    }
  if (faces.empty()) return;
  const auto bases = evaluator_->evaluate(points);
  for (size_t k = 0; k < faces.size(); ++k) {
    // Union of the nodes over the face's Gauss points, then a dense [g][6][n] table.
    Irregular irr;
    for (int g = 0; g < ng; ++g)
      for (int node : bases[k * ng + g].nodes)
        if (std::find(irr.nodes.begin(), irr.nodes.end(), node) == irr.nodes.end())
          irr.nodes.push_back(node);
    const int n = static_cast<int>(irr.nodes.size());
    irr.w.assign(ng * 6 * n, 0.0);
    for (int g = 0; g < ng; ++g) {
      const PointBasis& b = bases[k * ng + g];
      for (int i = 0; i < b.size(); ++i) {
        const int slot = static_cast<int>(
            std::find(irr.nodes.begin(), irr.nodes.end(), b.nodes[i]) - irr.nodes.begin());
        for (int d = 0; d < 6; ++d) irr.w[(g * 6 + d) * n + slot] = b.w[d][i];
      }
    }
    irregular_index_[faces[k]] = static_cast<int>(irregular_.size());
    irregular_.push_back(std::move(irr));
  }
}

SurfacePoint SubdivisionDiscretization::quadrature_point(int face, int g) const {
  return {face, gauss_.points[g % gauss_n_], gauss_.points[g / gauss_n_]};
}

double SubdivisionDiscretization::quadrature_weight(int g) const {
  return gauss_.weights[g % gauss_n_] * gauss_.weights[g / gauss_n_];
}

ElementBasis SubdivisionDiscretization::element_basis(int face) const {
  const int k = irregular_index_[face];
  if (k < 0) return {evaluator_->regular_nodes(face).data(), 16, regular_table_.data()};
  const Irregular& irr = irregular_[k];
  return {irr.nodes.data(), static_cast<int>(irr.nodes.size()), irr.w.data()};
}

std::vector<int> SubdivisionDiscretization::stencil(int face) const {
  const ElementBasis b = element_basis(face);
  return {b.nodes, b.nodes + b.size};
}

std::vector<int> SubdivisionDiscretization::neighbours(int face) const {
  std::vector<int> out;
  for (int k = 0; k < 4; ++k)
    if (across_[4 * face + k] >= 0) out.push_back(across_[4 * face + k]);
  return out;
}

std::vector<std::vector<int>> SubdivisionDiscretization::boundary_loops() const {
  // Each boundary edge runs from corner k to corner k+1 of its face; chain them head to tail.
  std::map<int, int> next;
  for (const BoundaryEdge& e : boundary_edges_)
    next[mesh_.quads[e.face][e.edge]] = mesh_.quads[e.face][(e.edge + 1) % 4];
  std::vector<std::vector<int>> loops;
  while (!next.empty()) {
    std::vector<int> loop{next.begin()->first};
    for (auto it = next.find(loop.back()); it != next.end(); it = next.find(loop.back())) {
      const int to = it->second;
      next.erase(it);
      if (to == loop.front()) break;
      loop.push_back(to);
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

std::unique_ptr<SurfaceSampling> SubdivisionDiscretization::sampling(int samples) const {
  return sample_limit_surface(*this, samples);
}

std::unique_ptr<SurfaceSampling> SubdivisionDiscretization::sampling_part(int samples, int i,
                                                                          int n) const {
  return sample_limit_surface(*this, samples, i, n);
}

std::unique_ptr<SurfaceSampling> SubdivisionDiscretization::element_sampling(int samples) const {
  return sample_element_grids(*this, samples);
}

SurfacePoint SubdivisionDiscretization::edge_point(const BoundaryEdge& e, double s) const {
  // Corners 0..3 sit at (0,0), (1,0), (1,1), (0,1); edge k runs from corner k to corner k+1.
  switch (e.edge) {
    case 0:
      return {e.face, s, 0.0};
    case 1:
      return {e.face, 1.0, s};
    case 2:
      return {e.face, 1.0 - s, 1.0};
    default:
      return {e.face, 0.0, 1.0 - s};
  }
}

}  // namespace mlshell
