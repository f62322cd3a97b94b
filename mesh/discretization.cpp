// What every kind of discretization shares (see discretization.hpp).
#include "mlshell/discretization.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace mlshell {

SurfaceSampling::SurfaceSampling(std::vector<double> reference, std::vector<std::int64_t> offsets,
                                 std::vector<int> nodes, std::vector<double> weights,
                                 std::vector<std::int64_t> cells, int cell_size, Place place)
    : reference_(std::move(reference)),
      offsets_(std::move(offsets)),
      nodes_(std::move(nodes)),
      weights_(std::move(weights)),
      cells_(std::move(cells)),
      cell_size_(cell_size),
      place_(place) {
  const auto n = static_cast<std::int64_t>(offsets_.size()) - 1;
  if (n < 0 || offsets_.front() != 0 ||
      offsets_.back() != static_cast<std::int64_t>(nodes_.size()) ||
      nodes_.size() != weights_.size() || reference_.size() != static_cast<size_t>(3 * n) ||
      cell_size_ < 3 || cells_.size() % cell_size_ != 0)
    throw std::invalid_argument("SurfaceSampling: inconsistent sizes (" + std::to_string(n) +
                                " samples, " + std::to_string(reference_.size()) +
                                " coordinates, " + std::to_string(nodes_.size()) + " nodes, " +
                                std::to_string(weights_.size()) + " weights)");
  if (place_.total_points < 0) place_.total_points = n;
  if (place_.total_cells < 0) place_.total_cells = num_cells();
  if (place_.first_point < 0 || place_.first_point + n > place_.total_points ||
      place_.first_cell < 0 || place_.first_cell + num_cells() > place_.total_cells)
    throw std::invalid_argument("SurfaceSampling: a slice outside its whole");
  for (std::int64_t c : cells_)
    if (c < 0 || c >= place_.total_points)
      throw std::invalid_argument("SurfaceSampling: cell index " + std::to_string(c) +
                                  " outside [0, " + std::to_string(place_.total_points) + ")");
}

std::pair<std::int64_t, std::int64_t> slice_range(std::int64_t count, int i, int n) {
  const std::int64_t base = count / n, extra = count % n;
  const std::int64_t first = i * base + std::min<std::int64_t>(i, extra);
  return {first, first + base + (i < extra ? 1 : 0)};
}

std::unique_ptr<SurfaceSampling> SurfaceSampling::slice(int i, int n) const {
  if (place_.first_point != 0 || place_.total_points != num_points())
    throw std::logic_error("SurfaceSampling::slice: not a whole sampling");
  const auto [p0, p1] = slice_range(num_points(), i, n);
  const auto [c0, c1] = slice_range(num_cells(), i, n);
  std::vector<std::int64_t> offsets{0};
  for (std::int64_t p = p0; p < p1; ++p) offsets.push_back(offsets_[p + 1] - offsets_[p0]);
  return std::make_unique<SurfaceSampling>(
      std::vector<double>(reference_.begin() + 3 * p0, reference_.begin() + 3 * p1),
      std::move(offsets),
      std::vector<int>(nodes_.begin() + offsets_[p0], nodes_.begin() + offsets_[p1]),
      std::vector<double>(weights_.begin() + offsets_[p0], weights_.begin() + offsets_[p1]),
      std::vector<std::int64_t>(cells_.begin() + cell_size_ * c0, cells_.begin() + cell_size_ * c1),
      cell_size_, Place{p0, num_points(), c0, num_cells()});
}

SurfaceSample SurfaceSampling::sample(const std::vector<double>& u) const {
  SurfaceSample s;
  s.cell_size = cell_size_;
  s.cells = cells_;
  s.points = reference_;
  s.displacement.assign(reference_.size(), 0.0);
  for (std::int64_t p = 0; p < num_points(); ++p) {
    double d[3] = {0.0, 0.0, 0.0};
    if (!u.empty())
      for (std::int64_t k = offsets_[p]; k < offsets_[p + 1]; ++k)
        for (int c = 0; c < 3; ++c) d[c] += weights_[k] * u[3 * nodes_[k] + c];
    for (int c = 0; c < 3; ++c) {
      s.points[3 * p + c] += d[c];
      s.displacement[3 * p + c] = d[c];
    }
  }
  return s;
}

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
