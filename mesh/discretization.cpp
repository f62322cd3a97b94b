// What every kind of discretization shares (see discretization.hpp).
#include "mlshell/discretization.hpp"

namespace mlshell {

std::uint64_t discretization_fingerprint(const Discretization& disc) {
  std::uint64_t h = 1469598103934665603ull;  // FNV-1a
  auto mix = [&](const void* data, size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 1099511628211ull;
  };
  const int n = disc.num_points();
  mix(&n, sizeof n);
  for (const Point3& p : disc.points()) mix(p.data(), 3 * sizeof(double));
  return h;
}

}  // namespace mlshell
