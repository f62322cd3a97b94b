// -mlshell_material_csv: the scene's material as tables, for plotting and checking a fit
// (examples/material/plot_material.py draws them).
#include <sstream>

#include "io_util.hpp"
#include "mlshell/output_files.hpp"
#include "mlshell/shell/material.hpp"

namespace mlshell {

void write_material_table(const MaterialSpec& spec, const std::filesystem::path& path) {
  const auto material = make_material(spec);
  std::ostringstream out;
  out << "kind,e11,e22,e12,psi,s11,s22,s12,beyond_fit,coupling_limited\n";
  auto row = [&](const char* kind, double e11, double e22, double e12) {
    Eigen::Vector3d g;
    const Strain3 e(e11, e22, e12);
    const double psi = material->energy_density(e, &g, nullptr);
    const MaterialPointStatus st = material->status(e);
    out << kind << ',' << io_detail::format_double(e11) << ',' << io_detail::format_double(e22)
        << ',' << io_detail::format_double(e12) << ',' << io_detail::format_double(psi) << ','
        << io_detail::format_double(g[0]) << ',' << io_detail::format_double(g[1]) << ','
        << io_detail::format_double(g[2]) << ',' << st.beyond_fit << ',' << st.coupling_limited
        << '\n';
  };
  // Uniaxial curves (the other components zero), then the (Ẽ11, Ẽ22) plane at Ẽ12 = 0.
  constexpr int n = 200;
  for (int i = -n; i <= n; ++i) {
    const double e = 0.4 * i / n;
    row("warp", e, 0.0, 0.0);
    row("weft", 0.0, e, 0.0);
    row("shear", 0.0, 0.0, e);
  }
  constexpr int m = 120;
  for (int i = -m; i <= m; ++i)
    for (int j = -m; j <= m; ++j) row("plane", 0.25 * i / m, 0.25 * j / m, 0.0);
  write_file_atomic(path, out.str());
}

}  // namespace mlshell
