// Number formatting and input checks shared by the text writers (OBJ, XDMF, CSV, JSON).
#include <algorithm>
#include <charconv>
#include <stdexcept>
#include <vector>

#include "io_util.hpp"

namespace mlshell::io_detail {

std::string format_double(double x) {
  // The shortest text that reads back as the same double (std::to_chars, no format given),
  // e.g. 0.1 rather than %.17g's 0.10000000000000001; 32 chars hold the longest output
  // ("-2.2250738585072014e-308" is 24).
  char buf[32];
  const auto r = std::to_chars(buf, buf + sizeof buf, x);
  return std::string(buf, r.ptr);
}

void check_surface(const SurfaceSample& s, const char* who) {
  const std::string where = std::string(who) + ": ";
  if (s.points.size() % 3 != 0)
    throw std::invalid_argument(where + "points must hold 3 coordinates per point (got " +
                                std::to_string(s.points.size()) + " values)");
  if (s.cell_size != 3 && s.cell_size != 4)
    throw std::invalid_argument(where + "cells must be triangles or quads (cell_size " +
                                std::to_string(s.cell_size) + ")");
  if (s.cells.size() % s.cell_size != 0)
    throw std::invalid_argument(where + "cells must hold " + std::to_string(s.cell_size) +
                                " indices per cell (got " + std::to_string(s.cells.size()) +
                                " values)");
  for (const auto& [name, values] : s.cell_data)
    if (values.size() != s.cells.size() / s.cell_size)
      throw std::invalid_argument(where + "cell field '" + name + "' has " +
                                  std::to_string(values.size()) + " values for " +
                                  std::to_string(s.cells.size() / s.cell_size) + " cells");
  if (!s.displacement.empty() && s.displacement.size() != s.points.size())
    throw std::invalid_argument(where + "displacement must be empty or hold 3 values per point (" +
                                std::to_string(s.displacement.size()) + " values for " +
                                std::to_string(s.points.size() / 3) + " points)");
  const auto npoints = static_cast<std::int64_t>(s.points.size() / 3);
  for (std::size_t i = 0; i < s.cells.size(); ++i) {
    if (s.cells[i] < 0 || s.cells[i] >= npoints)
      throw std::invalid_argument(where + "cell " + std::to_string(i / s.cell_size) +
                                  " refers to point " + std::to_string(s.cells[i]) +
                                  " but there are " + std::to_string(npoints) + " points");
  }
}

}  // namespace mlshell::io_detail

namespace mlshell::io_detail {

void check_petsc(PetscErrorCode ierr, const std::filesystem::path& file, const char* call) {
  if (ierr == 0) return;
  const char* text = nullptr;
  PetscErrorMessage(ierr, &text, nullptr);
  throw OutputError("cannot write '" + file.string() + "': " + call +
                    " failed: " + (text ? text : "unknown PETSc error") + " (PETSc error " +
                    std::to_string(static_cast<int>(ierr)) + ")");
}

std::string broadcast(MPI_Comm comm, std::string text) {
  int length = static_cast<int>(text.size());
  MPI_Bcast(&length, 1, MPI_INT, 0, comm);
  text.resize(length);
  MPI_Bcast(text.data(), length, MPI_CHAR, 0, comm);
  return text;
}

std::string gather_text(MPI_Comm comm, std::string text) {
  int rank, size;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  constexpr long long kPiece = 1LL << 30;
  long long mine = static_cast<long long>(text.size());
  std::vector<long long> lengths(size);
  MPI_Gather(&mine, 1, MPI_LONG_LONG, lengths.data(), 1, MPI_LONG_LONG, 0, comm);
  if (rank != 0) {
    for (long long at = 0; at < mine; at += kPiece)
      MPI_Send(text.data() + at, static_cast<int>(std::min(kPiece, mine - at)), MPI_CHAR, 0, 0,
               comm);
    return {};
  }
  long long total = 0;
  for (long long n : lengths) total += n;
  text.resize(static_cast<std::size_t>(total));
  long long end = mine;
  for (int r = 1; r < size; ++r) {
    for (long long at = 0; at < lengths[r]; at += kPiece)
      MPI_Recv(text.data() + end + at, static_cast<int>(std::min(kPiece, lengths[r] - at)),
               MPI_CHAR, r, 0, comm, MPI_STATUS_IGNORE);
    end += lengths[r];
  }
  return text;
}

}  // namespace mlshell::io_detail
