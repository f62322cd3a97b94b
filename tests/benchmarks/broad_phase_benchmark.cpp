// Contact broad phase on one core (src/contact/broad_phase/): the spatial hash against the BVH on
// three stacked rippled sheets of 92 × 92 cells (50,784 faces, 76,452 edges; 1 m squares 4 mm
// apart, rippled ±1.5 mm, so the layers come within 1 mm), for
//   Proximity  the barrier's candidates within δ = 1 mm at the current positions;
//   Swept      CCD's candidates along a step that moves each layer by (±2, ∓1, ∓3) mm, δ = 0.1 mm.
// Each time includes building the boxes and the structure and sorting the candidates.
// Counters: point–triangle and edge–edge candidates.
//
//   build/tests/benchmarks/broad_phase_benchmark
#include <benchmark/benchmark.h>

#include "../unit/contact/stacked_sheets.hpp"
#include "mlshell/contact/broad_phase/broad_phase.hpp"

using namespace mlshell;

namespace {

const test::SheetScene& scene() {
  static const test::SheetScene s = test::stacked_sheets(3, 92, 4e-3, 1.5e-3);
  return s;
}

void count(benchmark::State& state, const ContactCandidates& c) {
  state.counters["point-triangle"] = static_cast<double>(c.point_triangle.size());
  state.counters["edge-edge"] = static_cast<double>(c.edge_edge.size());
}

void BM_Proximity(benchmark::State& state) {
  const auto method = static_cast<BroadPhaseMethod>(state.range(0));
  ContactCandidates c;
  for (auto _ : state) {
    c = find_proximity_candidates(scene().surface, scene().x, 1e-3, method);
    benchmark::DoNotOptimize(c.point_triangle.data());
  }
  count(state, c);
}

void BM_Swept(benchmark::State& state) {
  const auto method = static_cast<BroadPhaseMethod>(state.range(0));
  std::vector<Eigen::Vector3d> x1 = scene().x;
  const int per_layer = 93 * 93;
  for (std::size_t i = 0; i < x1.size(); ++i) {
    const double sign = (i / per_layer) % 2 == 0 ? 1.0 : -1.0;
    x1[i] += sign * Eigen::Vector3d(2e-3, -1e-3, -3e-3);
  }
  ContactCandidates c;
  for (auto _ : state) {
    c = find_swept_candidates(scene().surface, scene().x, x1, 1e-4, method);
    benchmark::DoNotOptimize(c.point_triangle.data());
  }
  count(state, c);
}

// Argument: 0 the spatial hash, 1 the BVH (BroadPhaseMethod's order).
BENCHMARK(BM_Proximity)->ArgName("bvh")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Swept)->ArgName("bvh")->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace
