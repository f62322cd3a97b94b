// Number formatting and input checks shared by the text writers (OBJ, XDMF, CSV, JSON).
#include <charconv>
#include <stdexcept>

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
