// Helpers shared by the result-file writers (src/io/*.cpp); not part of the public interface.
#pragma once

#include <mpi.h>
#include <petscsys.h>

#include <exception>
#include <filesystem>
#include <string>

#include "mlshell/output_files.hpp"

namespace mlshell::io_detail {

/// `<path>.tmp.<pid>`: a name in the same folder (so the final rename never crosses file
/// systems) that two processes writing the same file cannot share.
std::filesystem::path temporary_path_for(const std::filesystem::path& path);

/// Creates the folder that will hold `path` (if it has one); throws OutputError naming `path`.
void create_parent_folder(const std::filesystem::path& path);

/// Renames the complete temporary `tmp` over `path`; on failure removes `tmp` and throws.
void commit_temporary(const std::filesystem::path& tmp, const std::filesystem::path& path);

/// The shortest text that reads back as the same double, bit-exactly (std::to_chars).
std::string format_double(double x);

/// Checks the shape invariants of a SurfaceSample (3 coordinates per point, 4 in-range indices
/// per quad, displacement empty or one vector per point); throws std::invalid_argument.
void check_surface(const SurfaceSample& surface, const char* who);

/// Throws OutputError naming the file when a PETSc call failed (the writers return void, so
/// PetscCall, which returns the error code, cannot be used in them).
void check_petsc(PetscErrorCode ierr, const std::filesystem::path& file, const char* call);

/// Rank 0's `text` on every rank.
std::string broadcast(MPI_Comm comm, std::string text);

/// Rank 0: every rank's `text` concatenated in rank order; other ranks: empty. Any length (sent
/// in pieces below MPI's int counts).
std::string gather_text(MPI_Comm comm, std::string text);

/// Runs `f` on rank 0 and throws the same OutputError on every rank if it threw there, so
/// that no rank goes on to a collective call the others have left.
template <class F>
void on_rank_zero(MPI_Comm comm, F&& f) {
  int rank;
  MPI_Comm_rank(comm, &rank);
  std::string error;
  if (rank == 0) try {
      f();
    } catch (const std::exception& e) {
      error = e.what();
      if (error.empty()) error = "unknown error";
    }
  error = broadcast(comm, std::move(error));
  if (!error.empty()) throw OutputError(error, true);
}

}  // namespace mlshell::io_detail
