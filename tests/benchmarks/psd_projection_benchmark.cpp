// The PSD projection of one stencil Hessian (projected Newton's per-element cost): the full
// eigen-decomposition (project_to_psd) against the one on the motions that are not translations
// (project_stencil_hessian_to_psd), for the triangle's membrane (3 points, 9 × 9), the hinge and
// the contact pair (4 points, 12 × 12) and the mid-edge element (6 points, 18 × 18). The inputs
// are random symmetric matrices with the translations in their null space and about a third of
// their other eigenvalues negative, as a compressed membrane's or a barrier's has.
//
//   build/tests/benchmarks/psd_projection_benchmark
#include <benchmark/benchmark.h>

#include <Eigen/Core>
#include <random>
#include <vector>

#include "mlshell/psd_projection.hpp"

using namespace mlshell;

namespace {

template <int K>
std::vector<Eigen::Matrix<double, 3 * K, 3 * K>> inputs() {
  constexpr int N = 3 * K;
  using Matrix = Eigen::Matrix<double, N, N>;
  std::mt19937 rng(83);
  std::normal_distribution<double> g(0.0, 1.0);
  Matrix Q;  // I − (1/K) Σ_c t_c t_cᵀ: removes the common translation
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) Q(i, j) = (i == j) - (i % 3 == j % 3 ? 1.0 / K : 0.0);
  std::vector<Matrix> out(64);
  for (Matrix& H : out) {
    Matrix A;
    for (int i = 0; i < N * N; ++i) A.data()[i] = g(rng);
    const Matrix R = A + A.transpose() + 1.5 * Matrix::Identity();
    H = Q * R * Q;
  }
  return out;
}

template <int K, bool Stencil>
void BM_Project(benchmark::State& state) {
  const auto in = inputs<K>();
  std::size_t i = 0;
  for (auto _ : state) {
    auto H = in[i++ % in.size()];
    if constexpr (Stencil)
      project_stencil_hessian_to_psd(H);
    else
      project_to_psd(H);
    benchmark::DoNotOptimize(H.data());
  }
}

}  // namespace

BENCHMARK(BM_Project<3, false>)->Name("membrane 9x9 / full");
BENCHMARK(BM_Project<3, true>)->Name("membrane 9x9 / without translations");
BENCHMARK(BM_Project<4, false>)->Name("hinge or pair 12x12 / full");
BENCHMARK(BM_Project<4, true>)->Name("hinge or pair 12x12 / without translations");
BENCHMARK(BM_Project<6, false>)->Name("midedge 18x18 / full");
BENCHMARK(BM_Project<6, true>)->Name("midedge 18x18 / without translations");
