// Assembly throughput of the shell energy on one core: elements per second for energy only,
// energy + gradient, and energy + gradient + Hessian, for the subdivision shell (denim material,
// 4×4 cage refined 3 times, 3 × 3 Gauss points) and for the triangle shell (neo-Hookean
// membrane + hinge bending, 64 × 64 squares of two triangles: each element is a triangle with
// its share, about 1.5, of the hinges; and the same membrane with midedge bending, one 18-dof
// element per triangle).
//
//   build/tests/benchmarks/assembly_benchmark
#include <benchmark/benchmark.h>
#include <petscsys.h>

#include "mlshell/effects.hpp"
#include "mlshell/subdivision/subdivision_hierarchy.hpp"
#include "mlshell/triangle/triangle_effects.hpp"
#include "mlshell/triangle/triangle_generators.hpp"

using namespace mlshell;

namespace {

struct Fixture {
  SubdivisionDiscretization disc;
  ParallelLayout layout;
  MaterialSpec material;
  std::unique_ptr<ShellElasticTerm> term;
  std::vector<double> u;
  Mat H = nullptr;
  Fixture()
      : disc(
            SubdivisionHierarchy(add_ghost_ring(make_rectangle_cage(1, 1, 4, 4, 0, 0)), 3).finest(),
            3),
        layout(PETSC_COMM_SELF, disc) {
    material.model = denim_preset();
    material.thickness = 0.66e-3;
    material.density = 0.4;
    term = std::make_unique<ShellElasticTerm>(disc, layout, material);
    u.resize(3 * layout.num_local_points());
    for (int i = 0; i < layout.num_local_points(); ++i) {
      const Point3& X = disc.mesh().points[layout.local_points()[i]];
      u[3 * i + 0] = 0.01 * X.x();
      u[3 * i + 2] = 0.05 * std::sin(3 * X.x()) * std::cos(2 * X.y());
    }
    layout.create_matrix(&H);
  }
  ~Fixture() { MatDestroy(&H); }
};

/// Times one evaluation of the fixture's elastic term (with its gradient, with its Hessian).
template <class F>
void run(benchmark::State& state, bool grad, bool hess) {
  F fx;
  std::vector<double> g(fx.u.size());
  for (auto _ : state) {
    CompensatedSum e;
    if (hess) MatZeroEntries(fx.H);
    fx.term->add(fx.u, e, grad ? &g : nullptr, hess ? fx.H : nullptr);
    if (hess) {
      MatAssemblyBegin(fx.H, MAT_FINAL_ASSEMBLY);
      MatAssemblyEnd(fx.H, MAT_FINAL_ASSEMBLY);
    }
    benchmark::DoNotOptimize(e.value());
  }
  state.counters["elements/s"] =
      benchmark::Counter(static_cast<double>(fx.disc.elements().size()) * state.iterations(),
                         benchmark::Counter::kIsRate);
}

struct TriangleFixture {
  TriangleDiscretization disc;
  ParallelLayout layout;
  std::unique_ptr<TriangleElasticTerm> term;
  std::vector<double> u;
  Mat H = nullptr;
  explicit TriangleFixture(
      TriangleShellParameters::Bending bending = TriangleShellParameters::Bending::kHinge)
      : disc(make_triangle_rectangle(1, 1, 64, 64, 0, 0)), layout(PETSC_COMM_SELF, disc) {
    TriangleShellParameters p;
    p.bending = bending;
    p.youngs_modulus = 9e6;
    p.poisson_ratio = 0.3;
    p.thickness = 0.66e-3;
    term = std::make_unique<TriangleElasticTerm>(disc, layout, p);
    u.resize(3 * layout.num_local_points());
    for (int i = 0; i < layout.num_local_points(); ++i) {
      const Point3& X = disc.points()[layout.local_points()[i]];
      u[3 * i + 0] = 0.01 * X.x();
      u[3 * i + 2] = 0.05 * std::sin(3 * X.x()) * std::cos(2 * X.y());
    }
    layout.create_matrix(&H);
  }
  ~TriangleFixture() { MatDestroy(&H); }
};

void BM_TriangleEnergy(benchmark::State& s) { run<TriangleFixture>(s, false, false); }
void BM_TriangleEnergyGradient(benchmark::State& s) { run<TriangleFixture>(s, true, false); }
void BM_TriangleEnergyGradientHessian(benchmark::State& s) { run<TriangleFixture>(s, true, true); }
BENCHMARK(BM_TriangleEnergy)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TriangleEnergyGradient)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_TriangleEnergyGradientHessian)->Unit(benchmark::kMillisecond);

struct MidedgeFixture : TriangleFixture {
  MidedgeFixture() : TriangleFixture(TriangleShellParameters::Bending::kMidedge) {}
};
void BM_MidedgeEnergy(benchmark::State& s) { run<MidedgeFixture>(s, false, false); }
void BM_MidedgeEnergyGradient(benchmark::State& s) { run<MidedgeFixture>(s, true, false); }
void BM_MidedgeEnergyGradientHessian(benchmark::State& s) { run<MidedgeFixture>(s, true, true); }
BENCHMARK(BM_MidedgeEnergy)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MidedgeEnergyGradient)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_MidedgeEnergyGradientHessian)->Unit(benchmark::kMillisecond);

void BM_ElasticEnergy(benchmark::State& s) { run<Fixture>(s, false, false); }
void BM_ElasticEnergyGradient(benchmark::State& s) { run<Fixture>(s, true, false); }
void BM_ElasticEnergyGradientHessian(benchmark::State& s) { run<Fixture>(s, true, true); }
BENCHMARK(BM_ElasticEnergy)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ElasticEnergyGradient)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_ElasticEnergyGradientHessian)->Unit(benchmark::kMillisecond);

}  // namespace
