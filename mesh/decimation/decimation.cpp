// Fine-to-coarse decimation hierarchies (paper 2 §4.1): quadric-error edge collapse with
// probabilistic plane quadrics (Garland and Heckbert 1997; Trettner and Kobbelt 2020), CGAL 5.5's
// Surface_mesh_simplification::edge_collapse with GarlandHeckbert_probabilistic_plane_policies,
// with every collapse recorded. CGAL stays in this translation unit (slow to compile;
// CGAL_EIGEN3_ENABLED is defined for this file only, in CMakeLists.txt).
//
// One CGAL::Surface_mesh is decimated level after level (finest → coarsest), so the records
// accumulate and level k is records[0, num_records). The mesh never collects garbage, so a
// Surface_mesh vertex keeps its index; `fine_of` maps it to the finest-mesh vertex that it stands
// for (the identity, except where a collapse that must keep a pinned vertex was carried out by
// CGAL on the other vertex of the edge: the survivor then takes the pinned vertex's index).
//
// Rules, each a refusal of one collapse (the edge comes back when its neighbourhood changes):
//   placement (Choice): a vertex of a group is never moved, and removed only into a neighbour
//     that belongs to exactly the same groups (so a side group loses vertices along its side,
//     a group never loses all of them, and a one-vertex group keeps its vertex); a boundary
//     vertex is never moved, and removed only along a boundary edge whose new edge (between its
//     two boundary neighbours) stays within boundary_deviation × its length of every fine
//     boundary vertex it replaces, so the boundary keeps the fine boundary's shape: straight
//     sides stay exact, corners stay, curved rims coarsen into chords; an interior edge with both ends
//     on the boundary is never collapsed (it would pinch or merge boundary loops), nor a
//     boundary edge of a loop of 3 vertices. Where a vertex must stay, the placement is its
//     position; elsewhere it is the quadric's optimum.
//   geometry (Fold_filter): no triangle around the edge turns its normal by more than
//     max_normal_change_degrees, and no new triangle gets an angle below
//     min(min_angle_degrees, the smallest angle around the edge before the collapse).
//   topology: CGAL's link condition. Each level is checked at the end: it passes
//     validate_triangle_mesh and keeps the fine mesh's Euler characteristic and boundary loops.
#include "mlshell/decimation/decimation.hpp"

#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_simplification/Edge_collapse_visitor_base.h>
#include <CGAL/Surface_mesh_simplification/Policies/Edge_collapse/GarlandHeckbert_probabilistic_plane_policies.h>
#include <CGAL/Surface_mesh_simplification/edge_collapse.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>

namespace mlshell {

namespace {

namespace SMS = CGAL::Surface_mesh_simplification;
using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using VertexIndex = Mesh::Vertex_index;
using Quadrics = SMS::GarlandHeckbert_probabilistic_plane_policies<Mesh, Kernel>;

constexpr double kDegree = std::numbers::pi / 180.0;

Point3 to_eigen(const Point& p) { return {p.x(), p.y(), p.z()}; }
Eigen::Vector3d vec(const Point& p) { return {p.x(), p.y(), p.z()}; }

/// The smallest angle of a triangle (radians): the one opposite its shortest edge.
double min_angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, bc = c - b, ca = a - c;
  const double lab = ab.squaredNorm(), lbc = bc.squaredNorm(), lca = ca.squaredNorm();
  // The angle at the corner opposite the shortest edge, between the two other edges.
  Eigen::Vector3d u, v;
  if (lab <= lbc && lab <= lca) {
    u = a - c, v = b - c;
  } else if (lbc <= lca) {
    u = b - a, v = c - a;
  } else {
    u = a - b, v = c - b;
  }
  return std::atan2(u.cross(v).norm(), u.dot(v));
}

/// A triangle rotated to start at its smallest vertex (orientation kept).
Triangle canonical(Triangle t) {
  const int k = static_cast<int>(std::min_element(t.begin(), t.end()) - t.begin());
  std::rotate(t.begin(), t.begin() + k, t.end());
  return t;
}

/// Everything the CGAL callbacks share (they are copied by value: each holds a pointer here).
struct State {
  const DecimationOptions* options = nullptr;
  std::vector<int> fine_of;       ///< Surface_mesh vertex index → finest-mesh vertex
  std::vector<char> boundary;     ///< by finest vertex: on the (fine = every level's) boundary
  std::vector<int> group_set;     ///< by finest vertex: 0, or an id of the set of its groups
  std::vector<int> loop_of;       ///< by finest vertex: its boundary loop, or -1
  std::vector<int> loop_size;     ///< current vertex count of each boundary loop
  std::vector<std::vector<int>> loops;  ///< the fine boundary loops, in order
  std::vector<int> loop_position;       ///< by finest vertex: its index in its loop
  std::vector<Eigen::Vector3d> fine_points;  ///< boundary vertices never move: their positions
  int num_vertices = 0;           ///< vertices left in the Surface_mesh
  int target = 0;                 ///< this level's vertex count
  double cos_max_normal_change = 0.5;
  double min_angle = 0.0;         ///< radians
  std::vector<CollapseRecord>* records = nullptr;
  // The collapse under way, between OnCollapsing and OnCollapsed.
  CollapseRecord pending;
  int pending_keep = -1;  ///< finest vertex that must survive it, or -1 for CGAL's choice
};

/// Which vertex of the edge v0–v1 must stay where it is.
enum class Keep { kRefused, kV0, kV1, kEither, kFree };

/// Whether boundary vertex v may go: the new boundary edge a–c of its two boundary neighbours
/// stays within `tolerance` × |ac| of every fine boundary vertex it replaces (v and those removed
/// before between a and c), each projecting inside the edge.
bool keeps_boundary_shape(const State& s, const Mesh& mesh, VertexIndex v, double tolerance) {
  for (auto h : CGAL::halfedges_around_target(v, mesh)) {
    if (!mesh.is_border(h)) continue;
    const int a = s.fine_of[mesh.source(h)], c = s.fine_of[mesh.target(mesh.next(h))];
    const int fv = s.fine_of[v];
    const std::vector<int>& loop = s.loops[s.loop_of[fv]];
    const int n = static_cast<int>(loop.size());
    // The fine vertices strictly between a and c on the side of v.
    bool forward = false;
    for (int j = (s.loop_position[a] + 1) % n; loop[j] != c; j = (j + 1) % n)
      forward = forward || loop[j] == fv;
    const int step = forward ? 1 : n - 1;
    const Eigen::Vector3d pa = s.fine_points[a], ac = s.fine_points[c] - pa;
    const double length2 = ac.squaredNorm();
    if (!(length2 > 0.0)) return false;
    for (int j = (s.loop_position[a] + step) % n; loop[j] != c; j = (j + step) % n) {
      const Eigen::Vector3d ap = s.fine_points[loop[j]] - pa;
      const double t = ap.dot(ac) / length2;
      if (t <= 0.0 || t >= 1.0 || (ap - t * ac).norm() > tolerance * std::sqrt(length2))
        return false;
    }
    return true;
  }
  return false;  // not on the boundary
}

/// The placement rules of the file header, on the current mesh.
template <class Profile>
Keep choose(const State& s, const Profile& profile) {
  const Mesh& mesh = profile.surface_mesh();
  const int f0 = s.fine_of[profile.v0()], f1 = s.fine_of[profile.v1()];
  const bool b0 = s.boundary[f0], b1 = s.boundary[f1];
  const int g0 = s.group_set[f0], g1 = s.group_set[f1];
  // A group vertex goes only into a vertex of the same groups; it never moves.
  const bool free0 = g0 == 0 || g0 == g1, free1 = g1 == 0 || g1 == g0;
  if (profile.is_v0_v1_a_border() || profile.is_v1_v0_a_border()) {
    if (s.loop_size[s.loop_of[f0]] <= 3) return Keep::kRefused;
    const double tol = s.options->boundary_deviation;
    const bool removable0 = free0 && keeps_boundary_shape(s, mesh, profile.v0(), tol);
    const bool removable1 = free1 && keeps_boundary_shape(s, mesh, profile.v1(), tol);
    if (removable0 && removable1) return Keep::kEither;
    if (removable1) return Keep::kV0;
    if (removable0) return Keep::kV1;
    return Keep::kRefused;
  }
  // An interior edge joining two boundary vertices (CGAL's link test refuses it too).
  if (b0 && b1) return Keep::kRefused;
  if (b0) return free1 ? Keep::kV0 : Keep::kRefused;
  if (b1) return free0 ? Keep::kV1 : Keep::kRefused;
  if (g0 != 0 && g1 != 0) return g0 == g1 ? Keep::kV0 : Keep::kRefused;
  if (g0 != 0) return Keep::kV0;
  if (g1 != 0) return Keep::kV1;
  return Keep::kFree;
}

/// The quadrics' placement, or the position of the vertex that must stay, or none.
struct Constrained_placement {
  const Quadrics* quadrics;
  const State* state;
  template <class Profile>
  boost::optional<Point> operator()(const Profile& profile) const {
    switch (choose(*state, profile)) {
      case Keep::kRefused: return boost::none;
      case Keep::kV0: return profile.p0();
      case Keep::kV1: return profile.p1();
      case Keep::kEither: {
        // Either boundary vertex may go: keep the one whose position costs less.
        const auto c0 = (*quadrics)(profile, boost::optional<Point>(profile.p0()));
        const auto c1 = (*quadrics)(profile, boost::optional<Point>(profile.p1()));
        return (c1 && c0 && *c1 < *c0) ? profile.p1() : profile.p0();
      }
      case Keep::kFree: break;
    }
    const boost::optional<Point> p = quadrics->get_placement()(profile);
    if (p && std::isfinite(p->x()) && std::isfinite(p->y()) && std::isfinite(p->z())) return p;
    return CGAL::midpoint(profile.p0(), profile.p1());
  }
};

/// Refuses collapses that fold or degenerate a triangle around the edge.
struct Fold_filter {
  const State* state;
  template <class Profile>
  boost::optional<Point> operator()(const Profile& profile, boost::optional<Point> op) const {
    if (!op) return op;
    const auto& triangles = profile.triangles();
    const auto v0 = profile.v0(), v1 = profile.v1();
    const Mesh& mesh = profile.surface_mesh();
    const Eigen::Vector3d q = vec(*op);
    double old_min = std::numeric_limits<double>::infinity();
    for (const auto& t : triangles)
      old_min = std::min(old_min, min_angle(vec(mesh.point(t.v0)), vec(mesh.point(t.v1)),
                                            vec(mesh.point(t.v2))));
    const double bound = std::min(state->min_angle, old_min) - 1e-9;
    for (const auto& t : triangles) {
      const std::array<VertexIndex, 3> v = {t.v0, t.v1, t.v2};
      int moved = 0;
      std::array<Eigen::Vector3d, 3> before, after;
      for (int k = 0; k < 3; ++k) {
        before[k] = vec(mesh.point(v[k]));
        after[k] = before[k];
        if (v[k] == v0 || v[k] == v1) after[k] = q, ++moved;
      }
      if (moved != 1) continue;  // a triangle on the edge: it goes
      const Eigen::Vector3d n0 = (before[1] - before[0]).cross(before[2] - before[0]);
      const Eigen::Vector3d n1 = (after[1] - after[0]).cross(after[2] - after[0]);
      if (n0.dot(n1) <= state->cos_max_normal_change * n0.norm() * n1.norm()) return boost::none;
      if (min_angle(after[0], after[1], after[2]) < bound) return boost::none;
    }
    return op;
  }
};

/// Stops at the level's vertex count.
struct Stop_at_target {
  const State* state;
  template <class FT, class Profile>
  bool operator()(const FT&, const Profile&, std::size_t, std::size_t) const {
    return state->num_vertices <= state->target;
  }
};

/// Records each collapse (finest-mesh indices) and keeps `fine_of` and the loop sizes current.
struct Recorder : SMS::Edge_collapse_visitor_base<Mesh> {
  State* state = nullptr;

  template <class Profile>
  void OnCollapsing(const Profile& profile, const boost::optional<Point>& placement) {
    State& s = *state;
    CollapseRecord& r = s.pending;
    r = CollapseRecord{};
    r.placement = to_eigen(*placement);
    // A pinned vertex is the one whose position is the placement (Constrained_placement).
    const Keep keep = choose(s, profile);
    s.pending_keep = -1;
    if (keep == Keep::kV0 || (keep == Keep::kEither && *placement == profile.p0()))
      s.pending_keep = s.fine_of[profile.v0()];
    else if (keep == Keep::kV1 || keep == Keep::kEither)
      s.pending_keep = s.fine_of[profile.v1()];
    const Mesh& mesh = profile.surface_mesh();
    for (const auto& t : profile.triangles())
      r.before.push_back(canonical({s.fine_of[t.v0], s.fine_of[t.v1], s.fine_of[t.v2]}));
    // Remember both ends' positions and indices (v0 first) until we know which survived.
    r.removed = s.fine_of[profile.v0()];
    r.kept = s.fine_of[profile.v1()];
    r.removed_at = to_eigen(mesh.point(profile.v0()));
    r.kept_from = to_eigen(mesh.point(profile.v1()));
  }

  template <class Profile>
  void OnCollapsed(const Profile& profile, const VertexIndex& survivor) {
    State& s = *state;
    CollapseRecord& r = s.pending;
    // r holds v0 as `removed`, v1 as `kept`; swap if v0 is the one that stays.
    const int cgal_kept = s.fine_of[survivor];
    const int kept = s.pending_keep >= 0 ? s.pending_keep : cgal_kept;
    if (kept == r.removed) {
      std::swap(r.removed, r.kept);
      std::swap(r.removed_at, r.kept_from);
    }
    s.fine_of[survivor] = r.kept;
    for (const Triangle& t : r.before) {
      const bool has_removed = std::find(t.begin(), t.end(), r.removed) != t.end();
      const bool has_kept = std::find(t.begin(), t.end(), r.kept) != t.end();
      if (has_removed && has_kept) continue;
      Triangle a = t;
      for (int& v : a)
        if (v == r.removed) v = r.kept;
      r.after.push_back(canonical(a));
    }
    --s.num_vertices;
    if (s.boundary[r.removed]) --s.loop_size[s.loop_of[r.removed]];
    s.records->push_back(std::move(r));
    r = CollapseRecord{};
  }
};

/// The Surface_mesh's current state as a level mesh (vertices in finest order, triangles rotated
/// to start at their smallest vertex and sorted), the fine mesh's groups mapped to it.
DecimationLevel extract_level(const Mesh& mesh, const State& s, const TriangleMesh& fine,
                              int num_records) {
  DecimationLevel level;
  level.num_records = num_records;
  std::vector<std::pair<int, VertexIndex>> alive;
  alive.reserve(mesh.number_of_vertices());
  for (VertexIndex v : mesh.vertices()) alive.emplace_back(s.fine_of[v], v);
  std::sort(alive.begin(), alive.end());
  std::vector<int> level_of(fine.points.size(), -1);
  std::vector<int> level_of_sm(mesh.num_vertices(), -1);
  for (int i = 0; i < static_cast<int>(alive.size()); ++i) {
    level.finest_vertex.push_back(alive[i].first);
    level.mesh.points.push_back(to_eigen(mesh.point(alive[i].second)));
    level_of[alive[i].first] = i;
    level_of_sm[alive[i].second] = i;
  }
  level.mesh.triangles.reserve(mesh.number_of_faces());
  for (auto f : mesh.faces()) {
    Triangle t{};
    int k = 0;
    for (VertexIndex v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) {
      if (k == 3) throw MeshError("decimation: a face with more than three vertices");
      t[k++] = level_of_sm[v];
    }
    level.mesh.triangles.push_back(canonical(t));
  }
  std::sort(level.mesh.triangles.begin(), level.mesh.triangles.end());
  for (const auto& [name, vertices] : fine.groups) {
    std::vector<int>& g = level.mesh.groups[name];
    for (int v : vertices)
      if (level_of[v] >= 0) g.push_back(level_of[v]);
  }
  return level;
}

/// FNV-1a, 64 bits.
struct Fnv {
  std::uint64_t h = 14695981039346656037ull;
  void bytes(const void* p, std::size_t n) {
    const auto* c = static_cast<const unsigned char*>(p);
    for (std::size_t i = 0; i < n; ++i) h = (h ^ c[i]) * 1099511628211ull;
  }
  void add(std::int64_t v) { bytes(&v, sizeof v); }
  void add(double x) {
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    bytes(&bits, sizeof bits);
  }
  void add(const Point3& p) { add(p.x()), add(p.y()), add(p.z()); }
  void add(const std::vector<Triangle>& ts) {
    add(static_cast<std::int64_t>(ts.size()));
    for (const Triangle& t : ts)
      for (int v : t) add(static_cast<std::int64_t>(v));
  }
};

template <class T>
[[noreturn]] void bad_option(const std::string& what, T value, const std::string& expected) {
  std::ostringstream m;
  m << "hierarchy: " << what << " " << value << " must be " << expected;
  throw std::invalid_argument(m.str());
}

}  // namespace

DecimationOptions DecimationOptions::by_ratio(int fine_vertices, int levels, double ratio) {
  if (levels < 2) bad_option("levels", levels, ">= 2");
  if (!(std::isfinite(ratio) && ratio > 1.0)) bad_option("ratio", ratio, "> 1");
  DecimationOptions o;
  double previous = fine_vertices;
  for (int k = 1; k < levels; ++k) {
    previous = std::round(previous / ratio);
    o.vertices.push_back(static_cast<int>(previous));
  }
  return o;
}

void DecimationOptions::validate(int fine_vertices) const {
  if (vertices.empty())
    bad_option("levels", vertices.size() + 1, ">= 2 (vertices names no coarse level)");
  for (size_t k = 0; k < vertices.size(); ++k) {
    const std::string name = "vertices[" + std::to_string(k) + "] =";
    if (vertices[k] < 4) bad_option(name, vertices[k], ">= 4");
    if (k == 0 && vertices[k] >= fine_vertices)
      bad_option(name, vertices[k], "< the fine mesh's " + std::to_string(fine_vertices) +
                                        " vertices");
    if (k > 0 && vertices[k] >= vertices[k - 1])
      bad_option(name, vertices[k],
                 "< vertices[" + std::to_string(k - 1) + "] = " + std::to_string(vertices[k - 1]) +
                     " (strictly decreasing)");
  }
  if (!(min_angle_degrees >= 0.0 && min_angle_degrees < 60.0))
    bad_option("min_angle_degrees", min_angle_degrees, "in [0, 60)");
  if (!(max_normal_change_degrees > 0.0 && max_normal_change_degrees <= 180.0))
    bad_option("max_normal_change_degrees", max_normal_change_degrees, "in (0, 180]");
  if (!(std::isfinite(boundary_deviation) && boundary_deviation >= 0.0 &&
        boundary_deviation < 0.5))
    bad_option("boundary_deviation", boundary_deviation, "a number in [0, 0.5)");
}

std::string DecimationHierarchy::fingerprint() const {
  Fnv f;
  f.add(static_cast<std::int64_t>(levels.size()));
  for (const DecimationLevel& l : levels) {
    f.add(static_cast<std::int64_t>(l.num_records));
    f.add(static_cast<std::int64_t>(l.mesh.points.size()));
    for (const Point3& p : l.mesh.points) f.add(p);
    f.add(l.mesh.triangles);
    for (int v : l.finest_vertex) f.add(static_cast<std::int64_t>(v));
  }
  f.add(static_cast<std::int64_t>(records.size()));
  for (const CollapseRecord& r : records) {
    f.add(static_cast<std::int64_t>(r.removed));
    f.add(static_cast<std::int64_t>(r.kept));
    f.add(r.removed_at), f.add(r.kept_from), f.add(r.placement);
    f.add(r.before), f.add(r.after);
  }
  std::ostringstream s;
  s << std::hex;
  s.width(16);
  s.fill('0');
  s << f.h;
  return s.str();
}

DecimationHierarchy decimate(const TriangleMesh& fine, const DecimationOptions& options) {
  options.validate(fine.num_points());
  validate_triangle_mesh(fine, "decimation: the fine mesh");
  const TriangleTopology topology(fine);
  const int euler = topology.euler_characteristic();
  const int num_loops = static_cast<int>(topology.boundary_loops().size());
  const int num_levels = static_cast<int>(options.vertices.size()) + 1;

  Mesh mesh;
  mesh.reserve(fine.num_points(), 3 * fine.num_triangles() / 2 + fine.num_points(),
               fine.num_triangles());
  for (const Point3& p : fine.points) mesh.add_vertex(Point(p.x(), p.y(), p.z()));
  for (const Triangle& t : fine.triangles)
    if (mesh.add_face(VertexIndex(t[0]), VertexIndex(t[1]), VertexIndex(t[2])) ==
        Mesh::null_face())
      throw MeshError("decimation: CGAL's Surface_mesh refuses a face of the fine mesh");

  DecimationHierarchy hierarchy;
  State s;
  s.options = &options;
  s.fine_of.resize(fine.points.size());
  for (int v = 0; v < fine.num_points(); ++v) s.fine_of[v] = v;
  s.boundary = topology.boundary_vertices();
  {  // number the distinct sets of groups the vertices belong to (1, 2, ...)
    std::vector<std::vector<int>> groups_of(fine.points.size());
    int g = 0;
    for (const auto& [name, vertices] : fine.groups) {
      for (int v : vertices) groups_of[v].push_back(g);
      ++g;
    }
    std::map<std::vector<int>, int> ids;
    s.group_set.assign(fine.points.size(), 0);
    for (size_t v = 0; v < groups_of.size(); ++v)
      if (!groups_of[v].empty())
        s.group_set[v] = ids.emplace(groups_of[v], static_cast<int>(ids.size()) + 1).first->second;
  }
  s.loop_of.assign(fine.points.size(), -1);
  s.loop_position.assign(fine.points.size(), -1);
  s.loops = topology.boundary_loops();
  s.fine_points.assign(fine.points.begin(), fine.points.end());
  for (int l = 0; l < num_loops; ++l) {
    for (size_t k = 0; k < s.loops[l].size(); ++k) {
      s.loop_of[s.loops[l][k]] = l;
      s.loop_position[s.loops[l][k]] = static_cast<int>(k);
    }
    s.loop_size.push_back(static_cast<int>(topology.boundary_loops()[l].size()));
  }
  s.num_vertices = fine.num_points();
  s.cos_max_normal_change = std::cos(options.max_normal_change_degrees * kDegree);
  s.min_angle = options.min_angle_degrees * kDegree;
  s.records = &hierarchy.records;

  std::vector<DecimationLevel> coarse;
  std::vector<double> seconds;
  for (size_t k = 0; k < options.vertices.size(); ++k) {
    const int level_number = num_levels - 2 - static_cast<int>(k);
    const auto start = std::chrono::steady_clock::now();
    s.target = options.vertices[k];
    Quadrics quadrics(mesh);
    Recorder recorder;
    recorder.state = &s;
    SMS::edge_collapse(mesh, Stop_at_target{&s},
                       CGAL::parameters::get_cost(quadrics.get_cost())
                           .get_placement(Constrained_placement{&quadrics, &s})
                           .filter(Fold_filter{&s})
                           .visitor(recorder));
    if (s.num_vertices > s.target) {
      std::ostringstream m;
      m << "decimation: level " << level_number << " of " << num_levels << " (0 coarsest): reached "
        << s.num_vertices << " vertices, target " << s.target
        << ": the remaining collapses would change the topology, the boundary or the groups, or "
           "fold triangles (min_angle_degrees "
        << options.min_angle_degrees << ", max_normal_change_degrees "
        << options.max_normal_change_degrees << ")";
      throw MeshError(m.str());
    }
    DecimationLevel level =
        extract_level(mesh, s, fine, static_cast<int>(hierarchy.records.size()));
    const std::string name = "decimation: level " + std::to_string(level_number);
    validate_triangle_mesh(level.mesh, name);
    const TriangleTopology level_topology(level.mesh);
    const int level_loops = static_cast<int>(level_topology.boundary_loops().size());
    if (level_topology.euler_characteristic() != euler || level_loops != num_loops) {
      std::ostringstream m;
      m << name << ": Euler characteristic " << level_topology.euler_characteristic() << " and "
        << level_loops << " boundary loops, the fine mesh's " << euler << " and " << num_loops;
      throw MeshError(m.str());
    }
    coarse.push_back(std::move(level));
    seconds.push_back(
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
  }

  for (size_t k = coarse.size(); k-- > 0;) {
    hierarchy.levels.push_back(std::move(coarse[k]));
    hierarchy.build_seconds.push_back(seconds[k]);
  }
  DecimationLevel finest;
  finest.mesh = fine;
  finest.finest_vertex.resize(fine.points.size());
  for (int v = 0; v < fine.num_points(); ++v) finest.finest_vertex[v] = v;
  hierarchy.levels.push_back(std::move(finest));
  hierarchy.build_seconds.push_back(0.0);
  return hierarchy;
}

}  // namespace mlshell
