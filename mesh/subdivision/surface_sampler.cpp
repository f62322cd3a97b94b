// Limit-surface sampling for output: the frames' watertight surface and the per-element grids of
// limit_surface.csv.
#include "mlshell/subdivision/surface_sampler.hpp"

#include <algorithm>
#include <unordered_map>

namespace mlshell {

namespace {

// The global numbering of the grid points of all elements, each point once. The elements are
// walked in order; each numbers the points no element before it has numbered: first its
// corners (corner order), then its edges (edge order; an edge's k − 1 points run from its lower
// to its higher vertex index, so that the faces on both sides find them), then its (k − 1)²
// interior points (u fastest). A corner or an edge thus belongs to the first element that
// contains it, boundary ones included. The numbering is topology alone: every rank computes
// it whole and samples only the points its elements own.
class SharedGridNumbering {
 public:
  SharedGridNumbering(const SubdivisionDiscretization& disc, int k)
      : quads_(disc.mesh().quads), elements_(disc.elements()), k_(k) {
    std::vector<std::int64_t> vertex(disc.mesh().num_points(), -1);
    std::unordered_map<std::int64_t, std::int64_t> edge_by_ends;
    std::int64_t next = 0;
    for (int f : elements_) {
      first_.push_back(next);
      const Quad& q = quads_[f];
      for (int c = 0; c < 4; ++c) {
        if (vertex[q[c]] < 0) vertex[q[c]] = next++;
        corner_.push_back(vertex[q[c]]);
      }
      for (int c = 0; c < 4; ++c) {
        const auto [lo, hi] = std::minmax(q[c], q[(c + 1) % 4]);
        const auto [it, fresh] =
            edge_by_ends.try_emplace(std::int64_t{lo} * disc.mesh().num_points() + hi, next);
        if (fresh) next += k - 1;
        edge_.push_back(it->second);
      }
      next += std::int64_t{k - 1} * (k - 1);
    }
    first_.push_back(next);
  }

  /// Points of elements [0, e) in all: element e owns points first(e) .. first(e + 1) − 1.
  std::int64_t first(std::int64_t e) const { return first_[e]; }

  /// The index of grid point (i, j), at (u, v) = (i/k, j/k), of element e.
  std::int64_t index(std::int64_t e, int i, int j) const {
    const int k = k_;
    if (i > 0 && i < k && j > 0 && j < k)
      return first_[e + 1] - std::int64_t{k - 1} * (k - 1) + std::int64_t{j - 1} * (k - 1) + i - 1;
    // Corners 0..3 sit at (0,0), (1,0), (1,1), (0,1) (SubdivisionDiscretization::edge_point);
    // edge c runs from corner c to corner c+1, the point t steps along it from corner c.
    int c, t;
    if (j == 0)
      c = 0, t = i;
    else if (i == k)
      c = 1, t = j;
    else if (j == k)
      c = 2, t = k - i;
    else
      c = 3, t = k - j;
    if (t == 0) return corner_[4 * e + c];
    if (t == k) return corner_[4 * e + (c + 1) % 4];
    const Quad& q = quads_[elements_[e]];
    return edge_[4 * e + c] + (q[c] < q[(c + 1) % 4] ? t - 1 : k - 1 - t);
  }

 private:
  const std::vector<Quad>& quads_;
  const std::vector<int>& elements_;
  int k_;
  std::vector<std::int64_t> first_;   // per element, and the total
  std::vector<std::int64_t> corner_;  // 4 per element: the index of corner c
  std::vector<std::int64_t> edge_;    // 4 per element: the first point of edge c, lower end first
};

/// The sampling of the limit surface at `points`, basis values only (evaluated in chunks).
std::unique_ptr<SurfaceSampling> evaluate(const SubdivisionDiscretization& disc,
                                          const std::vector<SurfacePoint>& points,
                                          std::vector<std::int64_t> cells, SamplingPlace place) {
  std::vector<double> reference;
  std::vector<std::int64_t> offsets{0};
  std::vector<int> nodes;
  std::vector<double> weights;
  const auto& X = disc.mesh().points;
  constexpr size_t kChunk = 4096;
  for (size_t begin = 0; begin < points.size(); begin += kChunk) {
    const std::vector<SurfacePoint> chunk(points.begin() + begin,
                                          points.begin() + std::min(points.size(), begin + kChunk));
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
                                           4, place);
}

}  // namespace

std::unique_ptr<SurfaceSampling> sample_limit_surface(const SubdivisionDiscretization& disc, int k,
                                                      int part, int parts) {
  const SharedGridNumbering numbering(disc, k);
  const auto& elements = disc.elements();
  const auto num_elements = static_cast<std::int64_t>(elements.size());
  const auto [first, last] = slice_range(num_elements, part, parts);
  const std::int64_t first_point = numbering.first(first);
  std::vector<SurfacePoint> points(numbering.first(last) - first_point);
  std::vector<std::int64_t> cells;
  for (std::int64_t e = first; e < last; ++e) {
    for (int j = 0; j <= k; ++j)
      for (int i = 0; i <= k; ++i) {
        const std::int64_t p = numbering.index(e, i, j);
        if (p >= numbering.first(e) && p < numbering.first(e + 1))  // a point e owns
          points[p - first_point] = {elements[e], double(i) / k, double(j) / k};
      }
    for (int j = 0; j < k; ++j)
      for (int i = 0; i < k; ++i)
        cells.insert(cells.end(), {numbering.index(e, i, j), numbering.index(e, i + 1, j),
                                   numbering.index(e, i + 1, j + 1), numbering.index(e, i, j + 1)});
  }
  const std::int64_t cells_per_element = std::int64_t{k} * k;
  return evaluate(disc, points, std::move(cells),
                  SamplingPlace{first_point, numbering.first(num_elements),
                                cells_per_element * first, cells_per_element * num_elements});
}

std::unique_ptr<SurfaceSampling> sample_element_grids(const SubdivisionDiscretization& disc,
                                                      int k) {
  std::vector<SurfacePoint> points;
  std::vector<std::int64_t> cells;
  for (int f : disc.elements()) {
    const auto base = static_cast<std::int64_t>(points.size());
    for (int j = 0; j <= k; ++j)
      for (int i = 0; i <= k; ++i) points.push_back({f, double(i) / k, double(j) / k});
    for (int j = 0; j < k; ++j)
      for (int i = 0; i < k; ++i) {
        const std::int64_t a = base + j * (k + 1) + i;
        cells.insert(cells.end(), {a, a + 1, a + k + 2, a + k + 1});
      }
  }
  return evaluate(disc, points, std::move(cells), {});
}

}  // namespace mlshell
