// The uniform-grid ("spatial hash") broad phase of broad_phase.hpp. The grid's cells are cubes
// of side h, the mean longest side of the edge boxes (faces' if there are no edges), so a
// typical box covers a few cells. Cell (i, j, k) has the exact key (i·n_y + j)·n_z + k (no hash
// collisions; h grows until the key fits 62 bits). Every box is listed in each cell it covers;
// the list is sorted by key, and within each cell every vertex–face and edge–edge pair is
// tested. A pair of overlapping boxes shares all cells that cover the lower corner of their
// intersection, max(lo_a, lo_b), and is reported only from that corner's cell: once, with no
// set to merge.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "primitive_boxes.hpp"

namespace mlshell::contact_detail {

namespace {

enum Kind : std::uint8_t { kVertex, kEdge, kFace };

struct Entry {
  std::uint64_t cell;
  int id;
  Kind kind;
};

class Grid {
 public:
  Grid(const PrimitiveBoxes& boxes) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    lo_ = {inf, inf, inf};
    std::array<double, 3> hi = {-inf, -inf, -inf};
    for (const auto* list : {&boxes.vertices, &boxes.edges, &boxes.faces})
      for (const Box& b : *list)
        for (int k = 0; k < 3; ++k)
          lo_[k] = std::min(lo_[k], b.lo[k]), hi[k] = std::max(hi[k], b.hi[k]);
    const auto& sized = boxes.edges.empty() ? boxes.faces : boxes.edges;
    double sum = 0.0;
    for (const Box& b : sized)
      sum += std::max({b.hi[0] - b.lo[0], b.hi[1] - b.lo[1], b.hi[2] - b.lo[2]});
    h_ = sized.empty() ? 0.0 : sum / sized.size();
    const double extent = std::max({hi[0] - lo_[0], hi[1] - lo_[1], hi[2] - lo_[2], 0.0});
    if (!(h_ > 0.0)) h_ = extent > 0.0 ? extent : 1.0;
    // At most 2^20 cells a side, so that the key of n_x·n_y·n_z cells fits 60 bits.
    h_ = std::max(h_, extent / double(1 << 20));
    // A few boxes far larger than the rest (a vertex that moves far in a step) would be listed
    // in very many cells: double h until the lists hold at most 64 entries a box on average.
    const double boxes_count =
        double(boxes.vertices.size() + boxes.edges.size() + boxes.faces.size());
    while (listed_cells(boxes) > 64.0 * boxes_count) h_ *= 2.0;
    for (int k = 0; k < 3; ++k) n_[k] = cell_index(hi[k], k) + 1;
  }

  /// How many cells the boxes cover in all.
  double listed_cells(const PrimitiveBoxes& boxes) const {
    double total = 0.0;
    for (const auto* list : {&boxes.vertices, &boxes.edges, &boxes.faces})
      for (const Box& b : *list) {
        double cells = 1.0;
        for (int k = 0; k < 3; ++k)
          cells *= double(cell_index(b.hi[k], k) - cell_index(b.lo[k], k) + 1);
        total += cells;
      }
    return total;
  }

  std::int64_t cell_index(double x, int k) const {
    return static_cast<std::int64_t>(std::floor((x - lo_[k]) / h_));
  }
  std::uint64_t key(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return static_cast<std::uint64_t>((i * n_[1] + j) * n_[2] + k);
  }
  std::uint64_t key_of_point(const std::array<double, 3>& p) const {
    return key(cell_index(p[0], 0), cell_index(p[1], 1), cell_index(p[2], 2));
  }
  void list(const Box& b, int id, Kind kind, std::vector<Entry>& out) const {
    const std::int64_t i0 = cell_index(b.lo[0], 0), i1 = cell_index(b.hi[0], 0);
    const std::int64_t j0 = cell_index(b.lo[1], 1), j1 = cell_index(b.hi[1], 1);
    const std::int64_t k0 = cell_index(b.lo[2], 2), k1 = cell_index(b.hi[2], 2);
    for (std::int64_t i = i0; i <= i1; ++i)
      for (std::int64_t j = j0; j <= j1; ++j)
        for (std::int64_t k = k0; k <= k1; ++k) out.push_back({key(i, j, k), id, kind});
  }

 private:
  std::array<double, 3> lo_;
  std::array<std::int64_t, 3> n_;
  double h_;
};

/// The lower corner of the intersection of two overlapping boxes.
std::array<double, 3> intersection_corner(const Box& a, const Box& b) {
  return {std::max(a.lo[0], b.lo[0]), std::max(a.lo[1], b.lo[1]), std::max(a.lo[2], b.lo[2])};
}

}  // namespace

ContactCandidates spatial_hash_candidates(const ContactSurface& surface,
                                          const PrimitiveBoxes& boxes) {
  const Grid grid(boxes);
  std::vector<Entry> entries;
  entries.reserve(2 * (boxes.vertices.size() + boxes.edges.size() + boxes.faces.size()));
  for (std::size_t i = 0; i < boxes.vertices.size(); ++i)
    grid.list(boxes.vertices[i], int(i), kVertex, entries);
  for (std::size_t i = 0; i < boxes.edges.size(); ++i)
    grid.list(boxes.edges[i], int(i), kEdge, entries);
  for (std::size_t i = 0; i < boxes.faces.size(); ++i)
    grid.list(boxes.faces[i], int(i), kFace, entries);
  std::sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return a.cell != b.cell ? a.cell < b.cell : a.kind != b.kind ? a.kind < b.kind : a.id < b.id;
  });

  ContactCandidates out;
  std::vector<int> vs, es, fs;
  for (std::size_t begin = 0; begin < entries.size();) {
    const std::uint64_t cell = entries[begin].cell;
    std::size_t end = begin;
    vs.clear(), es.clear(), fs.clear();
    for (; end < entries.size() && entries[end].cell == cell; ++end)
      (entries[end].kind == kVertex ? vs
       : entries[end].kind == kEdge ? es
                                    : fs)
          .push_back(entries[end].id);
    for (const int v : vs)
      for (const int f : fs) {
        const Box &a = boxes.vertices[v], &b = boxes.faces[f];
        if (!face_has_vertex(surface.faces[f], v) && overlap(a, b) &&
            grid.key_of_point(intersection_corner(a, b)) == cell)
          out.point_triangle.push_back({v, f});
      }
    for (std::size_t i = 0; i < es.size(); ++i)
      for (std::size_t j = i + 1; j < es.size(); ++j) {
        const Box &a = boxes.edges[es[i]], &b = boxes.edges[es[j]];
        if (!edges_share_vertex(surface.edges[es[i]], surface.edges[es[j]]) && overlap(a, b) &&
            grid.key_of_point(intersection_corner(a, b)) == cell)
          out.edge_edge.push_back({es[i], es[j]});  // es is sorted: es[i] < es[j]
      }
    begin = end;
  }
  std::sort(out.point_triangle.begin(), out.point_triangle.end());
  std::sort(out.edge_edge.begin(), out.edge_edge.end());
  return out;
}

}  // namespace mlshell::contact_detail
