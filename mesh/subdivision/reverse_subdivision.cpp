// Reverse subdivision (paper §5.3.2, Appendices B and C): a sparse projection Q_{l+1}^l of fine
// control points onto the coarse level that is exact on subdivided data, Q S = I.
//
// Interior coarse vertex v of valence ϑ ≠ 3 (eq. 5.19 with 5.21), from its own child v', the
// child edge points e' of its ϑ edges and the child face points f' of its ϑ faces:
//   v = c1 v' + c2 Σ e' + c3 Σ f',  c1 = ϑ/(ϑ−3), c2 = −4/(ϑ(ϑ−3)), c3 = 1/(ϑ(ϑ−3)).
// Ghost vertices (whose own children were trimmed away) and valence-3 vertices (where 5.20 is
// singular) use the edge-point rule (B.2) along an edge to an already reconstructed vertex w,
//   v = 4 e' − w − f'_1 − f'_2,
// and corner ghosts the face-point rule (B.4), v = N f' − Σ (the face's other vertices).
#include "reverse_subdivision.hpp"

#include <map>
#include <string>

namespace mlshell {

namespace Far = OpenSubdiv::Far;

SubdivisionMatrix build_reverse_subdivision(const Far::TopologyRefiner& refiner,
                                            const QuadMesh& coarse,
                                            const std::vector<int>& fine_kept, int num_fine) {
  const Far::TopologyLevel& level = refiner.GetLevel(0);
  const int n = coarse.num_points();
  using Row = std::map<int, double>;
  std::vector<Row> rows(n);
  std::vector<char> done(n, 0), ghost(n, 1);
  for (int f = 0; f < coarse.num_faces(); ++f)
    if (!coarse.is_ghost(f))
      for (int v : coarse.quads[f]) ghost[v] = 0;

  auto kept = [&](int refined) { return fine_kept[refined]; };
  auto add = [](Row& row, const Row& other, double w) {
    for (const auto& [i, x] : other) row[i] += w * x;
  };
  // Eq. (5.19) for interior vertices of valence other than 3.
  for (int v = 0; v < n; ++v) {
    const auto edges = level.GetVertexEdges(v);
    const auto faces = level.GetVertexFaces(v);
    const int valence = edges.size();
    if (ghost[v] || valence == 3 || faces.size() != edges.size()) continue;
    const double t = static_cast<double>(valence);
    const double c1 = t / (t - 3.0), c2 = -4.0 / (t * (t - 3.0)), c3 = 1.0 / (t * (t - 3.0));
    Row row;
    bool complete = kept(level.GetVertexChildVertex(v)) >= 0;
    if (complete) row[kept(level.GetVertexChildVertex(v))] += c1;
    for (int e : edges) {
      const int child = kept(level.GetEdgeChildVertex(e));
      complete = complete && child >= 0;
      if (child >= 0) row[child] += c2;
    }
    for (int f : faces) {
      const int child = kept(level.GetFaceChildVertex(f));
      complete = complete && child >= 0;
      if (child >= 0) row[child] += c3;
    }
    if (complete) rows[v] = std::move(row), done[v] = 1;
  }
  // (B.2) and (B.4), repeated while vertices remain that can be reached from reconstructed ones.
  for (bool progress = true; progress;) {
    progress = false;
    for (int v = 0; v < n; ++v) {
      if (done[v]) continue;
      for (int e : level.GetVertexEdges(v)) {
        const auto ev = level.GetEdgeVertices(e);
        const int w = ev[0] == v ? ev[1] : ev[0];
        const auto ef = level.GetEdgeFaces(e);
        const int child = kept(level.GetEdgeChildVertex(e));
        if (!done[w] || child < 0 || ef.size() != 2) continue;
        const int f1 = kept(level.GetFaceChildVertex(ef[0]));
        const int f2 = kept(level.GetFaceChildVertex(ef[1]));
        if (f1 < 0 || f2 < 0) continue;
        Row row{{child, 4.0}};
        add(row, rows[w], -1.0);
        row[f1] -= 1.0;
        row[f2] -= 1.0;
        rows[v] = std::move(row);
        done[v] = progress = true;
        break;
      }
      if (done[v]) continue;
      for (int f : level.GetVertexFaces(v)) {
        const int child = kept(level.GetFaceChildVertex(f));
        const auto fv = level.GetFaceVertices(f);
        bool ready = child >= 0;
        for (int u : fv) ready = ready && (u == v || done[u]);
        if (!ready) continue;
        Row row{{child, static_cast<double>(fv.size())}};
        for (int u : fv)
          if (u != v) add(row, rows[u], -1.0);
        rows[v] = std::move(row);
        done[v] = progress = true;
        break;
      }
    }
  }
  std::vector<Eigen::Triplet<double>> triplets;
  for (int v = 0; v < n; ++v) {
    if (!done[v])
      throw MeshError("reverse subdivision: control point " + std::to_string(v + 1) +
                      " cannot be reconstructed from the finer level");
    for (const auto& [i, w] : rows[v])
      if (w != 0.0) triplets.emplace_back(v, i, w);
  }
  SubdivisionMatrix Q(n, num_fine);
  Q.setFromTriplets(triplets.begin(), triplets.end());
  return Q;
}

}  // namespace mlshell
