// Limit-surface sampling for output.
#include "mlshell/subdivision/surface_sampler.hpp"

#include <algorithm>

namespace mlshell {

std::unique_ptr<SurfaceSampling> sample_limit_surface(const SubdivisionDiscretization& disc,
                                                      int k) {
  std::vector<SurfacePoint> pts;
  std::vector<std::int64_t> cells;
  for (int f : disc.elements()) {
    const std::int64_t base = static_cast<std::int64_t>(pts.size());
    for (int j = 0; j <= k; ++j)
      for (int i = 0; i <= k; ++i) pts.push_back({f, double(i) / k, double(j) / k});
    for (int j = 0; j < k; ++j)
      for (int i = 0; i < k; ++i) {
        const std::int64_t a = base + j * (k + 1) + i;
        cells.insert(cells.end(), {a, a + 1, a + k + 2, a + k + 1});
      }
  }
  std::vector<double> reference;
  std::vector<std::int64_t> offsets{0};
  std::vector<int> nodes;
  std::vector<double> weights;
  const auto& X = disc.mesh().points;
  // In chunks, values only: every rank samples the whole surface (DistributedSampling keeps its
  // slice), so this is replicated work.
  constexpr size_t kChunk = 4096;
  for (size_t first = 0; first < pts.size(); first += kChunk) {
    const std::vector<SurfacePoint> chunk(pts.begin() + first,
                                          pts.begin() + std::min(pts.size(), first + kChunk));
    for (const PointBasis& b : disc.evaluator().evaluate(chunk, BasisSlots::kValueOnly)) {
      const Point3 x = b.apply(kValue, X);
      reference.insert(reference.end(), {x[0], x[1], x[2]});
      nodes.insert(nodes.end(), b.nodes.begin(), b.nodes.end());
      weights.insert(weights.end(), b.w[kValue].begin(), b.w[kValue].end());
      offsets.push_back(static_cast<std::int64_t>(nodes.size()));
    }
  }
  return std::make_unique<SurfaceSampling>(std::move(reference), std::move(offsets),
                                           std::move(nodes), std::move(weights), std::move(cells),
                                           4);
}

}  // namespace mlshell
