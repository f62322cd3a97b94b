// What the solvers, the parallel layout, the time stepper and the output see of one level of a
// shell, whatever its kind: points that carry three displacement dofs each, elements whose
// energies couple the points of their stencils, the adjacency of the elements (for METIS), the
// boundary, a mesh size h, and the deformed surface sampled for output.
//
// Implementations: SubdivisionDiscretization (Catmull–Clark limit surfaces, paper 1; points are
// control points, elements the interior faces of the cage) and TriangleDiscretization
// (unstructured triangle meshes, paper 2; points are vertices, elements the triangles).
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "mlshell/mesh_error.hpp"

namespace mlshell {

/// A surface sampled for output: points (3 per point), their displacements, and cells of
/// `cell_size` point indices (4: quadrilaterals, 3: triangles).
struct SurfaceSample {
  std::vector<double> points;
  std::vector<std::int64_t> cells;
  std::vector<double> displacement;
  int cell_size = 4;
  /// Scalar fields per cell (name, one value per cell), e.g. a triangle's membrane strain.
  std::vector<std::pair<std::string, std::vector<double>>> cell_data;
  std::int64_t num_points() const { return static_cast<std::int64_t>(points.size() / 3); }
  std::int64_t num_cells() const { return static_cast<std::int64_t>(cells.size()) / cell_size; }
};

/// The deformed surface of one discretization at fixed sample points, each a fixed linear
/// combination of the control points: sample s lies at X_s + Σ_k w_k u_{n_k}, k over
/// [offsets[s], offsets[s + 1]) of `nodes` (natural point indices) and `weights`. Being linear,
/// it is also a matrix, which the parallel frame writer applies to distributed displacements
/// (DistributedSampling).
/// Where a sampling lies in the whole it may be a part of (Discretization::sampling_part): its
/// points are points first_point, … of the whole's total_points, its cells likewise, and its
/// cells hold the whole's point indices. A whole sampling: 0 and its own counts (−1 here).
struct SamplingPlace {
  std::int64_t first_point = 0, total_points = -1, first_cell = 0, total_cells = -1;
};

class SurfaceSampling {
 public:
  using Place = SamplingPlace;
  /// reference: 3 coordinates per sample; offsets: one more than samples, from 0; cells:
  /// cell_size sample indices each. Throws std::invalid_argument on inconsistent sizes.
  SurfaceSampling(std::vector<double> reference, std::vector<std::int64_t> offsets,
                  std::vector<int> nodes, std::vector<double> weights,
                  std::vector<std::int64_t> cells, int cell_size, Place place = {});
  /// Slice i of n of this whole sampling: contiguous ranges of its points and of its cells,
  /// split as PetscSplitOwnership splits (the first n mod size slices one longer).
  std::unique_ptr<SurfaceSampling> slice(int i, int n) const;
  const Place& place() const { return place_; }
  /// The deformed surface for natural-order displacements `u` (3 per point; empty: the
  /// reference surface).
  SurfaceSample sample(const std::vector<double>& u) const;
  std::int64_t num_points() const { return static_cast<std::int64_t>(offsets_.size()) - 1; }
  std::int64_t num_cells() const { return static_cast<std::int64_t>(cells_.size()) / cell_size_; }
  int cell_size() const { return cell_size_; }
  const std::vector<double>& reference() const { return reference_; }
  const std::vector<std::int64_t>& offsets() const { return offsets_; }
  const std::vector<int>& nodes() const { return nodes_; }
  const std::vector<double>& weights() const { return weights_; }
  const std::vector<std::int64_t>& cells() const { return cells_; }

 private:
  std::vector<double> reference_;
  std::vector<std::int64_t> offsets_;
  std::vector<int> nodes_;
  std::vector<double> weights_;
  std::vector<std::int64_t> cells_;
  int cell_size_;
  Place place_;
};

/// [first, last) of slice i of n over `count` items: PetscSplitOwnership's split.
std::pair<std::int64_t, std::int64_t> slice_range(std::int64_t count, int i, int n);

class Discretization {
 public:
  virtual ~Discretization() = default;
  /// "subdivision" or "triangle", for messages and output.
  virtual std::string kind() const = 0;
  /// Points carrying the dofs and their reference positions (natural order).
  virtual int num_points() const = 0;
  int num_dofs() const { return 3 * num_points(); }
  virtual const std::vector<Point3>& points() const = 0;
  /// Face indices run over 0..num_faces() − 1; the elements are the faces that carry energy
  /// (a subdivision level's ghost faces do not).
  virtual int num_faces() const = 0;
  virtual const std::vector<int>& elements() const = 0;
  /// Points whose dofs the energy of an element depends on (its Hessian couples them all).
  virtual std::vector<int> stencil(int face) const = 0;
  /// Points that take the rank of this element (its corners): ownership follows the elements.
  virtual std::vector<int> corners(int face) const = 0;
  /// Elements sharing an edge with an element: the dual graph that METIS partitions.
  virtual std::vector<int> neighbours(int face) const = 0;
  /// The boundary of the simulated surface as closed loops of points, each ordered along the
  /// boundary; empty for a closed surface.
  virtual std::vector<std::vector<int>> boundary_loops() const = 0;
  /// The h of the penalty β = h^-σ and of tolerances: the mean element edge length (m).
  virtual double mesh_size() const = 0;
  /// Sampling of the surface for output, `samples` per element edge (ignored by kinds whose
  /// elements are flat): one watertight surface, every point once.
  virtual std::unique_ptr<SurfaceSampling> sampling(int samples) const = 0;
  /// Part i of n of a sampling of the surface, what rank i of n writes of each frame
  /// (DistributedSampling): the same points and cells as sampling(samples) has, in the same
  /// order, cut into contiguous parts. Kinds that can sample a part alone override it.
  virtual std::unique_ptr<SurfaceSampling> sampling_part(int samples, int i, int n) const {
    return sampling(samples)->slice(i, n);
  }
  /// Each element sampled on its own, points shared by elements repeated: the rows of
  /// -mlshell_limit_csv, which the accuracy study integrates element by element. Kinds whose
  /// elements are flat: sampling(samples).
  virtual std::unique_ptr<SurfaceSampling> element_sampling(int samples) const {
    return sampling(samples);
  }
};

/// 64-bit fingerprint of a discretization (point count and reference coordinates), for
/// checkpoints.
std::uint64_t discretization_fingerprint(const Discretization& disc);

}  // namespace mlshell
