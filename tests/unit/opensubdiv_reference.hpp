// An independent reference for the subdivision levels: OpenSubdiv's own uniform Catmull–Clark
// refinement of a whole cage (every ghost layer kept), interpolated directly.
#pragma once

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

#include "mlshell/subdivision/quad_mesh.hpp"

namespace mlshell {

/// Points of levels 0..levels of OpenSubdiv's refinement of `cage` (boundary: edges only).
inline std::vector<std::vector<Point3>> opensubdiv_levels(const QuadMesh& cage, int levels) {
  struct Position {
    Point3 p = Point3::Zero();
    void Clear() { p.setZero(); }
    void AddWithWeight(const Position& src, double w) { p += w * src.p; }
  };
  namespace Far = OpenSubdiv::Far;
  std::vector<int> nverts(cage.num_faces(), 4);
  std::vector<Far::Index> idx;
  for (const Quad& q : cage.quads) idx.insert(idx.end(), q.begin(), q.end());
  Far::TopologyDescriptor desc;
  desc.numVertices = cage.num_points();
  desc.numFaces = cage.num_faces();
  desc.numVertsPerFace = nverts.data();
  desc.vertIndicesPerFace = idx.data();
  OpenSubdiv::Sdc::Options sdc;
  sdc.SetVtxBoundaryInterpolation(OpenSubdiv::Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
  using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
  std::unique_ptr<Far::TopologyRefiner> refiner(
      Factory::Create(desc, Factory::Options(OpenSubdiv::Sdc::SCHEME_CATMARK, sdc)));
  refiner->RefineUniform(Far::TopologyRefiner::UniformOptions(levels));
  std::vector<Position> current(cage.num_points());
  for (int i = 0; i < cage.num_points(); ++i) current[i].p = cage.points[i];
  std::vector<std::vector<Point3>> out(1, cage.points);
  for (int l = 1; l <= levels; ++l) {
    std::vector<Position> next(refiner->GetLevel(l).GetNumVertices());
    Far::PrimvarRefinerReal<double>(*refiner).Interpolate(l, current, next);
    current = std::move(next);
    out.emplace_back();
    for (const Position& q : current) out.back().push_back(q.p);
  }
  return out;
}

/// The largest distance from a point of `points` to its nearest point of `reference`.
inline double farthest_from(const std::vector<Point3>& points,
                            const std::vector<Point3>& reference) {
  double worst = 0.0;
  for (const Point3& p : points) {
    double best = INFINITY;
    for (const Point3& q : reference) best = std::min(best, (q - p).norm());
    worst = std::max(worst, best);
  }
  return worst;
}

}  // namespace mlshell
