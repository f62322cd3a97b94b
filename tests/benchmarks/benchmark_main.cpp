// Entry point of mlshell's Google Benchmark programs: PETSc lives for the whole run.
#include <benchmark/benchmark.h>
#include <petscsys.h>

int main(int argc, char** argv) {
  if (PetscInitialize(&argc, &argv, nullptr, nullptr) != 0) return 1;
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  PetscFinalize();
  return 0;
}
