// Number formatting and input checks shared by the text writers (OBJ, XDMF, CSV, JSON).
#include <cstdio>
#include <stdexcept>

#include "io_util.hpp"

namespace mlshell::io_detail {

std::string format_double(double x) {
  // 17 significant digits round-trip every IEEE double; 32 chars hold the longest output
  // ("-2.2250738585072014e-308" is 24).
  char buf[32];
  const int n = std::snprintf(buf, sizeof buf, "%.17g", x);
  return std::string(buf, static_cast<std::size_t>(n));
}

void check_surface(const SurfaceSample& s, const char* who) {
  const std::string where = std::string(who) + ": ";
  if (s.points.size() % 3 != 0)
    throw std::invalid_argument(where + "points must hold 3 coordinates per point (got " +
                                std::to_string(s.points.size()) + " values)");
  if (s.quads.size() % 4 != 0)
    throw std::invalid_argument(where + "quads must hold 4 indices per quad (got " +
                                std::to_string(s.quads.size()) + " values)");
  if (!s.displacement.empty() && s.displacement.size() != s.points.size())
    throw std::invalid_argument(where + "displacement must be empty or hold 3 values per point (" +
                                std::to_string(s.displacement.size()) + " values for " +
                                std::to_string(s.points.size() / 3) + " points)");
  const auto npoints = static_cast<std::int64_t>(s.points.size() / 3);
  for (std::size_t i = 0; i < s.quads.size(); ++i) {
    if (s.quads[i] < 0 || s.quads[i] >= npoints)
      throw std::invalid_argument(where + "quad " + std::to_string(i / 4) + " refers to point " +
                                  std::to_string(s.quads[i]) + " but there are " +
                                  std::to_string(npoints) + " points");
  }
}

}  // namespace mlshell::io_detail
