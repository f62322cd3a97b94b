// IPC barrier contact of a triangle shell with itself and with static obstacles (paper 2 §3;
// IPC, Li et al. 2020; Codimensional IPC, Li et al. 2021), on distributed vectors.
//
// The contact surface is the shell's mesh (its vertices are the unknowns) followed by the
// obstacles' triangles (fixed, the same on every rank). The energy is
//   B(x) = κ Σ_{(v, f)} b_ξ(d_PT(x_v, x_f)) + κ Σ_{(a, b)} m_ab(x) b_ξ(d_EE(x_a, x_b))
// over the point–triangle and edge–edge pairs closer than ξ + ĝ, with the offset barrier b_ξ of
// barrier.hpp and the edge–edge mollifier m of edge_edge_mollifier.hpp (barrier_pair_energy.hpp
// has the pair's derivatives). Obstacle–obstacle pairs never count; shell–shell pairs only with
// self-contact.
//
// Distribution. Every pair is evaluated once, by the rank that owns it. A rank owns the shell
// vertices it owns as points, its elements (faces), and every edge whose lowest-ranked face is
// its own, so each vertex of its own primitives is one of its local points. A point–triangle
// pair belongs to its shell vertex's owner (to the face's owner when the vertex is an
// obstacle's), an edge–edge pair to the owner of its lower-numbered shell edge. The rest of the
// surface comes by a halo exchange, not by gathering it: the ranks share the bounding boxes of
// their own primitives (over the step for CCD), and each sends every other rank the vertices of
// its own primitives whose boxes come within ξ + ĝ of that rank's box. A halo vertex's gradient
// is added into the global vector (add_nonlocal_gradient) and its Hessian blocks go in by
// global index, other ranks' rows through PETSc's stash. On any number of ranks the pairs, as
// global primitives, are the same.
//
// The Hessian's pattern follows the pairs (update_sparsity): the point pairs of the candidates
// seen so far are the pattern (extend_sparsity); when a Hessian needs one outside it, the
// pattern grows, sparsity_version() changes and LevelProblem rebuilds the matrix under the
// same handle. It restarts from the current pairs when it holds over twice as many. A rank's
// pattern holds the pairs of its own rows only: each pair is sent to the owners of its rows.
//
// The proximity candidates are a Verlet list: found within ξ + ĝ + 2s (the skin s = ξ + ĝ) and
// reused while every known vertex stays within s of where it was then, so that the evaluations
// of a line search and of a converging Newton solve share one broad phase.
//
// CCD is max_step: the swept candidates of u → u + du, each by additive CCD (additive_ccd.hpp),
// the smallest time of impact over all ranks.
//
// Scripted colliders move between solves, never within one: obstacle_step_limit is CCD over
// the obstacles' straight move to new places together with a shell step, move_obstacles puts
// them there, and carry gives the step that takes the shell vertices near a moving obstacle
// along with it (collider_motion.hpp drives them).
//
// Stiffness κ: the scene's, or adaptive. IPC's κ_min from the lumped masses
// (adaptive_stiffness.hpp) is the scale of inertia and far too soft for quasistatics (a sheet
// resting on a sphere sank to the thickness ξ with it); the start is instead the κ at which one
// pair at half the gap, d½ = (ξ + ĝ/2)², holds the force f a vertex must carry
// (ContactSettings::vertex_force):
//   κ₀ = max(κ_min, f / (|b_ξ'(d½)| 2√d½)),   κ_max = max(100 κ₀, f_max / (|b_ξ'(d½)| 2√d½)),
// and after an accepted iterate κ doubles (up to κ_max) while the smallest gap is below 10⁻² ĝ
// and shrinking (IPC's rule with its threshold raised from 10⁻⁹ L). f_max
// (ContactSettings::max_vertex_force) is the most a vertex can be pressed with: IPC's 100 κ₀ is
// too soft where the shell's own tension presses it together (a twisted rope).
#pragma once

#include <petscmat.h>

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "mlshell/contact/barrier/barrier.hpp"
#include "mlshell/contact/broad_phase/contact_candidates.hpp"
#include "mlshell/contact/ccd/additive_ccd.hpp"
#include "mlshell/energy_term.hpp"
#include "mlshell/triangle/triangle_mesh.hpp"

namespace mlshell {

struct ContactSettings {
  ContactBarrier barrier;      ///< ξ and ĝ
  bool self_contact = true;    ///< shell–shell pairs count
  /// Several bodies on one shell mesh (triangle_bodies.hpp): the body of each shell point, and
  /// per body whether its pairs with itself count. Pairs between two bodies always count. Empty:
  /// one body, whose pairs with itself count if self_contact.
  std::vector<int> body_of_point;
  std::vector<char> self_contact_of_body;
  double stiffness = 0.0;      ///< κ > 0 fixed; 0: adaptive
  double average_mass = 0.0;   ///< m̄ (kg), the average lumped nodal mass (adaptive κ)
  double bbox_diagonal = 0.0;  ///< L (m), the scene's size (adaptive κ)
  double vertex_force = 0.0;   ///< f (N), the force a vertex in contact must hold (adaptive κ)
  double max_vertex_force = 0.0;  ///< f_max (N), the most a vertex is pressed with (κ_max)
  AdditiveCcdOptions ccd;
};

/// What a contact term saw at the last prepared state (summed or reduced over the ranks).
struct ContactStatistics {
  long candidates = 0;             ///< broad-phase pairs (owned; the Verlet list's)
  long active = 0;                 ///< pairs closer than ξ + ĝ
  double min_distance = INFINITY;  ///< the smallest pair distance (m), ∞ without pairs
  double stiffness = 0.0;          ///< κ
  long halo_points = 0;            ///< vertices received from other ranks
  long pattern_rebuilds = 0;       ///< Hessian patterns grown or restarted so far
  long list_builds = 0;            ///< proximity broad phases run so far (Verlet lists)
};

class ContactTerm final : public EnergyTerm {
 public:
  /// `shell` is the level's mesh (the layout's discretization), `obstacles` static surfaces.
  /// Throws std::invalid_argument for settings out of range.
  ContactTerm(std::string name, const TriangleMesh& shell, const ParallelLayout& layout,
              std::vector<TriangleMesh> obstacles, ContactSettings settings);
  bool needs_prepare() const override { return true; }
  /// The halo exchange and broad phase at u (proximity) or along u → u + du (swept).
  PetscErrorCode prepare(Vec u, Vec du) override;
  /// Energy, gradient and Hessian at the prepared u (`u` must be its local values).
  PetscErrorCode add(const std::vector<double>& u, CompensatedSum& energy,
                     std::vector<double>* grad, Mat hess) const override;
  PetscErrorCode add_nonlocal_gradient(Vec g) const override;
  bool limits_steps() const override { return true; }
  /// The smallest time of impact of the prepared step, on this rank's pairs.
  double max_step(const std::vector<double>& u, const std::vector<double>& du) const override;
  /// Adaptive κ at the prepared, accepted u (collective).
  void after_accept(const std::vector<double>& u) override;
  long revision() const override { return revision_; }
  void extend_sparsity(std::vector<std::array<int, 2>>& pairs) const override;
  long sparsity_version() const override { return version_; }
  PetscErrorCode update_sparsity() override;

  /// The statistics of the prepared state, over all ranks (collective).
  PetscErrorCode statistics(ContactStatistics* s) const;
  /// The smallest squared pair distance among the prepared candidates, over all ranks
  /// (collective); +∞ without candidates.
  PetscErrorCode min_squared_distance(double* d) const;
  /// The obstacles where they are now (their rest places until move_obstacles).
  const std::vector<TriangleMesh>& obstacles() const { return obstacles_; }
  /// Puts obstacle k's vertices at points[k] (the same on every rank; each as many as the
  /// obstacle has). The next prepare finds the pairs afresh; revision() changes.
  void move_obstacles(const std::vector<std::vector<Point3>>& points);
  /// The largest fraction α ∈ [0, 1] of the joint straight move of the shell, u → u + du, and
  /// of the obstacles, to `points`, that keeps every pair apart by more than ξ (additive CCD,
  /// over all ranks; collective). Leaves the term unprepared.
  PetscErrorCode obstacle_step_limit(Vec u, Vec du, const std::vector<std::vector<Point3>>& points,
                                     double* alpha);
  /// The step du that pushes the shell ahead of the obstacles flagged in `moving` as they move
  /// straight to `points` (collective): a shell vertex that obstacle k would reach at its time
  /// of impact t (additive CCD of the obstacles' move against the shell at rest) gets the
  /// fraction 1 − t/2 of place(k, x) − x, the rigid motion that takes the obstacle's current
  /// place to its new one (the largest fraction over its pairs); every other vertex 0. Leaves
  /// the term unprepared.
  PetscErrorCode carry(Vec u, const std::vector<std::vector<Point3>>& points,
                       const std::vector<char>& moving,
                       const std::function<Point3(int, const Point3&)>& place, Vec du);
  const ContactSettings& settings() const { return settings_; }
  double stiffness() const { return kappa_; }

 private:
  struct Pair {
    bool edge_edge;
    std::array<int, 4> v;  ///< compact vertices (point–triangle: p, t0, t1, t2)
  };
  /// Positions of the pair's four vertices (at the prepared state, plus t·dx).
  Vector12 stencil(const Pair& p, double t) const;
  /// The pair's energy and, where not null, gradient and Hessian; +∞ for d ≤ ξ². *active:
  /// whether the pair is within ξ + ĝ (else nothing is written).
  double pair_energy(const Pair& p, Vector12* grad, Matrix12* hess, bool* active) const;
  double squared_distance(const Pair& p) const;
  void collect_pairs(const ContactCandidates& c);

  const ParallelLayout& layout_;
  std::vector<TriangleMesh> obstacles_;
  ContactSettings settings_;
  int num_shell_points_ = 0, num_shell_faces_ = 0, num_shell_edges_ = 0;
  std::vector<Eigen::Vector3d> rest_;  ///< every surface vertex (shell, then obstacles)
  ContactSurface surface_;             ///< the whole surface (global ids)
  std::vector<int> edge_owner_;        ///< owner of each shell edge
  std::vector<int> own_vertices_, own_edges_, own_faces_;    ///< this rank's primitives
  std::vector<int> own_box_points_;                          ///< local indices of their vertices
  std::vector<Eigen::Matrix<double, 6, 1>> obstacle_boxes_;  ///< each obstacle face's (lo, hi)
  /// Each obstacle vertex's move in a swept prepare (obstacle_step_limit); empty: none.
  std::vector<Eigen::Vector3d> obstacle_dx_;
  std::vector<int> obstacle_of_;     ///< each obstacle vertex's obstacle (surface id − shell's)
  std::vector<int> obstacle_first_;  ///< each obstacle's first surface id
  /// obstacle_dx_ for the obstacles' straight move to `points` (null: none), their boxes over
  /// it; the term is left unprepared.
  void set_obstacle_motion(const std::vector<std::vector<Point3>>* points);
  /// Each obstacle face's box, over its move when obstacle_dx_ is set.
  void update_obstacle_boxes();
  std::vector<int> block_first_;  ///< each rank's first PETSc block, then the number of blocks
  /// The rank that owns PETSc block `block`.
  int owner_of_block(PetscInt block) const;
  /// send[r] to rank r, all received in rank order (collective).
  PetscErrorCode exchange(const std::vector<std::vector<double>>& send,
                          std::vector<double>& received) const;
  /// The current place of surface vertex v ≥ num_shell_points_ (an obstacle's).
  const Point3& obstacle_point(int v) const;
  /// The surface of the vertices with compact[v] ≥ 0 (num_vertices of them): the edges and faces
  /// whose vertices all are, and their global ids.
  ContactSurface known_surface(const std::vector<int>& compact, int num_vertices,
                               std::vector<int>& edge_id, std::vector<int>& face_id) const;
  /// The candidates this rank owns (the file comment's rules), with shell–shell pairs only if
  /// `shell_shell`; `vertex_id`, `edge_id`, `face_id` map the known surface to global ids.
  void own_pairs(const ContactCandidates& candidates, const ContactSurface& known,
                 const std::vector<int>& vertex_id, const std::vector<int>& edge_id,
                 const std::vector<int>& face_id, bool shell_shell, std::vector<Pair>& out) const;
  long revision_ = 0;  ///< changes of κ
  double kappa_ = 0.0, kappa_max_ = 0.0, prev_min_distance_ = INFINITY;

  // The prepared state, on the compact surface of the vertices this rank knows.
  bool swept_ = false;
  bool finite_ = true;  ///< the prepared u (and du) are finite on every rank
  /// The vector (id and state) of the last proximity prepare, which a repeat may skip.
  bool prepared_ = false;
  PetscObjectId prepared_id_ = 0;
  PetscObjectState prepared_state_ = 0;
  std::vector<Eigen::Vector3d> x_, dx_;
  std::vector<int> vertex_id_, local_index_;  ///< compact → surface id, → local point (−1)
  std::vector<PetscInt> block_index_;         ///< compact → PETSc block (−1: obstacle)
  std::vector<Pair> pairs_;                   ///< this rank's candidate pairs
  /// The last proximity pairs as a Verlet list: the vertices and positions they were found at.
  std::vector<int> list_vertex_id_;
  std::vector<Eigen::Vector3d> list_x_;
  std::vector<Pair> list_pairs_;
  long list_builds_ = 0;
  long halo_points_ = 0;
  mutable std::vector<PetscInt> remote_rows_;
  mutable std::vector<double> remote_values_;

  std::vector<std::array<int, 2>> pattern_;  ///< natural point pairs of the Hessian's pattern
  long version_ = 0, rebuilds_ = 0;
};

}  // namespace mlshell
