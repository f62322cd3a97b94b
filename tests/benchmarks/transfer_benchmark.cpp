// Level hierarchy on one core: time to build it (subdivision levels, discretizations, layouts,
// S, R = Sᵀ, Q), and apply times of S, R and Q between the two finest levels, for the 4×4
// square refined 5 times (51,483 dofs) and 6 times (201,243 dofs).
//
//   build/tests/benchmarks/transfer_benchmark
#include <benchmark/benchmark.h>
#include <petscsys.h>

#include "mlshell/subdivision/level_hierarchy.hpp"

using namespace mlshell;

namespace {

QuadMesh square() { return add_ghost_ring(make_rectangle_cage(1, 1, 4, 4, 0, 0)); }

void BM_BuildHierarchy(benchmark::State& state) {
  const int refine = static_cast<int>(state.range(0));
  for (auto _ : state) {
    SubdivisionHierarchy sub(square(), refine);
    LevelHierarchy levels(PETSC_COMM_SELF, sub, 0, 3);
    benchmark::DoNotOptimize(levels.num_levels());
    state.counters["finest dofs"] = levels.discretization(levels.finest()).num_dofs();
  }
}

/// op: 0 = S (coarse → fine), 1 = R = Sᵀ formed explicitly (fine → coarse), 2 = Q (fine →
/// coarse), 3 = Sᵀ applied by MatMultTranspose(S) instead of the explicit R.
void BM_ApplyTransfer(benchmark::State& state) {
  const int refine = static_cast<int>(state.range(0)), op = static_cast<int>(state.range(1));
  SubdivisionHierarchy sub(square(), refine);
  LevelHierarchy levels(PETSC_COMM_SELF, sub, refine - 1, 3);
  Mat A = op == 0   ? levels.prolongation(0)
          : op == 1 ? levels.restriction(0)
          : op == 2 ? levels.projection(0)
                    : levels.prolongation(0);
  Vec x, y;
  if (op == 3)
    MatCreateVecs(A, &y, &x);
  else
    MatCreateVecs(A, &x, &y);
  VecSet(x, 1.0);
  for (auto _ : state) {
    if (op == 3)
      MatMultTranspose(A, x, y);
    else
      MatMult(A, x, y);
  }
  const char* labels[] = {"S", "R = S^T (explicit)", "Q", "S^T via MatMultTranspose"};
  state.SetLabel(labels[op]);
  state.counters["fine dofs"] = levels.discretization(1).num_dofs();
  VecDestroy(&x);
  VecDestroy(&y);
}

BENCHMARK(BM_BuildHierarchy)->Arg(5)->Arg(6)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ApplyTransfer)->ArgsProduct({{5, 6}, {0, 1, 2, 3}})->Unit(benchmark::kMicrosecond);

}  // namespace
