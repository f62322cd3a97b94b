// Rank 0's result files of a Simulation (private to src/simulation).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "mlshell/output_files.hpp"
#include "mlshell/simulation.hpp"
#include "mlshell/subdivision/surface_sampler.hpp"

namespace mlshell {

/// Rank 0's result files.
struct Simulation::Output {
  std::filesystem::path dir;
  std::unique_ptr<XdmfSeries> xdmf;
  std::unique_ptr<CsvTable> csv;
  std::unique_ptr<SurfaceSampling> sampler;
  std::vector<std::string> effect_names;
};

}  // namespace mlshell
