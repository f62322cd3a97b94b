// Limit-surface sampling for output.
#include "mlshell/subdivision/surface_sampler.hpp"

namespace mlshell {

SurfaceSampler::SurfaceSampler(const SubdivisionDiscretization& disc, int k) : disc_(disc) {
  std::vector<SurfacePoint> pts;
  for (int f : disc.elements()) {
    const std::int64_t base = static_cast<std::int64_t>(pts.size());
    for (int j = 0; j <= k; ++j)
      for (int i = 0; i <= k; ++i) pts.push_back({f, double(i) / k, double(j) / k});
    for (int j = 0; j < k; ++j)
      for (int i = 0; i < k; ++i) {
        const std::int64_t a = base + j * (k + 1) + i;
        cells_.insert(cells_.end(), {a, a + 1, a + k + 2, a + k + 1});
      }
  }
  basis_ = disc.evaluator().evaluate(pts);
}

SurfaceSample SurfaceSampler::sample(const std::vector<double>& u) const {
  SurfaceSample s;
  const auto& X = disc_.mesh().points;
  for (const PointBasis& b : basis_) {
    const Point3 x = b.apply(kValue, X);
    Point3 d = Point3::Zero();
    if (!u.empty())
      for (int i = 0; i < b.size(); ++i)
        for (int c = 0; c < 3; ++c) d[c] += b.w[kValue][i] * u[3 * b.nodes[i] + c];
    for (int c = 0; c < 3; ++c) {
      s.points.push_back(x[c] + d[c]);
      s.displacement.push_back(d[c]);
    }
  }
  s.cells = cells_;
  return s;
}

}  // namespace mlshell
