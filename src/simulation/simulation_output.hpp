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

/// One mesh's frames: the run's (the finest level) or one level's of a progressive run.
struct Simulation::FrameSeries {
  std::string stem;        ///< the series <stem>.xdmf (and its HDF5 files)
  std::string obj_prefix;  ///< OBJ frames <obj_prefix>_%06d.obj
  const Discretization* disc = nullptr;
  const ParallelLayout* layout = nullptr;
  LevelProblem* problem = nullptr;  ///< for the per-face fields
  std::unique_ptr<DistributedSampling> sampling;  // the frames' surface, sliced over the ranks
  std::unique_ptr<XdmfSeries> xdmf;               // on the first frame
};

/// The result files (the XDMF series on every rank, the others on rank 0).
struct Simulation::Output {
  std::filesystem::path dir;
  FrameSeries frames;                       ///< the finest level's
  std::vector<FrameSeries> level_frames;    ///< a progressive run's, per level (finest included)
  std::unique_ptr<CsvTable> csv;
  std::vector<std::string> effect_names;
};

}  // namespace mlshell
