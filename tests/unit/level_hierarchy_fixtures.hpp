// A level hierarchy on a cage with an extraordinary vertex, and helpers to apply transfers to
// natural-order data.
#pragma once

#include <memory>
#include <random>
#include <vector>

#include "mlshell/subdivision/level_hierarchy.hpp"
#include "physics_fixtures.hpp"

namespace mlshell {

struct HierarchyFixture {
  SubdivisionHierarchy subdivision;
  std::unique_ptr<LevelHierarchy> levels;

  /// A valence-5 fan cage refined 3 times; levels `coarsest`..3.
  HierarchyFixture(MPI_Comm comm, int coarsest)
      : subdivision(add_ghost_ring(fan_cage(5)), 3),
        levels(std::make_unique<LevelHierarchy>(comm, subdivision, coarsest, 3)) {}

  /// Random natural-order values on level l (identical for any rank count).
  std::vector<double> random(int l, unsigned seed) const {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> d(-1, 1);
    std::vector<double> v(levels->discretization(l).num_dofs());
    for (double& x : v) x = d(rng);
    return v;
  }

  /// y = A x with x on level `from`, y on level `to`, natural order (result on rank 0).
  std::vector<double> apply(Mat A, int from, int to, const std::vector<double>& x) const {
    Vec xv, yv;
    levels->layout(from).create_vector(&xv);
    levels->layout(to).create_vector(&yv);
    levels->layout(from).scatter_natural(
        levels->layout(from).rank() == 0 ? x : std::vector<double>{}, xv);
    MatMult(A, xv, yv);
    std::vector<double> y;
    levels->layout(to).gather_natural(yv, y);
    VecDestroy(&xv);
    VecDestroy(&yv);
    return y;
  }
};

}  // namespace mlshell
