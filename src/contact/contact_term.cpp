// IPC contact on distributed vectors (contact_term.hpp).
#include "mlshell/contact/contact_term.hpp"

#include <petsc/private/petscimpl.h>  // PetscObjectStateGet

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "mlshell/contact/barrier/adaptive_stiffness.hpp"
#include "mlshell/contact/barrier/barrier_pair_energy.hpp"
#include "mlshell/contact/broad_phase/broad_phase.hpp"
#include "mlshell/contact/distance/edge_edge.hpp"
#include "mlshell/contact/distance/edge_edge_mollifier.hpp"
#include "mlshell/contact/distance/point_triangle.hpp"
#include "mlshell/log_events.hpp"

namespace mlshell {

namespace {

using Box = Eigen::Matrix<double, 6, 1>;  // lo (3), hi (3)

/// The Verlet list's skin, as a fraction of the reach ξ + ĝ.
constexpr double kVerletSkin = 1.0;

/// κ doubles while the smallest gap is below this fraction of ĝ and shrinking.
constexpr double kCloseGap = 1e-2;

Box empty_box() {
  Box b;
  b << INFINITY, INFINITY, INFINITY, -INFINITY, -INFINITY, -INFINITY;
  return b;
}

void grow(Box& b, const Eigen::Vector3d& p) {
  b.head<3>() = b.head<3>().cwiseMin(p);
  b.tail<3>() = b.tail<3>().cwiseMax(p);
}

bool overlap(const Box& a, const Box& b, double margin) {
  for (int c = 0; c < 3; ++c)
    if (a[c] > b[3 + c] + margin || b[c] > a[3 + c] + margin) return false;
  return true;
}

}  // namespace

ContactTerm::ContactTerm(std::string name, const TriangleMesh& shell, const ParallelLayout& layout,
                         std::vector<TriangleMesh> obstacles, ContactSettings settings)
    : EnergyTerm(std::move(name)),
      layout_(layout),
      obstacles_(std::move(obstacles)),
      settings_(settings) {
  settings_.barrier = ContactBarrier::from(settings.barrier.thickness, settings.barrier.gap);
  settings_.ccd.validate();
  if (!(settings_.stiffness >= 0.0) || !std::isfinite(settings_.stiffness))
    throw std::invalid_argument("contact: the stiffness must be finite and >= 0");
  num_shell_points_ = shell.num_points();
  num_shell_faces_ = shell.num_triangles();
  if (!settings_.body_of_point.empty()) {
    if (settings_.body_of_point.size() != static_cast<std::size_t>(num_shell_points_))
      throw std::invalid_argument("contact: body_of_point needs one body per shell point");
    for (int b : settings_.body_of_point)
      if (b < 0 || b >= static_cast<int>(settings_.self_contact_of_body.size()))
        throw std::invalid_argument("contact: a body without a self_contact_of_body entry");
  }
  std::vector<std::array<int, 3>> faces(shell.triangles.begin(), shell.triangles.end());
  rest_.assign(shell.points.begin(), shell.points.end());
  for (std::size_t k = 0; k < obstacles_.size(); ++k) {
    const TriangleMesh& o = obstacles_[k];
    const int offset = static_cast<int>(rest_.size());
    obstacle_of_.insert(obstacle_of_.end(), o.points.size(), static_cast<int>(k));
    obstacle_first_.push_back(offset);
    rest_.insert(rest_.end(), o.points.begin(), o.points.end());
    for (const Triangle& t : o.triangles)
      faces.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  }
  surface_ = ContactSurface::from_faces(static_cast<int>(rest_.size()), std::move(faces));
  // Shell edges come first: their vertices are below every obstacle vertex.
  num_shell_edges_ =
      static_cast<int>(std::count_if(surface_.edges.begin(), surface_.edges.end(),
                                     [&](const auto& e) { return e[1] < num_shell_points_; }));
  edge_owner_.assign(num_shell_edges_, std::numeric_limits<int>::max());
  for (int f = 0; f < num_shell_faces_; ++f) {
    const auto& t = surface_.faces[f];
    for (int k = 0; k < 3; ++k) {
      const std::array<int, 2> e{std::min(t[k], t[(k + 1) % 3]), std::max(t[k], t[(k + 1) % 3])};
      const auto it = std::lower_bound(surface_.edges.begin(), surface_.edges.end(), e);
      int& owner = edge_owner_[it - surface_.edges.begin()];
      owner = std::min(owner, layout_.face_owner(f));
    }
  }
  update_obstacle_boxes();
  const int rank = layout_.rank(), size = layout_.size();
  block_first_.resize(size + 1);
  const int owned_first = layout_.first_owned(), owned = layout_.num_owned_points();
  PetscCallAbort(layout_.comm(), MPI_Allgather(&owned_first, 1, MPI_INT, block_first_.data(), 1,
                                               MPI_INT, layout_.comm()));
  PetscCallAbort(layout_.comm(),
                 MPI_Allreduce(&owned, &block_first_[size], 1, MPI_INT, MPI_SUM, layout_.comm()));
  for (int l = 0; l < layout_.num_owned_points(); ++l)
    own_vertices_.push_back(layout_.local_points()[l]);
  for (int e = 0; e < num_shell_edges_; ++e)
    if (edge_owner_[e] == rank) own_edges_.push_back(e);
  own_faces_ = layout_.local_elements();
  std::vector<char> used(num_shell_points_, 0);
  for (int v : own_vertices_) used[v] = 1;
  for (int e : own_edges_)
    for (int v : surface_.edges[e]) used[v] = 1;
  for (int f : own_faces_)
    for (int v : surface_.faces[f]) used[v] = 1;
  for (int v = 0; v < num_shell_points_; ++v)
    if (used[v]) {
      const int l = layout_.local_of(v);
      if (l < 0) throw std::logic_error("contact: a vertex of an own primitive is not local");
      own_box_points_.push_back(l);
    }
  if (settings_.stiffness > 0.0) {
    kappa_ = kappa_max_ = settings_.stiffness;
  } else {
    // One pair at half the gap holds the force per vertex: κ |b_ξ'(d½)| 2√d½ = f.
    const double half = settings_.barrier.thickness + 0.5 * settings_.barrier.gap;
    const double holding = std::abs(settings_.barrier.first_derivative(half * half)) * 2.0 * half;
    // Massless shells (quasistatic scenes may have no density) have no κ_min.
    const double by_mass = settings_.average_mass > 0.0
                               ? min_barrier_stiffness(settings_.barrier, settings_.bbox_diagonal,
                                                       settings_.average_mass)
                               : 0.0;
    kappa_ = std::max(by_mass, settings_.vertex_force / holding);
    if (!(kappa_ > 0.0) || !std::isfinite(kappa_))
      throw std::invalid_argument(
          "contact: no barrier stiffness follows from the scene (no "
          "mass and no force); give `stiffness`");
    kappa_max_ = std::max(100.0 * kappa_, settings_.max_vertex_force / holding);
  }
}

const Point3& ContactTerm::obstacle_point(int v) const {
  const int k = obstacle_of_[v - num_shell_points_];
  return obstacles_[k].points[v - obstacle_first_[k]];
}

void ContactTerm::update_obstacle_boxes() {
  obstacle_boxes_.clear();
  for (std::size_t f = num_shell_faces_; f < surface_.faces.size(); ++f) {
    Box b = empty_box();
    for (int v : surface_.faces[f]) {
      grow(b, obstacle_point(v));
      if (!obstacle_dx_.empty()) grow(b, obstacle_point(v) + obstacle_dx_[v - num_shell_points_]);
    }
    obstacle_boxes_.push_back(b);
  }
}

void ContactTerm::move_obstacles(const std::vector<std::vector<Point3>>& points) {
  if (points.size() != obstacles_.size())
    throw std::logic_error("contact: move_obstacles needs a place for every obstacle");
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (points[k].size() != obstacles_[k].points.size())
      throw std::logic_error("contact: move_obstacles needs a place for every vertex");
    obstacles_[k].points = points[k];
  }
  update_obstacle_boxes();
  prepared_ = false;
  ++revision_;
}

void ContactTerm::set_obstacle_motion(const std::vector<std::vector<Point3>>* points) {
  obstacle_dx_.clear();
  if (points)
    for (std::size_t k = 0; k < obstacles_.size(); ++k)
      for (std::size_t i = 0; i < obstacles_[k].points.size(); ++i)
        obstacle_dx_.push_back(points->at(k).at(i) - obstacles_[k].points[i]);
  update_obstacle_boxes();
  prepared_ = false;
}

PetscErrorCode ContactTerm::obstacle_step_limit(Vec u, Vec du,
                                                const std::vector<std::vector<Point3>>& points,
                                                double* alpha) {
  PetscFunctionBeginUser;
  set_obstacle_motion(&points);
  PetscErrorCode ierr = prepare(u, du);
  double mine = ierr ? 0.0 : max_step({}, {});
  set_obstacle_motion(nullptr);
  PetscCall(ierr);
  PetscCallMPI(MPI_Allreduce(&mine, alpha, 1, MPI_DOUBLE, MPI_MIN, layout_.comm()));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactTerm::carry(Vec u, const std::vector<std::vector<Point3>>& points,
                                  const std::vector<char>& moving,
                                  const std::function<Point3(int, const Point3&)>& place, Vec du) {
  PetscFunctionBeginUser;
  // The obstacles' move against the shell at rest (du = 0): the swept pairs.
  PetscCall(VecZeroEntries(du));
  set_obstacle_motion(&points);
  const PetscErrorCode ierr = prepare(u, du);
  // Each shell vertex that a moving obstacle would reach at t (its time of impact) is pushed by
  // the fraction 1 − t/2 of that obstacle's rigid motion, the largest over its pairs: it keeps
  // ahead of the obstacle with half of the safe approach to spare.
  std::vector<double> fraction(x_.size(), 0.0);
  std::vector<int> pushed_by(x_.size(), -1);
  const std::vector<Pair> none;
  for (const Pair& p : ierr || !finite_ ? none : pairs_) {
    int k = -1;
    for (int c : p.v)
      if (vertex_id_[c] >= num_shell_points_) k = obstacle_of_[vertex_id_[c] - num_shell_points_];
    if (k < 0 || !moving.at(k)) continue;
    const Vector12 x0 = stencil(p, 0.0), dx = stencil(p, 1.0) - x0;
    const CcdResult r =
        p.edge_edge ? edge_edge_ccd(x0, dx, settings_.barrier.thickness, 1.0, settings_.ccd)
                    : point_triangle_ccd(x0, dx, settings_.barrier.thickness, 1.0, settings_.ccd);
    if (!r.may_collide) continue;
    for (int c : p.v)
      if (vertex_id_[c] < num_shell_points_ && 1.0 - 0.5 * r.toi > fraction[c])
        fraction[c] = 1.0 - 0.5 * r.toi, pushed_by[c] = k;
  }
  set_obstacle_motion(nullptr);
  PetscCall(ierr);
  // Each pushed vertex goes to its owner as (PETSc block, fraction, obstacle), and the owner
  // keeps the largest fraction (the lowest obstacle among equals): the same push on any number
  // of ranks, whichever ranks own the pairs.
  const int owned_first = layout_.first_owned(), owned = layout_.num_owned_points();
  std::vector<std::vector<double>> send(layout_.size());
  for (std::size_t c = 0; c < x_.size(); ++c) {
    if (pushed_by[c] < 0 || block_index_[c] < 0) continue;
    const int r = owner_of_block(block_index_[c]);
    send[r].insert(send[r].end(), {double(block_index_[c]), fraction[c], double(pushed_by[c])});
  }
  std::vector<double> received;
  PetscCall(exchange(send, received));
  std::vector<double> best(owned, 0.0);
  std::vector<int> by(owned, -1);
  for (std::size_t i = 0; i < received.size(); i += 3) {
    const int l = static_cast<int>(received[i]) - owned_first;
    const int k = static_cast<int>(received[i + 2]);
    const double f = received[i + 1];
    if (f > best[l] || (f == best[l] && by[l] >= 0 && k < by[l])) best[l] = f, by[l] = k;
  }
  std::vector<double> ul;
  PetscCall(layout_.to_local(u, ul));
  PetscScalar* d;
  PetscCall(VecGetArray(du, &d));
  for (int l = 0; l < owned; ++l) {
    if (by[l] < 0) continue;
    const Eigen::Vector3d x =
        rest_[layout_.local_points()[l]] + Eigen::Vector3d(ul[3 * l], ul[3 * l + 1], ul[3 * l + 2]);
    const Eigen::Vector3d step = best[l] * (place(by[l], x) - x);
    for (int k = 0; k < 3; ++k) d[3 * l + k] = step[k];
  }
  PetscCall(VecRestoreArray(du, &d));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactTerm::exchange(const std::vector<std::vector<double>>& send,
                                     std::vector<double>& received) const {
  PetscFunctionBeginUser;
  const int size = layout_.size();
  std::vector<int> send_counts(size), recv_counts(size), send_displs(size, 0), recv_displs(size, 0);
  for (int r = 0; r < size; ++r) send_counts[r] = static_cast<int>(send[r].size());
  PetscCallMPI(
      MPI_Alltoall(send_counts.data(), 1, MPI_INT, recv_counts.data(), 1, MPI_INT, layout_.comm()));
  std::vector<double> flat;
  for (int r = 0; r < size; ++r) {
    if (r > 0) {
      send_displs[r] = send_displs[r - 1] + send_counts[r - 1];
      recv_displs[r] = recv_displs[r - 1] + recv_counts[r - 1];
    }
    flat.insert(flat.end(), send[r].begin(), send[r].end());
  }
  received.resize(recv_displs[size - 1] + recv_counts[size - 1]);
  PetscCallMPI(MPI_Alltoallv(flat.data(), send_counts.data(), send_displs.data(), MPI_DOUBLE,
                             received.data(), recv_counts.data(), recv_displs.data(), MPI_DOUBLE,
                             layout_.comm()));
  PetscFunctionReturn(0);
}

PetscErrorCode ContactTerm::prepare(Vec u, Vec du) {
  PetscFunctionBeginUser;
  // The same state prepared again (an objective and then a Hessian at one iterate): nothing to
  // do. A vector's id and state change with every write to it.
  PetscObjectId id;
  PetscObjectState state;
  PetscCall(PetscObjectGetId((PetscObject)u, &id));
  PetscCall(PetscObjectStateGet((PetscObject)u, &state));
  if (!du && !swept_ && prepared_ && id == prepared_id_ && state == prepared_state_)
    PetscFunctionReturn(0);
  const LogEventScope event(du ? "Contact:swept" : "Contact:proximity");
  swept_ = du != nullptr;
  prepared_ = !swept_, prepared_id_ = id, prepared_state_ = state;
  std::vector<double> ul, dl;
  PetscCall(layout_.to_local(u, ul));
  if (swept_) PetscCall(layout_.to_local(du, dl));
  // A non-finite iterate or step (a failed linear solve) has no pairs: its energy is +∞ and its
  // step limit 0, on every rank alike, and the broad phase never sees it.
  int finite = std::all_of(ul.begin(), ul.end(), [](double v) { return std::isfinite(v); }) &&
               std::all_of(dl.begin(), dl.end(), [](double v) { return std::isfinite(v); });
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, &finite, 1, MPI_INT, MPI_LAND, layout_.comm()));
  finite_ = finite;
  if (!finite_) {
    pairs_.clear();
    PetscFunctionReturn(0);
  }
  const auto& points = layout_.local_points();
  auto position = [&](int l) {
    return Eigen::Vector3d(rest_[points[l]] +
                           Eigen::Vector3d(ul[3 * l], ul[3 * l + 1], ul[3 * l + 2]));
  };
  auto motion = [&](int l) {
    return swept_ ? Eigen::Vector3d(dl[3 * l], dl[3 * l + 1], dl[3 * l + 2])
                  : Eigen::Vector3d::Zero();
  };
  const double reach = settings_.barrier.thickness + settings_.barrier.gap;
  const int size = layout_.size(), rank = layout_.rank();

  // Halo: every rank's box of its own primitives, then the vertices of own primitives that
  // come within reach of another rank's box.
  Box mine = empty_box();
  for (int l : own_box_points_) {
    grow(mine, position(l));
    grow(mine, position(l) + motion(l));
  }
  // The proximity pairs are kept as a Verlet list, found within reach + 2 skin and reused
  // while every vertex stays within the skin of where it was then: a pair within reach now was
  // within reach + 2 skin then. The halo and the obstacles' culling see as far.
  const double skin = kVerletSkin * reach, list_reach = reach + (swept_ ? 0.0 : 2.0 * skin);
  // A margin of rounding on top of that: a pair at the reach has no energy anyway.
  const double margin = list_reach * (1.0 + 1e-6) + 1e-12 * settings_.bbox_diagonal;
  std::vector<double> received;  // (id, x, dx) per vertex
  if (size > 1) {
    std::vector<double> boxes(6 * size);
    PetscCallMPI(
        MPI_Allgather(mine.data(), 6, MPI_DOUBLE, boxes.data(), 6, MPI_DOUBLE, layout_.comm()));
    std::vector<std::vector<double>> send(size);
    std::vector<int> marked(num_shell_points_, -1);  // the last rank a vertex was sent to
    auto primitive_box = [&](const int* v, int n) {
      Box b = empty_box();
      for (int i = 0; i < n; ++i) {
        const int l = layout_.local_of(v[i]);
        grow(b, position(l));
        grow(b, position(l) + motion(l));
      }
      return b;
    };
    for (int r = 0; r < size; ++r) {
      if (r == rank) continue;
      const Box other = Eigen::Map<const Box>(&boxes[6 * r]);
      if (!(other[0] <= other[3])) continue;  // no primitives there
      auto offer = [&](const int* v, int n) {
        if (!overlap(primitive_box(v, n), other, margin)) return;
        for (int i = 0; i < n; ++i) {
          if (marked[v[i]] == r) continue;
          marked[v[i]] = r;
          const int l = layout_.local_of(v[i]);
          const Eigen::Vector3d x = position(l), d = motion(l);
          send[r].insert(send[r].end(), {double(v[i]), x[0], x[1], x[2], d[0], d[1], d[2]});
        }
      };
      for (int v : own_vertices_) offer(&v, 1);
      for (int e : own_edges_) offer(surface_.edges[e].data(), 2);
      for (int f : own_faces_) offer(surface_.faces[f].data(), 3);
    }
    PetscCall(exchange(send, received));
  }

  // The compact surface: known shell vertices in natural order, then the vertices of the
  // obstacles' faces within reach of this rank's own primitives.
  const int total = static_cast<int>(rest_.size());
  std::vector<int> compact(total, -1), halo_of(num_shell_points_, -1);
  std::vector<char> near(total - num_shell_points_, 0);
  for (std::size_t k = 0; k < obstacle_boxes_.size(); ++k)
    if (overlap(obstacle_boxes_[k], mine, margin))
      for (int v : surface_.faces[num_shell_faces_ + k]) near[v - num_shell_points_] = 1;
  for (std::size_t k = 0; k < received.size(); k += 7) halo_of[static_cast<int>(received[k])] = k;
  x_.clear(), dx_.clear(), vertex_id_.clear(), local_index_.clear(), block_index_.clear();
  halo_points_ = 0;
  for (int v = 0; v < total; ++v) {
    Eigen::Vector3d x, d = Eigen::Vector3d::Zero();
    int l = -1;
    if (v >= num_shell_points_) {
      if (!near[v - num_shell_points_]) continue;
      x = obstacle_point(v);
      if (swept_ && !obstacle_dx_.empty()) d = obstacle_dx_[v - num_shell_points_];
    } else if ((l = layout_.local_of(v)) >= 0) {
      x = position(l), d = motion(l);
    } else if (halo_of[v] >= 0) {
      const double* h = &received[halo_of[v]];
      x = Eigen::Vector3d(h[1], h[2], h[3]), d = Eigen::Vector3d(h[4], h[5], h[6]);
      ++halo_points_;
    } else {
      continue;
    }
    compact[v] = static_cast<int>(x_.size());
    x_.push_back(x), dx_.push_back(d), vertex_id_.push_back(v), local_index_.push_back(l);
    block_index_.push_back(v < num_shell_points_ ? layout_.petsc_of(v) : -1);
  }
  if (!swept_ && vertex_id_ == list_vertex_id_) {
    double moved = 0.0;
    for (std::size_t i = 0; i < x_.size(); ++i)
      moved = std::max(moved, (x_[i] - list_x_[i]).norm());
    if (moved < skin) {
      pairs_ = list_pairs_;
      PetscFunctionReturn(0);
    }
  }
  std::vector<int> edge_id, face_id;
  const ContactSurface known =
      known_surface(compact, static_cast<int>(x_.size()), edge_id, face_id);

  ContactCandidates candidates;
  if (swept_) {
    std::vector<Eigen::Vector3d> x1(x_.size());
    for (std::size_t i = 0; i < x_.size(); ++i) x1[i] = x_[i] + dx_[i];
    candidates = find_swept_candidates(known, x_, x1, settings_.barrier.thickness);
  } else {
    candidates = find_proximity_candidates(known, x_, list_reach);
  }

  pairs_.clear();
  own_pairs(candidates, known, vertex_id_, edge_id, face_id, settings_.self_contact, pairs_);
  if (!swept_) list_vertex_id_ = vertex_id_, list_x_ = x_, list_pairs_ = pairs_, ++list_builds_;
  PetscFunctionReturn(0);
}

ContactSurface ContactTerm::known_surface(const std::vector<int>& compact, int num_vertices,
                                          std::vector<int>& edge_id,
                                          std::vector<int>& face_id) const {
  ContactSurface known;
  known.num_vertices = num_vertices;
  edge_id.clear(), face_id.clear();
  for (int e = 0; e < static_cast<int>(surface_.edges.size()); ++e) {
    const auto& [a, b] = surface_.edges[e];
    if (compact[a] < 0 || compact[b] < 0) continue;
    known.edges.push_back({compact[a], compact[b]});
    edge_id.push_back(e);
  }
  for (int f = 0; f < static_cast<int>(surface_.faces.size()); ++f) {
    const auto& t = surface_.faces[f];
    if (compact[t[0]] < 0 || compact[t[1]] < 0 || compact[t[2]] < 0) continue;
    known.faces.push_back({compact[t[0]], compact[t[1]], compact[t[2]]});
    face_id.push_back(f);
  }
  return known;
}

void ContactTerm::own_pairs(const ContactCandidates& candidates, const ContactSurface& known,
                            const std::vector<int>& vertex_id, const std::vector<int>& edge_id,
                            const std::vector<int>& face_id, bool shell_shell,
                            std::vector<Pair>& out) const {
  const int rank = layout_.rank();
  // Whether a pair of the shell points p's and q's primitives counts: always between two
  // bodies, within one if its self-contact is on.
  const auto counts = [&](int p, int q) {
    if (settings_.body_of_point.empty()) return shell_shell;
    const int a = settings_.body_of_point[p], b = settings_.body_of_point[q];
    return a != b || settings_.self_contact_of_body[a] != 0;
  };
  const auto mine_point = [&](int v) {
    const int l = layout_.local_of(v);
    return l >= 0 && l < layout_.num_owned_points();
  };
  for (const auto& [cv, cf] : candidates.point_triangle) {
    const int v = vertex_id[cv], f = face_id[cf];
    const bool shell_v = v < num_shell_points_, shell_f = f < num_shell_faces_;
    if (!shell_v && !shell_f) continue;
    if (shell_v && shell_f && !counts(v, surface_.faces[f][0])) continue;
    if (shell_v ? !mine_point(v) : layout_.face_owner(f) != rank) continue;
    const auto& t = known.faces[cf];
    out.push_back({false, {cv, t[0], t[1], t[2]}});
  }
  for (const auto& [ca, cb] : candidates.edge_edge) {
    const int a = edge_id[ca], b = edge_id[cb];
    const bool shell_a = a < num_shell_edges_, shell_b = b < num_shell_edges_;
    if (!shell_a && !shell_b) continue;
    if (shell_a && shell_b && !counts(surface_.edges[a][0], surface_.edges[b][0])) continue;
    const int owner_edge = shell_a ? a : b;  // edge ids are sorted: a < b
    if (edge_owner_[owner_edge] != rank) continue;
    const auto &ea = known.edges[ca], &eb = known.edges[cb];
    out.push_back({true, {ea[0], ea[1], eb[0], eb[1]}});
  }
}

Vector12 ContactTerm::stencil(const Pair& p, double t) const {
  Vector12 x;
  for (int i = 0; i < 4; ++i) x.segment<3>(3 * i) = x_[p.v[i]] + t * dx_[p.v[i]];
  return x;
}

double ContactTerm::squared_distance(const Pair& p) const {
  const auto &a = x_[p.v[0]], &b = x_[p.v[1]], &c = x_[p.v[2]], &d = x_[p.v[3]];
  return p.edge_edge ? edge_edge_distance(a, b, c, d) : point_triangle_distance(a, b, c, d);
}

double ContactTerm::pair_energy(const Pair& p, Vector12* grad, Matrix12* hess, bool* active) const {
  *active = false;
  const auto &a = x_[p.v[0]], &b = x_[p.v[1]], &c = x_[p.v[2]], &d = x_[p.v[3]];
  const ContactBarrier& barrier = settings_.barrier;
  const bool derivatives = grad || hess;
  Vector12 gd = Vector12::Zero();
  Matrix12 hd = Matrix12::Zero();
  const bool project = projects_hessian();
  // Most candidates of the Verlet list are beyond the barrier's reach: their distance alone
  // decides, and only active pairs pay for its derivatives.
  if (!p.edge_edge) {
    const auto type = point_triangle_distance_type(a, b, c, d);
    double dist = point_triangle_distance(a, b, c, d, type);
    if (dist >= barrier.activation_squared_distance()) return 0.0;
    *active = true;
    if (derivatives)
      dist = point_triangle_distance(a, b, c, d, type, &gd, hess ? &hd : nullptr);
    return barrier_pair_energy<12>(kappa_, barrier, dist, gd, hd, grad, hess, project);
  }
  const auto type = edge_edge_distance_type(a, b, c, d);
  double dist = edge_edge_distance(a, b, c, d, type);
  if (dist >= barrier.activation_squared_distance()) return 0.0;
  *active = true;
  if (derivatives) dist = edge_edge_distance(a, b, c, d, type, &gd, hess ? &hd : nullptr);
  const int* v = p.v.data();
  const double eps_x =
      edge_edge_mollifier_threshold(rest_[vertex_id_[v[0]]], rest_[vertex_id_[v[1]]],
                                    rest_[vertex_id_[v[2]]], rest_[vertex_id_[v[3]]]);
  if (!edge_edge_mollifier_active(a, b, c, d, eps_x))
    return barrier_pair_energy<12>(kappa_, barrier, dist, gd, hd, grad, hess, project);
  Vector12 gm = Vector12::Zero();
  Matrix12 hm = Matrix12::Zero();
  const double m =
      edge_edge_mollifier(a, b, c, d, eps_x, derivatives ? &gm : nullptr, hess ? &hm : nullptr);
  return mollified_barrier_pair_energy(kappa_, barrier, dist, gd, hd, m, gm, hm, grad, hess,
                                       project);
}

PetscErrorCode ContactTerm::add(const std::vector<double>&, CompensatedSum& energy,
                                std::vector<double>* grad, Mat hess) const {
  PetscFunctionBeginUser;
  PetscCheck(!swept_, PETSC_COMM_SELF, PETSC_ERR_ORDER,
             "contact: add() after a swept prepare(); prepare(u, nullptr) first");
  remote_rows_.clear(), remote_values_.clear();
  if (!finite_) {
    energy.add(INFINITY);
    PetscFunctionReturn(0);
  }
  Vector12 g;
  Matrix12 h;
  std::vector<PetscInt> rows;
  std::vector<int> which;
  std::vector<double> block;
  for (const Pair& p : pairs_) {
    bool active;
    const double e = pair_energy(p, grad ? &g : nullptr, hess ? &h : nullptr, &active);
    energy.add(e);
    // Exactly parallel edges have m = 0, so e = 0 and ∇e = 0, but their Hessian κ b ∇²m is not.
    if (!active || !std::isfinite(e)) continue;
    if (grad)
      for (int i = 0; i < 4; ++i) {
        const int c = p.v[i];
        if (local_index_[c] >= 0) {
          for (int k = 0; k < 3; ++k) (*grad)[3 * local_index_[c] + k] += g[3 * i + k];
        } else if (block_index_[c] >= 0) {
          remote_rows_.push_back(block_index_[c]);
          remote_values_.insert(remote_values_.end(), {g[3 * i], g[3 * i + 1], g[3 * i + 2]});
        }
      }
    if (hess) {
      rows.clear(), which.clear();
      for (int i = 0; i < 4; ++i)
        if (block_index_[p.v[i]] >= 0) rows.push_back(block_index_[p.v[i]]), which.push_back(i);
      const int n = static_cast<int>(rows.size());
      block.assign(9 * n * n, 0.0);
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b)
          for (int r = 0; r < 3; ++r)
            for (int c = 0; c < 3; ++c)
              block[(3 * a + r) * 3 * n + 3 * b + c] = h(3 * which[a] + r, 3 * which[b] + c);
      PetscCall(
          MatSetValuesBlocked(hess, n, rows.data(), n, rows.data(), block.data(), ADD_VALUES));
    }
  }
  PetscFunctionReturn(0);
}

PetscErrorCode ContactTerm::add_nonlocal_gradient(Vec g) const {
  PetscFunctionBeginUser;
  if (!remote_rows_.empty())
    PetscCall(VecSetValuesBlocked(g, static_cast<PetscInt>(remote_rows_.size()),
                                  remote_rows_.data(), remote_values_.data(), ADD_VALUES));
  PetscCall(VecAssemblyBegin(g));
  PetscCall(VecAssemblyEnd(g));
  PetscFunctionReturn(0);
}

double ContactTerm::max_step(const std::vector<double>&, const std::vector<double>&) const {
  if (!swept_) throw std::logic_error("contact: max_step() needs prepare(u, du)");
  const LogEventScope event("Contact:ccd");
  if (!finite_) return 0.0;
  double alpha = 1.0;
  for (const Pair& p : pairs_) {
    const Vector12 x0 = stencil(p, 0.0), dx = stencil(p, 1.0) - x0;
    const CcdResult r =
        p.edge_edge ? edge_edge_ccd(x0, dx, settings_.barrier.thickness, alpha, settings_.ccd)
                    : point_triangle_ccd(x0, dx, settings_.barrier.thickness, alpha, settings_.ccd);
    if (r.may_collide) alpha = std::min(alpha, r.toi);
  }
  return alpha;
}

PetscErrorCode ContactTerm::min_squared_distance(double* d) const {
  PetscFunctionBeginUser;
  double mine = INFINITY;
  for (const Pair& p : pairs_) mine = std::min(mine, squared_distance(p));
  PetscCallMPI(MPI_Allreduce(&mine, d, 1, MPI_DOUBLE, MPI_MIN, layout_.comm()));
  PetscFunctionReturn(0);
}

void ContactTerm::after_accept(const std::vector<double>&) {
  double d = INFINITY;
  PetscCallAbort(layout_.comm(), min_squared_distance(&d));
  const double kappa = kappa_;
  if (settings_.stiffness == 0.0 && std::isfinite(d) && std::isfinite(prev_min_distance_))
    kappa_ = update_barrier_stiffness(prev_min_distance_, d, kappa_max_, kappa_,
                                      settings_.bbox_diagonal, settings_.barrier.thickness,
                                      kCloseGap * settings_.barrier.gap / settings_.bbox_diagonal);
  if (kappa_ != kappa) ++revision_;
  prev_min_distance_ = d;
}

void ContactTerm::extend_sparsity(std::vector<std::array<int, 2>>& pairs) const {
  pairs.insert(pairs.end(), pattern_.begin(), pattern_.end());
}

PetscErrorCode ContactTerm::update_sparsity() {
  PetscFunctionBeginUser;
  // Each pair of natural points (a < b) goes to the owners of a's and b's rows, and stays here,
  // where its blocks are added (an edge–edge pair's owner may own neither end). A rank's
  // pattern holds those pairs only, which is all its matrix needs.
  std::vector<std::vector<double>> send(layout_.size());
  for (const Pair& p : pairs_) {
    // Point–triangle: the point with the triangle; edge–edge: each end with each end.
    const int first = p.edge_edge ? 2 : 1;
    for (int i = 0; i < first; ++i)
      for (int j = first; j < 4; ++j) {
        const int a = std::min(vertex_id_[p.v[i]], vertex_id_[p.v[j]]);
        const int b = std::max(vertex_id_[p.v[i]], vertex_id_[p.v[j]]);
        if (b >= num_shell_points_) continue;
        const int ra = owner_of_block(layout_.petsc_of(a)),
                  rb = owner_of_block(layout_.petsc_of(b));
        const int me = layout_.rank();
        send[ra].insert(send[ra].end(), {double(a), double(b)});
        if (rb != ra) send[rb].insert(send[rb].end(), {double(a), double(b)});
        if (me != ra && me != rb) send[me].insert(send[me].end(), {double(a), double(b)});
      }
  }
  std::vector<double> received;
  PetscCall(exchange(send, received));
  std::vector<std::array<int, 2>> current;
  for (std::size_t k = 0; k < received.size(); k += 2)
    current.push_back({static_cast<int>(received[k]), static_cast<int>(received[k + 1])});
  std::sort(current.begin(), current.end());
  current.erase(std::unique(current.begin(), current.end()), current.end());
  // Restarts and rebuilds happen on every rank or on none: a pair between two ranks' rows is
  // then in both ranks' patterns or in neither (a rank's matrix sends its ghost rows' blocks,
  // within its own pattern, to their owners).
  int change[2] = {
      pattern_.size() > 2 * current.size() + 64,
      !std::includes(pattern_.begin(), pattern_.end(), current.begin(), current.end())};
  PetscCallMPI(MPI_Allreduce(MPI_IN_PLACE, change, 2, MPI_INT, MPI_LOR, layout_.comm()));
  const bool restart = change[0];
  if (!restart && !change[1]) PetscFunctionReturn(0);
  if (restart) {
    pattern_ = std::move(current);  // restart from the current pairs
  } else {
    std::vector<std::array<int, 2>> grown;
    std::set_union(pattern_.begin(), pattern_.end(), current.begin(), current.end(),
                   std::back_inserter(grown));
    pattern_ = std::move(grown);
  }
  ++version_, ++rebuilds_;
  PetscFunctionReturn(0);
}

int ContactTerm::owner_of_block(PetscInt block) const {
  return static_cast<int>(std::upper_bound(block_first_.begin(), block_first_.end() - 1, block) -
                          block_first_.begin() - 1);
}

PetscErrorCode ContactTerm::statistics(ContactStatistics* s) const {
  PetscFunctionBeginUser;
  long mine[3] = {static_cast<long>(pairs_.size()), 0, halo_points_}, sums[3];
  double dmin = INFINITY;
  for (const Pair& p : pairs_) {
    const double d = squared_distance(p);
    dmin = std::min(dmin, d);
    if (d < settings_.barrier.activation_squared_distance()) ++mine[1];
  }
  PetscCallMPI(MPI_Allreduce(mine, sums, 3, MPI_LONG, MPI_SUM, layout_.comm()));
  double global;
  PetscCallMPI(MPI_Allreduce(&dmin, &global, 1, MPI_DOUBLE, MPI_MIN, layout_.comm()));
  long builds;
  PetscCallMPI(MPI_Allreduce(&list_builds_, &builds, 1, MPI_LONG, MPI_MAX, layout_.comm()));
  *s = ContactStatistics{sums[0], sums[1], std::sqrt(global), kappa_, sums[2], rebuilds_, builds};
  PetscFunctionReturn(0);
}

}  // namespace mlshell
