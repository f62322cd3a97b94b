// Wavefront OBJ output of a sampled surface, for quick looks in any mesh viewer: from a whole
// sample on one process, or from a frame distributed over the ranks (each formats its slice).
#include <petscis.h>
#include <petscvec.h>

#include <sstream>

#include "io_util.hpp"

namespace mlshell {

namespace {

/// The comment, one `#` line per line (a multi-line comment cannot inject geometry
/// statements), and a line with the counts.
std::string obj_header(const std::string& comment, long long points, long long cells,
                       int cell_size) {
  std::string out;
  std::istringstream lines(comment);
  for (std::string line; std::getline(lines, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    out += line.empty() ? "#\n" : "# " + line + "\n";
  }
  out += "# " + std::to_string(points) + " vertices, " + std::to_string(cells) +
         (cell_size == 3 ? " triangles\n" : " quads\n");
  return out;
}

/// `v x y z` lines of n points (3n coordinates).
void append_vertices(std::string& out, const double* x, std::size_t n) {
  out.reserve(out.size() + n * 60);
  for (std::size_t i = 0; i < 3 * n; i += 3) {
    out += "v ";
    out += io_detail::format_double(x[i]);
    out += ' ';
    out += io_detail::format_double(x[i + 1]);
    out += ' ';
    out += io_detail::format_double(x[i + 2]);
    out += '\n';
  }
}

/// `f a b c [d]` lines of the cells in `c` (0-based point indices; OBJ's are 1-based).
template <class Index>
void append_faces(std::string& out, const Index* c, std::size_t values, int cell_size) {
  out.reserve(out.size() + values * 8);
  for (std::size_t i = 0; i < values; i += cell_size) {
    out += 'f';
    for (int k = 0; k < cell_size; ++k) {
      out += ' ';
      out += std::to_string(static_cast<long long>(c[i + k]) + 1);
    }
    out += '\n';
  }
}

}  // namespace

void write_obj(const std::filesystem::path& path, const SurfaceSample& surface,
               const std::string& comment) {
  io_detail::check_surface(surface, "write_obj");
  std::string out = obj_header(comment, static_cast<long long>(surface.points.size() / 3),
                               static_cast<long long>(surface.num_cells()), surface.cell_size);
  append_vertices(out, surface.points.data(), surface.points.size() / 3);
  append_faces(out, surface.cells.data(), surface.cells.size(), surface.cell_size);
  write_file_atomic(path, out);
}

void write_obj(MPI_Comm comm, const std::filesystem::path& path, const FrameData& frame,
               const std::string& comment) {
  using io_detail::check_petsc;
  PetscInt points, cells, local_points, local_cells;
  check_petsc(VecGetSize(frame.geometry, &points), path, "VecGetSize");
  check_petsc(VecGetLocalSize(frame.geometry, &local_points), path, "VecGetLocalSize");
  check_petsc(ISGetSize(frame.topology, &cells), path, "ISGetSize");
  check_petsc(ISGetLocalSize(frame.topology, &local_cells), path, "ISGetLocalSize");
  std::string vertices, faces;
  const PetscScalar* x;
  check_petsc(VecGetArrayRead(frame.geometry, &x), path, "VecGetArrayRead");
  append_vertices(vertices, x, static_cast<std::size_t>(local_points / 3));
  check_petsc(VecRestoreArrayRead(frame.geometry, &x), path, "VecRestoreArrayRead");
  const PetscInt* c;
  check_petsc(ISGetIndices(frame.topology, &c), path, "ISGetIndices");
  append_faces(faces, c, static_cast<std::size_t>(local_cells), frame.cell_size);
  check_petsc(ISRestoreIndices(frame.topology, &c), path, "ISRestoreIndices");
  vertices = io_detail::gather_text(comm, std::move(vertices));
  faces = io_detail::gather_text(comm, std::move(faces));
  io_detail::on_rank_zero(comm, [&] {
    std::string out = obj_header(comment, points / 3, cells / frame.cell_size, frame.cell_size);
    out.reserve(out.size() + vertices.size() + faces.size());
    out += vertices;
    vertices = std::string();
    out += faces;
    faces = std::string();
    write_file_atomic(path, out);
  });
}

}  // namespace mlshell
