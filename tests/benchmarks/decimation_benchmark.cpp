// Decimation hierarchy on one core (mesh/decimation/decimation.cpp): time to build 4 levels at
// ratio 4 (fine → 1/4 → 1/16 → 1/64 of the vertices), all collapses recorded, every level
// validated, for a structured flat plate of 80,000 and 199,712 faces (criss-cross, no groups: its
// straight sides coarsen too) and an icosphere of 81,920 and 327,680 faces. Goal: 200k faces in
// ≤ 5 s. Counters: fine faces, records, and the seconds of each coarse level (finest-but-one
// first).
//
//   build/tests/benchmarks/decimation_benchmark
#include <benchmark/benchmark.h>

#include "mlshell/decimation/decimation.hpp"
#include "mlshell/triangle/triangle_generators.hpp"

using namespace mlshell;

namespace {

void run(benchmark::State& state, const TriangleMesh& fine) {
  const DecimationOptions options = DecimationOptions::by_ratio(fine.num_points(), 4, 4.0);
  for (auto _ : state) {
    const DecimationHierarchy h = decimate(fine, options);
    benchmark::DoNotOptimize(h.records.data());
    state.counters["fine faces"] = fine.num_triangles();
    state.counters["records"] = static_cast<double>(h.records.size());
    for (int l = 0; l + 1 < h.num_levels(); ++l)
      state.counters["s level " + std::to_string(l)] = h.build_seconds[l];
  }
}

/// n × n cells of the unit square, two triangles each.
void BM_DecimatePlate(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  TriangleMesh fine = make_triangle_rectangle(1.0, 1.0, n, n);
  fine.groups.clear();
  run(state, fine);
}

/// Icosphere of 20·4^s faces.
void BM_DecimateSphere(benchmark::State& state) {
  run(state, make_sphere(1.0, static_cast<int>(state.range(0))));
}

BENCHMARK(BM_DecimatePlate)->Arg(200)->Arg(316)->Unit(benchmark::kMillisecond)->Iterations(1);
BENCHMARK(BM_DecimateSphere)->Arg(6)->Arg(7)->Unit(benchmark::kMillisecond)->Iterations(1);

}  // namespace
