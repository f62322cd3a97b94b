// The subdivision frames' surface (sample_limit_surface) is watertight: every sample point once,
// V + E(k−1) + F(k−1)² of them, each cell at its element's own grid points, every interior cell
// edge shared by two cells in opposite directions and the boundary's k cell edges per element
// edge; on a cage with an extraordinary vertex of valence 3, 5 and 8 and on an L-shape, and the
// same surface when two ranks write it.
#include "mlshell/subdivision/surface_sampler.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <set>
#include <string>

#include "mlshell/distributed_sampling.hpp"
#include "physics_fixtures.hpp"

using namespace mlshell;

namespace {

/// Pairs of sample points closer than `tol`.
int coincident_points(const std::vector<double>& x, double tol) {
  std::vector<std::size_t> order(x.size() / 3);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return x[3 * a] < x[3 * b]; });
  int pairs = 0;
  for (std::size_t i = 0; i < order.size(); ++i)
    for (std::size_t j = i + 1; j < order.size() && x[3 * order[j]] - x[3 * order[i]] < tol; ++j) {
      const double* a = &x[3 * order[i]];
      const double* b = &x[3 * order[j]];
      pairs += std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]) < tol;
    }
  return pairs;
}

/// Checks the frame surface of `disc` with k × k cells per element.
void expect_watertight(const SubdivisionDiscretization& disc, int k, const std::string& name) {
  SCOPED_TRACE(name + ", k = " + std::to_string(k));
  const auto sampling = disc.sampling(k);
  const SurfaceSample s = sampling->sample({});
  const double h = disc.mesh_size();
  // V + E(k−1) + F(k−1)² points over the elements' vertices, edges and faces.
  std::set<int> vertices;
  std::set<std::pair<int, int>> edges;
  for (int f : disc.elements()) {
    const Quad& q = disc.mesh().quads[f];
    for (int c = 0; c < 4; ++c) {
      vertices.insert(q[c]);
      edges.insert(std::minmax(q[c], q[(c + 1) % 4]));
    }
  }
  const std::int64_t F = disc.elements().size(), E = edges.size(), V = vertices.size();
  EXPECT_EQ(s.num_points(), V + E * (k - 1) + F * (k - 1) * (k - 1));
  EXPECT_EQ(coincident_points(s.points, 1e-6 * h), 0) << "points repeated";
  // Each cell's corners are its element's grid points (one element sampled on its own).
  const SurfaceSample grids = sample_element_grids(disc, k)->sample({});
  ASSERT_EQ(s.num_cells(), F * k * k);
  double off = 0.0;
  for (std::int64_t e = 0; e < F; ++e)
    for (int j = 0; j < k; ++j)
      for (int i = 0; i < k; ++i) {
        const std::int64_t* cell = &s.cells[4 * ((e * k + j) * k + i)];
        const std::int64_t at[4] = {j * (k + 1) + i, j * (k + 1) + i + 1, (j + 1) * (k + 1) + i + 1,
                                    (j + 1) * (k + 1) + i};
        for (int c = 0; c < 4; ++c)
          for (int d = 0; d < 3; ++d)
            off = std::max(off, std::abs(s.points[3 * cell[c] + d] -
                                         grids.points[3 * (e * (k + 1) * (k + 1) + at[c]) + d]));
      }
  EXPECT_LT(off, 1e-10 * h) << "a cell is not at its element's grid points";
  // Every directed cell edge once; an interior one has its reverse, the others are the boundary.
  std::map<std::pair<std::int64_t, std::int64_t>, int> directed;
  for (std::int64_t c = 0; c < s.num_cells(); ++c)
    for (int m = 0; m < 4; ++m) ++directed[{s.cells[4 * c + m], s.cells[4 * c + (m + 1) % 4]}];
  std::int64_t boundary = 0, repeated = 0;
  for (const auto& [edge, count] : directed) {
    repeated += count > 1;
    boundary += !directed.count({edge.second, edge.first});
  }
  EXPECT_EQ(repeated, 0) << "a directed cell edge in two cells";
  EXPECT_EQ(boundary, k * static_cast<std::int64_t>(disc.boundary_edges().size()));
}

SubdivisionDiscretization refined(const QuadMesh& cage, int refine) {
  return SubdivisionDiscretization(SubdivisionHierarchy(cage, refine).finest(), 2);
}

}  // namespace

TEST(SurfaceSampler, RectangleFrameIsWatertight) {
  const auto disc = refined(add_ghost_ring(make_rectangle_cage(1, 0.5, 4, 2, 0, 0)), 1);
  for (int k : {1, 2, 4}) expect_watertight(disc, k, "rectangle");
}

TEST(SurfaceSampler, ExtraordinaryVertexFrameIsWatertight) {
  for (int valence : {3, 5, 8}) {
    const auto disc = refined(add_ghost_ring(fan_cage(valence)), 1);
    for (int k : {1, 3}) expect_watertight(disc, k, "valence " + std::to_string(valence));
  }
  // The extraordinary vertex one edge from the boundary.
  expect_watertight(refined(add_ghost_ring(fan_cage(5, true)), 1), 3, "valence 5 near boundary");
}

TEST(SurfaceSampler, LShapeFrameIsWatertight) {
  const auto disc = refined(add_ghost_ring(make_l_shape_cage(1, 1, 5, 5, 0.4, 0.4, 0, 0)), 0);
  for (int k : {2, 4}) expect_watertight(disc, k, "L-shape");
}

TEST(SurfaceSampler, ElementGridsRepeatSharedPoints) {
  // -mlshell_limit_csv's rows: (k+1)² points per element, shared ones repeated.
  const auto disc = refined(add_ghost_ring(fan_cage(5)), 1);
  const auto grids = sample_element_grids(disc, 2);
  EXPECT_EQ(grids->num_points(), 9 * static_cast<std::int64_t>(disc.elements().size()));
  EXPECT_EQ(grids->num_points(), disc.element_sampling(2)->num_points());
  EXPECT_LT(disc.sampling(2)->num_points(), grids->num_points());
}

TEST(MpiSurfaceSampler, TwoRanksWriteTheSerialSurface) {
  // Each rank samples its elements' points alone (sampling_part); together, in rank order,
  // they are the serial surface: the same points and the same cells, bit for bit.
  int size;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  ASSERT_GE(size, 2) << "run under mpiexec -n 2";
  TestProblem tp("extraordinary", PETSC_COMM_WORLD);
  const int k = 3;
  DistributedSampling distributed(*tp.disc->sampling_part(k, tp.layout->rank(), size), *tp.layout);
  Vec u, geometry, displacement;
  tp.layout->create_vector(&u);
  VecSet(u, 0.0);
  ASSERT_EQ(distributed.sample(u, &geometry, &displacement), 0);
  IS cells, all_cells;
  ASSERT_EQ(distributed.topology(&cells), 0);
  Vec gathered;
  VecScatter to_zero;
  VecScatterCreateToZero(geometry, &to_zero, &gathered);
  VecScatterBegin(to_zero, geometry, gathered, INSERT_VALUES, SCATTER_FORWARD);
  VecScatterEnd(to_zero, geometry, gathered, INSERT_VALUES, SCATTER_FORWARD);
  ISAllGather(cells, &all_cells);
  if (tp.layout->rank() == 0) {
    const auto serial = tp.disc->sampling(k);
    PetscInt n;
    const PetscScalar* x;
    VecGetLocalSize(gathered, &n);
    VecGetArrayRead(gathered, &x);
    EXPECT_EQ(std::vector<double>(x, x + n), serial->reference());
    VecRestoreArrayRead(gathered, &x);
    const PetscInt* c;
    ISGetLocalSize(all_cells, &n);
    ISGetIndices(all_cells, &c);
    EXPECT_EQ(std::vector<std::int64_t>(c, c + n), serial->cells());
    ISRestoreIndices(all_cells, &c);
  }
  VecScatterDestroy(&to_zero);
  VecDestroy(&gathered);
  ISDestroy(&all_cells);
  ISDestroy(&cells);
  VecDestroy(&geometry);
  VecDestroy(&displacement);
  VecDestroy(&u);
}
