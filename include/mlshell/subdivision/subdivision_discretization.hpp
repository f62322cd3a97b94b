// Subdivision finite elements on one level (paper §5.2): the interior faces of a control mesh
// are the elements, their one-rings the element stencils, and the limit-surface basis at Gauss
// points is precomputed once (regular faces share a single table).
#pragma once

#include <memory>
#include <vector>

#include "mlshell/discretization.hpp"
#include "mlshell/subdivision/limit_basis.hpp"
#include "mlshell/subdivision/quad_mesh.hpp"

namespace mlshell {

/// Gauss–Legendre rule on [0, 1].
struct GaussRule {
  std::vector<double> points, weights;
  explicit GaussRule(int n);
};

/// Basis of one element at its quadrature points: w[(g * 6 + d) * size + i] is derivative slot d
/// (BasisDerivative) of node i at quadrature point g.
struct ElementBasis {
  const int* nodes = nullptr;
  int size = 0;
  const double* w = nullptr;
  double at(int g, int d, int i) const { return w[(g * 6 + d) * size + i]; }
  const double* slot(int g, int d) const { return w + (g * 6 + d) * size; }
};

/// Edge k (corner k → k+1) of an interior face that lies on the domain boundary.
struct BoundaryEdge {
  int face = -1;
  int edge = 0;
};

class SubdivisionDiscretization final : public Discretization {
 public:
  /// `mesh`: a level with interior faces and ghost ring; `gauss` points per direction (2..6).
  SubdivisionDiscretization(QuadMesh mesh, int gauss);

  // Discretization
  std::string kind() const override { return "subdivision"; }
  int num_points() const override { return mesh_.num_points(); }
  const std::vector<Point3>& points() const override { return mesh_.points; }
  int num_faces() const override { return mesh_.num_faces(); }
  /// Interior faces, i.e. the finite elements.
  const std::vector<int>& elements() const override { return elements_; }
  /// Control points of the element stencil of a face.
  std::vector<int> stencil(int face) const override;
  std::vector<int> corners(int face) const override {
    const Quad& q = mesh_.quads[face];
    return {q.begin(), q.end()};
  }
  /// Interior faces across the face's edges.
  std::vector<int> neighbours(int face) const override;
  /// Corner control points of the interior faces along the domain boundary (they lie on the
  /// control polygon of the boundary curve, not on the limit surface).
  std::vector<std::vector<int>> boundary_loops() const override;
  /// Mean length of the interior faces' edges (the h of β = h^-σ).
  double mesh_size() const override { return mesh_size_; }
  /// The limit surface on a samples × samples grid of quadrilaterals per element, points shared
  /// by elements once (sample_limit_surface).
  std::unique_ptr<SurfaceSampling> sampling(int samples) const override;
  /// The elements of part i of n and the points they own, sampled alone.
  std::unique_ptr<SurfaceSampling> sampling_part(int samples, int i, int n) const override;
  /// A (samples+1)² grid per element (sample_element_grids).
  std::unique_ptr<SurfaceSampling> element_sampling(int samples) const override;

  const QuadMesh& mesh() const { return mesh_; }
  const LimitEvaluator& evaluator() const { return *evaluator_; }
  const GaussRule& gauss() const { return gauss_; }
  /// Tensor quadrature on [0,1]²: point g = (points[g % n], points[g / n]).
  int num_quadrature_points() const { return gauss_n_ * gauss_n_; }
  SurfacePoint quadrature_point(int face, int g) const;
  double quadrature_weight(int g) const;
  ElementBasis element_basis(int face) const;
  const std::vector<BoundaryEdge>& boundary_edges() const { return boundary_edges_; }
  /// Point at parameter s ∈ [0,1] along a boundary edge, and the face parameter direction that
  /// crosses the edge (kDu or kDv).
  SurfacePoint edge_point(const BoundaryEdge& e, double s) const;

 private:
  QuadMesh mesh_;
  std::unique_ptr<LimitEvaluator> evaluator_;
  GaussRule gauss_;
  int gauss_n_;
  std::vector<int> elements_;
  std::vector<BoundaryEdge> boundary_edges_;
  std::vector<int> across_;  // 4 per face: the interior face across edge k, or -1
  double mesh_size_ = 0.0;
  std::vector<double> regular_table_;  // [g][6][16]
  struct Irregular {
    std::vector<int> nodes;
    std::vector<double> w;
  };
  std::vector<int> irregular_index_;  // per face, -1 if regular
  std::vector<Irregular> irregular_;
};

}  // namespace mlshell
