// Wavefront OBJ output of a sampled surface, for quick looks in any mesh viewer.
#include <sstream>

#include "io_util.hpp"

namespace mlshell {

void write_obj(const std::filesystem::path& path, const SurfaceSample& surface,
               const std::string& comment) {
  io_detail::check_surface(surface, "write_obj");
  std::string out;
  out.reserve(surface.points.size() * 24 + surface.cells.size() * 8 + comment.size() + 64);
  // Every line of the comment becomes its own `#` line, so a multi-line comment cannot inject
  // geometry statements.
  std::istringstream lines(comment);
  for (std::string line; std::getline(lines, line);) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    out += line.empty() ? "#\n" : "# " + line + "\n";
  }
  out += "# " + std::to_string(surface.points.size() / 3) + " vertices, " +
         std::to_string(surface.num_cells()) +
         (surface.cell_size == 3 ? " triangles\n" : " quads\n");
  for (std::size_t i = 0; i < surface.points.size(); i += 3) {
    out += "v ";
    out += io_detail::format_double(surface.points[i]);
    out += ' ';
    out += io_detail::format_double(surface.points[i + 1]);
    out += ' ';
    out += io_detail::format_double(surface.points[i + 2]);
    out += '\n';
  }
  const auto n = static_cast<std::size_t>(surface.cell_size);
  for (std::size_t i = 0; i < surface.cells.size(); i += n) {
    out += 'f';
    for (std::size_t k = 0; k < n; ++k) {  // OBJ indices are 1-based
      out += ' ';
      out += std::to_string(surface.cells[i + k] + 1);
    }
    out += '\n';
  }
  write_file_atomic(path, out);
}

}  // namespace mlshell
