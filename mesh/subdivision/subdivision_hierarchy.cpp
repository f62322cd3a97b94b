// Uniform Catmull–Clark refinement with OpenSubdiv; each level keeps its interior faces plus the
// faces touching them (one ghost ring). The kept control points of level l+1 depend only on kept
// points of level l (the outer ghost ring never feeds the inner one), which is checked here.
#include "mlshell/subdivision/subdivision_hierarchy.hpp"

#include <opensubdiv/far/primvarRefiner.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <utility>

#include "reverse_subdivision.hpp"

namespace mlshell {

namespace {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

/// A refined point as a sparse combination of the previous level's points (PrimvarRefiner
/// buffer type). Rules may add already computed child points, so rows compose. A row has a
/// few dozen terms at most, so a linear search beats a map; sorted() orders them by point.
struct SparseRow {
  std::vector<std::pair<int, double>> weights;
  void Clear() { weights.clear(); }
  void AddWithWeight(const SparseRow& src, double w) {
    for (const auto& [i, x] : src.weights) {
      auto it = std::find_if(weights.begin(), weights.end(),
                             [i = i](const std::pair<int, double>& t) { return t.first == i; });
      if (it == weights.end())
        weights.emplace_back(i, w * x);
      else
        it->second += w * x;
    }
  }
  const std::vector<std::pair<int, double>>& sorted() {
    std::sort(weights.begin(), weights.end());
    return weights;
  }
};

std::unique_ptr<Far::TopologyRefiner> make_refiner(const QuadMesh& mesh) {
  std::vector<int> verts_per_face(mesh.num_faces(), 4);
  std::vector<Far::Index> indices;
  indices.reserve(4 * mesh.num_faces());
  for (const Quad& q : mesh.quads) indices.insert(indices.end(), q.begin(), q.end());
  Far::TopologyDescriptor desc;
  desc.numVertices = mesh.num_points();
  desc.numFaces = mesh.num_faces();
  desc.numVertsPerFace = verts_per_face.data();
  desc.vertIndicesPerFace = indices.data();
  Sdc::Options sdc;
  sdc.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
  using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
  std::unique_ptr<Far::TopologyRefiner> refiner(
      Factory::Create(desc, Factory::Options(Sdc::SCHEME_CATMARK, sdc)));
  if (!refiner) throw MeshError("OpenSubdiv could not build the cage topology");
  return refiner;
}

/// Faces to keep: interior faces and faces sharing a vertex with one.
std::vector<char> kept_faces(const std::vector<Quad>& quads, const std::vector<char>& interior,
                             int num_points) {
  std::vector<char> touches(num_points, 0), keep(quads.size(), 0);
  for (size_t f = 0; f < quads.size(); ++f)
    if (interior[f])
      for (int v : quads[f]) touches[v] = 1;
  for (size_t f = 0; f < quads.size(); ++f)
    for (int v : quads[f]) keep[f] |= touches[v];
  return keep;
}

}  // namespace

SubdivisionHierarchy::SubdivisionHierarchy(const QuadMesh& cage, int refinements) {
  // Level 0 is the cage trimmed to one ghost ring.
  std::vector<char> interior(cage.num_faces());
  for (int f = 0; f < cage.num_faces(); ++f) interior[f] = !cage.is_ghost(f);
  QuadMesh current = cage;
  {
    const auto keep = kept_faces(cage.quads, interior, cage.num_points());
    std::vector<int> remap(cage.num_points(), -1);
    QuadMesh trimmed;
    for (int f = 0; f < cage.num_faces(); ++f) {
      if (!keep[f]) continue;
      Quad q = cage.quads[f];
      for (int& v : q) {
        if (remap[v] < 0) {
          remap[v] = trimmed.num_points();
          trimmed.points.push_back(cage.points[v]);
        }
        v = remap[v];
      }
      trimmed.quads.push_back(q);
      trimmed.ghost.push_back(cage.ghost[f]);
    }
    current = std::move(trimmed);
  }
  levels_.push_back(current);

  for (int l = 0; l < refinements; ++l) {
    // Refine the kept level once: children of interior faces are interior.
    auto refiner = make_refiner(current);
    refiner->RefineUniform(Far::TopologyRefiner::UniformOptions(1));
    const Far::TopologyLevel& coarse = refiner->GetLevel(0);
    const Far::TopologyLevel& fine = refiner->GetLevel(1);
    std::vector<Quad> fine_quads(fine.GetNumFaces());
    std::vector<char> fine_interior(fine.GetNumFaces(), 0);
    for (int f = 0; f < fine.GetNumFaces(); ++f) {
      auto fv = fine.GetFaceVertices(f);
      fine_quads[f] = {fv[0], fv[1], fv[2], fv[3]};
    }
    for (int f = 0; f < coarse.GetNumFaces(); ++f) {
      if (current.is_ghost(f)) continue;
      for (int c : coarse.GetFaceChildFaces(f)) fine_interior[c] = 1;
    }
    std::vector<SparseRow> src(current.num_points()), dst(fine.GetNumVertices());
    for (int i = 0; i < current.num_points(); ++i) src[i].weights.emplace_back(i, 1.0);
    Far::PrimvarRefinerReal<double>(*refiner).Interpolate(1, src, dst);

    const auto keep = kept_faces(fine_quads, fine_interior, fine.GetNumVertices());
    std::vector<int> remap(fine.GetNumVertices(), -1);
    QuadMesh next;
    std::vector<Eigen::Triplet<double>> triplets;
    std::vector<int> parents;
    for (int f = 0; f < fine.GetNumFaces(); ++f) {
      if (!keep[f]) continue;
      parents.push_back(fine.GetFaceParentFace(f));
      Quad q = fine_quads[f];
      for (int& v : q) {
        if (remap[v] < 0) {
          remap[v] = next.num_points();
          Point3 p = Point3::Zero();
          for (const auto& [i, w] : dst[v].sorted()) {
            p += w * current.points[i];
            triplets.emplace_back(remap[v], i, w);
          }
          next.points.push_back(p);
        }
        v = remap[v];
      }
      next.quads.push_back(q);
      next.ghost.push_back(fine_interior[f] ? 0 : 1);
    }
    SubdivisionMatrix S(next.num_points(), current.num_points());
    S.setFromTriplets(triplets.begin(), triplets.end());
    S.prune(0.0);
    subdivision_.push_back(std::move(S));
    reverse_.push_back(build_reverse_subdivision(*refiner, current, remap, next.num_points()));
    parent_face_.push_back(std::move(parents));
    levels_.push_back(next);
    current = std::move(next);
  }
}

}  // namespace mlshell
