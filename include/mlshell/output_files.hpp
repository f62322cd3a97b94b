// Result files: every writer here but XdmfSeries runs on one process (rank 0 of the simulation)
// with data that has already been gathered in natural (rank-independent) order; XdmfSeries
// writes distributed data in parallel. All write atomically: the
// content goes to `<name>.tmp.<pid>` in the same folder and is renamed over `<name>` only when it
// is complete, so a reader never sees a partly written file passed off as complete.
// Errors (cannot create folder, disk full, ...) throw OutputError naming the file and the cause.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include <petscis.h>
#include <petscvec.h>

#include "mlshell/discretization.hpp"

namespace mlshell {

class OutputError : public std::runtime_error {
 public:
  /// `every_rank`: raised identically on every rank, so the run can end without MPI_Abort.
  explicit OutputError(const std::string& what, bool every_rank = false)
      : std::runtime_error(what), every_rank_(every_rank) {}
  bool every_rank() const { return every_rank_; }

 private:
  bool every_rank_;
};

/// Rank 0 creates the output folder `dir` (and its parents) and removes the summary.json an
/// earlier run left there (it must not pass for this run's result). Collective: if rank 0
/// cannot, every rank throws OutputError("cannot create output folder 'dir': <cause>").
void create_output_folder(MPI_Comm comm, const std::filesystem::path& dir);

/// Writes `content` to `path` atomically (temporary file + rename). Creates parent folders.
void write_file_atomic(const std::filesystem::path& path, const std::string& content);

struct MaterialSpec;
/// -mlshell_material_csv: ψ and its gradient (the stresses ∂ψ/∂Ẽ, Pa) along the uniaxial warp,
/// weft and shear strains (|Ẽ| ≤ 0.4) and on the (Ẽ11, Ẽ22) plane (|Ẽ| ≤ 0.25), with where each
/// point lies in the model (continuation, coupling limit). CSV columns: kind, e11, e22, e12,
/// psi, s11, s22, s12, beyond_fit, coupling_limited.
void write_material_table(const MaterialSpec& spec, const std::filesystem::path& path);

/// One frame's datasets as PETSc objects on a series' communicator, each rank holding a
/// contiguous slice in natural order: geometry (and displacement) of block size 3, topology of
/// block size cell_size, and scalar cell fields (block size 1, named "cell_<name>").
struct FrameData {
  Vec geometry = nullptr;
  Vec displacement = nullptr;  ///< optional
  IS topology = nullptr;
  int cell_size = 4;
  std::vector<std::pair<std::string, Vec>> cell_fields;
};

/// Wavefront OBJ of a sampled surface (v and f lines, 1-based indices, coordinates as the
/// shortest text that reads back exactly).
void write_obj(const std::filesystem::path& path, const SurfaceSample& surface,
               const std::string& comment);
/// The same file from a frame distributed over `comm` (its geometry and topology): every rank
/// formats its slice's lines, rank 0 writes the file; an error there is thrown on every rank.
void write_obj(MPI_Comm comm, const std::filesystem::path& path, const FrameData& frame,
               const std::string& comment);


/// A time series for ParaView: one HDF5 file per frame (`<stem>_<step 6 digits>.h5` holding
/// `/geometry` (N×3 float64), `/topology` (M×4 PetscInt, i.e. int32 or int64 as PETSc was built;
/// the XDMF states which) and, when present, `/displacement` (N×3 float64)) plus `<stem>.xdmf`,
/// an XDMF 3 temporal collection that is rewritten atomically after each frame, so it is valid
/// at any moment and lists only complete frames. Adding a step already listed replaces it.
/// Collective on `comm`: each rank writes its slice of the datasets (parallel HDF5); rank 0
/// names, renames and lists the files.
class XdmfSeries {
 public:
  XdmfSeries(std::filesystem::path dir, std::string stem, MPI_Comm comm = PETSC_COMM_SELF);
  ~XdmfSeries();
  XdmfSeries(const XdmfSeries&) = delete;
  XdmfSeries& operator=(const XdmfSeries&) = delete;
  /// One process's surface (a series on one rank).
  void add_frame(int step, double time, const SurfaceSample& surface);
  /// Distributed datasets (collective).
  void add_frame(int step, double time, const FrameData& frame);
  const std::filesystem::path& xdmf_path() const { return xdmf_; }

 private:
  std::string h5_name(int step) const;
  void write_xdmf() const;
  MPI_Comm comm_;
  std::filesystem::path dir_, xdmf_;
  std::string stem_;
  struct Frame {
    int step;
    double time;
    std::string h5;
    std::int64_t npoints, ncells;
    bool displacement = false;             ///< whether the HDF5 file holds /displacement
    int cell_size = 4;                     ///< 4 quadrilaterals, 3 triangles
    std::vector<std::string> cell_fields;  ///< scalar cell datasets /cell_<name>
  };
  std::vector<Frame> frames_;
};

/// A CSV table with a fixed header; each append rewrites the file atomically.
class CsvTable {
 public:
  CsvTable(std::filesystem::path path, std::vector<std::string> columns);
  /// One value per column; numbers are written as the shortest text that reads back exactly,
  /// strings as given (quoted if needed).
  void append(const std::vector<std::variant<double, long long, std::string>>& row);
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
  std::vector<std::string> columns_;
  std::string text_;
};

/// A small JSON value for summary.json (objects keep insertion order).
class Json {
 public:
  using Object = std::vector<std::pair<std::string, Json>>;
  using Array = std::vector<Json>;
  Json() : v_(nullptr) {}
  Json(std::nullptr_t) : v_(nullptr) {}
  Json(bool b) : v_(b) {}
  Json(int i) : v_(static_cast<long long>(i)) {}
  Json(long i) : v_(static_cast<long long>(i)) {}
  Json(long long i) : v_(i) {}
  Json(double d) : v_(d) {}
  Json(const char* s) : v_(std::string(s)) {}
  Json(std::string s) : v_(std::move(s)) {}
  Json(Array a) : v_(std::make_shared<Array>(std::move(a))) {}
  Json(Object o) : v_(std::make_shared<Object>(std::move(o))) {}
  static Json array(const std::vector<double>& xs);
  /// Adds or replaces a key of an object (the value must be an object).
  Json& set(const std::string& key, Json value);
  /// Serialises with 2-space indentation. Non-finite doubles are written as null.
  std::string dump(int indent = 2) const;

 private:
  std::variant<std::nullptr_t, bool, long long, double, std::string, std::shared_ptr<Array>,
               std::shared_ptr<Object>>
      v_;
  void dump_to(std::string& out, int indent, int depth) const;
};

/// State saved for restart: natural-order displacements and velocities of all control points.
struct Checkpoint {
  int step = 0;                         ///< the completed step
  double time = 0.0;                    ///< time at that step
  std::uint64_t scene_fingerprint = 0;  ///< hash of the discretization (dofs + reference geometry)
  std::vector<double> displacement;     ///< 3 per control point
  std::vector<double> velocity;         ///< 3 per control point (zeros without inertia)
};

/// Binary format: magic "MLSHCKPT", version, step, time, fingerprint, n, data, and a trailing
/// checksum. Written atomically.
void write_checkpoint(const std::filesystem::path& path, const Checkpoint& c);
/// Throws OutputError naming the file if it is missing, truncated, corrupt (checksum) or of
/// another format/version.
Checkpoint read_checkpoint(const std::filesystem::path& path);

}  // namespace mlshell
