// The result files of a Simulation (private to src/simulation).
#pragma once

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "mlshell/distributed_sampling.hpp"
#include "mlshell/output_files.hpp"
#include "mlshell/simulation.hpp"

namespace mlshell {

/// The result files (the XDMF series on every rank, the others on rank 0).
struct Simulation::Output {
  std::filesystem::path dir;
  std::unique_ptr<XdmfSeries> xdmf;
  std::unique_ptr<DistributedSampling> sampling;  // the frames' surface, sliced over the ranks
  std::unique_ptr<CsvTable> csv;
  std::vector<std::string> effect_names;
};

}  // namespace mlshell
