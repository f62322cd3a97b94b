// Limit-surface basis functions: bicubic B-splines on regular faces, OpenSubdiv limit stencils
// (feature-adaptive, isolation level 4) on faces touching extraordinary vertices.
#include <opensubdiv/far/ptexIndices.h>
#include <opensubdiv/far/stencilTable.h>
#include <opensubdiv/far/stencilTableFactory.h>
#include <opensubdiv/far/topologyDescriptor.h>
#include <opensubdiv/far/topologyRefinerFactory.h>

#include <algorithm>
#include <map>
#include <stdexcept>
#include <utility>

#include "mlshell/subdivision/limit_basis.hpp"

namespace mlshell {

namespace Far = OpenSubdiv::Far;
namespace Sdc = OpenSubdiv::Sdc;

Point3 PointBasis::apply(int d, const std::vector<Point3>& q) const {
  Point3 x = Point3::Zero();
  for (int i = 0; i < size(); ++i) x += w[d][i] * q[nodes[i]];
  return x;
}

namespace {

/// Uniform cubic B-spline basis B_0..B_3 on [0,1] and its first two derivatives.
void cubic_bspline(double t, double b[3][4]) {
  const double s = 1.0 - t;
  b[0][0] = s * s * s / 6.0;
  b[0][1] = (3.0 * t * t * t - 6.0 * t * t + 4.0) / 6.0;
  b[0][2] = (-3.0 * t * t * t + 3.0 * t * t + 3.0 * t + 1.0) / 6.0;
  b[0][3] = t * t * t / 6.0;
  b[1][0] = -0.5 * s * s;
  b[1][1] = 1.5 * t * t - 2.0 * t;
  b[1][2] = -1.5 * t * t + t + 0.5;
  b[1][3] = 0.5 * t * t;
  b[2][0] = s;
  b[2][1] = 3.0 * t - 2.0;
  b[2][2] = -3.0 * t + 1.0;
  b[2][3] = t;
}

}  // namespace

void bicubic_bspline_basis(double u, double v, std::array<std::array<double, 16>, 6>& w) {
  double bu[3][4], bv[3][4];
  cubic_bspline(u, bu);
  cubic_bspline(v, bv);
  // (du order, dv order) of each derivative slot.
  static constexpr int order[6][2] = {{0, 0}, {1, 0}, {0, 1}, {2, 0}, {1, 1}, {0, 2}};
  for (int d = 0; d < 6; ++d)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) w[d][i + 4 * j] = bu[order[d][0]][i] * bv[order[d][1]][j];
}

struct LimitEvaluator::OpenSubdivState {
  std::unique_ptr<Far::TopologyRefiner> refiner;
  std::vector<int> ptex_of_face;
};

namespace {

/// The 4×4 one-ring grid of a face whose corners all have valence 4, or false if the one-ring
/// is not a regular grid.
bool regular_grid(const QuadMesh& mesh, const QuadAdjacency& adj, int face,
                  std::array<int, 16>& grid) {
  const Quad& F = mesh.quads[face];
  for (int v : F)
    if (adj.valence(v) != 4 || adj.on_boundary(v)) return false;
  // For the directed edge a→b, the face across (the one with edge b→a, among b's few faces)
  // read as [b, a, x, y]: x is one step outward from a, y from b.
  auto across = [&](int a, int b, int& x, int& y) {
    for (int g : adj.vertex_faces(b)) {
      const Quad& G = mesh.quads[g];
      for (int m = 0; m < 4; ++m)
        if (G[m] == b && G[(m + 1) % 4] == a) {
          x = G[(m + 2) % 4];
          y = G[(m + 3) % 4];
          return true;
        }
    }
    return false;
  };
  grid.fill(-1);
  for (int r = 0; r < 4; ++r) {
    const int d0 = F[r], d1 = F[(r + 1) % 4];
    int p10, p20, p01, p00;
    if (!across(d0, d1, p10, p20) || !across(d0, p10, p01, p00)) return false;
    // Local grid (i', j') of rotation r maps to the face frame by r quarter turns,
    // (i, j) = (3 − j', i') per turn.
    auto place = [&](int i, int j, int node) {
      for (int k = 0; k < r; ++k) {
        const int ii = 3 - j, jj = i;
        i = ii;
        j = jj;
      }
      grid[i + 4 * j] = node;
    };
    place(1, 1, d0);
    place(1, 0, p10);
    place(2, 0, p20);
    place(0, 0, p00);
  }
  std::array<int, 16> sorted = grid;
  std::sort(sorted.begin(), sorted.end());
  return sorted.front() >= 0 && std::adjacent_find(sorted.begin(), sorted.end()) == sorted.end();
}

}  // namespace

LimitEvaluator::LimitEvaluator(const QuadMesh& mesh)
    : mesh_(mesh), regular_(mesh.num_faces(), 0), grid_(mesh.num_faces()) {
  const QuadAdjacency adj(mesh);
  for (int f = 0; f < mesh.num_faces(); ++f)
    if (!mesh.is_ghost(f)) regular_[f] = regular_grid(mesh, adj, f, grid_[f]);
}

LimitEvaluator::~LimitEvaluator() = default;

int LimitEvaluator::num_irregular_faces() const {
  int n = 0;
  for (int f = 0; f < mesh_.num_faces(); ++f) n += !mesh_.is_ghost(f) && !regular_[f];
  return n;
}

std::vector<PointBasis> LimitEvaluator::evaluate(const std::vector<SurfacePoint>& points,
                                                 BasisSlots slots) const {
  const int num_slots = slots == BasisSlots::kAll ? 6 : 1;
  std::vector<PointBasis> out(points.size());
  std::vector<size_t> irregular;
  std::array<std::array<double, 16>, 6> w;
  for (size_t p = 0; p < points.size(); ++p) {
    const SurfacePoint& sp = points[p];
    if (sp.face < 0 || sp.face >= mesh_.num_faces() || mesh_.is_ghost(sp.face))
      throw std::logic_error("LimitEvaluator: point on a ghost or missing face");
    if (!regular_[sp.face]) {
      irregular.push_back(p);
      continue;
    }
    bicubic_bspline_basis(sp.u, sp.v, w);
    PointBasis& b = out[p];
    b.nodes.assign(grid_[sp.face].begin(), grid_[sp.face].end());
    for (int d = 0; d < num_slots; ++d) b.w[d].assign(w[d].begin(), w[d].end());
  }
  if (irregular.empty()) return out;

  if (!osd_) {
    osd_ = std::make_unique<OpenSubdivState>();
    std::vector<int> verts_per_face(mesh_.num_faces(), 4);
    std::vector<Far::Index> indices;
    for (const Quad& q : mesh_.quads) indices.insert(indices.end(), q.begin(), q.end());
    Far::TopologyDescriptor desc;
    desc.numVertices = mesh_.num_points();
    desc.numFaces = mesh_.num_faces();
    desc.numVertsPerFace = verts_per_face.data();
    desc.vertIndicesPerFace = indices.data();
    Sdc::Options sdc;
    sdc.SetVtxBoundaryInterpolation(Sdc::Options::VTX_BOUNDARY_EDGE_ONLY);
    using Factory = Far::TopologyRefinerFactory<Far::TopologyDescriptor>;
    osd_->refiner.reset(Factory::Create(desc, Factory::Options(Sdc::SCHEME_CATMARK, sdc)));
    if (!osd_->refiner) throw MeshError("OpenSubdiv could not build the topology for evaluation");
    osd_->refiner->RefineAdaptive(Far::TopologyRefiner::AdaptiveOptions(4));
    Far::PtexIndices ptex(*osd_->refiner);
    osd_->ptex_of_face.resize(mesh_.num_faces());
    for (int f = 0; f < mesh_.num_faces(); ++f) osd_->ptex_of_face[f] = ptex.GetFaceId(f);
  }
  using Factory = Far::LimitStencilTableFactoryReal<double>;
  std::vector<double> s(irregular.size()), t(irregular.size());
  Factory::LocationArrayVec locations(irregular.size());
  for (size_t k = 0; k < irregular.size(); ++k) {
    const SurfacePoint& sp = points[irregular[k]];
    s[k] = sp.u;
    t[k] = sp.v;
    locations[k].ptexIdx = osd_->ptex_of_face[sp.face];
    locations[k].numLocations = 1;
    locations[k].s = &s[k];
    locations[k].t = &t[k];
  }
  Factory::Options options;
  options.generate1stDerivatives = num_slots > 1;
  options.generate2ndDerivatives = num_slots > 1;
  std::unique_ptr<const Far::LimitStencilTableReal<double>> table(
      Factory::Create(*osd_->refiner, locations, nullptr, nullptr, options));
  if (!table || table->GetNumStencils() != static_cast<int>(irregular.size()))
    throw MeshError("OpenSubdiv could not evaluate limit stencils");
  const auto& sizes = table->GetSizes();
  const auto& offsets = table->GetOffsets();
  const auto& idx = table->GetControlIndices();
  const std::vector<double>* weights[6] = {&table->GetWeights(),    &table->GetDuWeights(),
                                           &table->GetDvWeights(),  &table->GetDuuWeights(),
                                           &table->GetDuvWeights(), &table->GetDvvWeights()};
  for (size_t k = 0; k < irregular.size(); ++k) {
    PointBasis& b = out[irregular[k]];
    // Merge repeated indices and drop exact zeros.
    std::map<int, std::array<double, 6>> merged;
    for (int e = offsets[k]; e < offsets[k] + sizes[k]; ++e) {
      auto& slot = merged[idx[e]];
      for (int d = 0; d < num_slots; ++d) slot[d] += (*weights[d])[e];
    }
    for (const auto& [node, ws] : merged) {
      if (std::all_of(ws.begin(), ws.end(), [](double x) { return x == 0.0; })) continue;
      b.nodes.push_back(node);
      for (int d = 0; d < num_slots; ++d) b.w[d].push_back(ws[d]);
    }
  }
  return out;
}

}  // namespace mlshell
