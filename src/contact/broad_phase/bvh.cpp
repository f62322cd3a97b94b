// The bounding-volume-hierarchy broad phase of broad_phase.hpp: a binary tree over a list of
// boxes, each node's box the union of its children's, built top-down by splitting the node's
// boxes at the median of their centres along the longest axis of the centres' bounds
// (std::nth_element, so O(n log n) in all), with leaves of at most 4 boxes. One tree over the
// face boxes answers every vertex box; one over the edge boxes answers every edge box (each
// pair once, a < b).
#include <algorithm>
#include <limits>
#include <numeric>

#include "primitive_boxes.hpp"

namespace mlshell::contact_detail {

namespace {

constexpr int kLeafSize = 4;

class BoxTree {
 public:
  explicit BoxTree(const std::vector<Box>& boxes) : boxes_(boxes), order_(boxes.size()) {
    std::iota(order_.begin(), order_.end(), 0);
    nodes_.reserve(2 * boxes.size() / kLeafSize + 2);
    if (!boxes.empty()) build(0, static_cast<int>(boxes.size()));
  }

  /// Calls report(i) for every box i that overlaps `query`.
  template <class Report>
  void query(const Box& query, Report&& report) const {
    if (nodes_.empty()) return;
    int stack[128];
    int top = 0;
    stack[top++] = 0;
    while (top > 0) {
      const Node& n = nodes_[stack[--top]];
      if (!overlap(n.box, query)) continue;
      if (n.right < 0) {
        for (int i = n.begin; i < n.end; ++i)
          if (overlap(boxes_[order_[i]], query)) report(order_[i]);
      } else {
        stack[top++] = n.right;
        stack[top++] = n.left;
      }
    }
  }

 private:
  struct Node {
    Box box;
    int left = -1, right = -1;  ///< children; right < 0 for a leaf of order_[begin, end)
    int begin = 0, end = 0;
  };

  int build(int begin, int end) {
    constexpr double inf = std::numeric_limits<double>::infinity();
    const int id = static_cast<int>(nodes_.size());
    nodes_.push_back({});
    Box box{{inf, inf, inf}, {-inf, -inf, -inf}};
    std::array<double, 3> clo = box.lo, chi = box.hi;  // bounds of the centres (doubled)
    for (int i = begin; i < end; ++i) {
      const Box& b = boxes_[order_[i]];
      for (int k = 0; k < 3; ++k) {
        box.lo[k] = std::min(box.lo[k], b.lo[k]), box.hi[k] = std::max(box.hi[k], b.hi[k]);
        const double c = b.lo[k] + b.hi[k];
        clo[k] = std::min(clo[k], c), chi[k] = std::max(chi[k], c);
      }
    }
    nodes_[id].box = box;
    nodes_[id].begin = begin, nodes_[id].end = end;
    if (end - begin <= kLeafSize) return id;
    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if (chi[k] - clo[k] > chi[axis] - clo[axis]) axis = k;
    const int mid = begin + (end - begin) / 2;
    std::nth_element(order_.begin() + begin, order_.begin() + mid, order_.begin() + end,
                     [&](int a, int b) {
                       const double ca = boxes_[a].lo[axis] + boxes_[a].hi[axis];
                       const double cb = boxes_[b].lo[axis] + boxes_[b].hi[axis];
                       return ca != cb ? ca < cb : a < b;
                     });
    const int left = build(begin, mid);
    const int right = build(mid, end);
    nodes_[id].left = left, nodes_[id].right = right;
    return id;
  }

  const std::vector<Box>& boxes_;
  std::vector<int> order_;
  std::vector<Node> nodes_;
};

}  // namespace

ContactCandidates bvh_candidates(const ContactSurface& surface, const PrimitiveBoxes& boxes) {
  ContactCandidates out;
  const BoxTree faces(boxes.faces);
  for (int v = 0; v < static_cast<int>(boxes.vertices.size()); ++v)
    faces.query(boxes.vertices[v], [&](int f) {
      if (!face_has_vertex(surface.faces[f], v)) out.point_triangle.push_back({v, f});
    });
  const BoxTree edges(boxes.edges);
  for (int a = 0; a < static_cast<int>(boxes.edges.size()); ++a)
    edges.query(boxes.edges[a], [&](int b) {
      if (a < b && !edges_share_vertex(surface.edges[a], surface.edges[b]))
        out.edge_edge.push_back({a, b});
    });
  std::sort(out.point_triangle.begin(), out.point_triangle.end());
  std::sort(out.edge_edge.begin(), out.edge_edge.end());
  return out;
}

}  // namespace mlshell::contact_detail
