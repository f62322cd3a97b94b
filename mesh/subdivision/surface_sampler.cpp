// Limit-surface sampling for output.
#include "mlshell/subdivision/surface_sampler.hpp"

#include <algorithm>

namespace mlshell {

std::unique_ptr<SurfaceSampling> sample_limit_surface(const SubdivisionDiscretization& disc, int k,
                                                      int part, int parts) {
  const auto& elements = disc.elements();
  const auto num_elements = static_cast<std::int64_t>(elements.size());
  const auto [first, last] = slice_range(num_elements, part, parts);
  const std::int64_t points_per_element = (k + 1) * (k + 1), cells_per_element = k * k;
  std::vector<SurfacePoint> pts;
  std::vector<std::int64_t> cells;
  for (std::int64_t e = first; e < last; ++e) {
    const int f = elements[e];
    const std::int64_t base = points_per_element * first + static_cast<std::int64_t>(pts.size());
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
  // In chunks, values only.
  constexpr size_t kChunk = 4096;
  for (size_t begin = 0; begin < pts.size(); begin += kChunk) {
    const std::vector<SurfacePoint> chunk(pts.begin() + begin,
                                          pts.begin() + std::min(pts.size(), begin + kChunk));
    for (const PointBasis& b : disc.evaluator().evaluate(chunk, BasisSlots::kValueOnly)) {
      const Point3 x = b.apply(kValue, X);
      reference.insert(reference.end(), {x[0], x[1], x[2]});
      nodes.insert(nodes.end(), b.nodes.begin(), b.nodes.end());
      weights.insert(weights.end(), b.w[kValue].begin(), b.w[kValue].end());
      offsets.push_back(static_cast<std::int64_t>(nodes.size()));
    }
  }
  return std::make_unique<SurfaceSampling>(
      std::move(reference), std::move(offsets), std::move(nodes), std::move(weights),
      std::move(cells), 4,
      SurfaceSampling::Place{points_per_element * first, points_per_element * num_elements,
                             cells_per_element * first, cells_per_element * num_elements});
}

}  // namespace mlshell
