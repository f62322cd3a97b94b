// Scripted colliders: obstacles that follow a rigid motion φ(X, t) (a collider's `motion`) and
// never jump into the shell (docs/contact.md, "Moving colliders").
//
// A collider moves between the solves of a step, never within one. Before each solve,
// advance(t, u) moves the colliders towards their places at the step's time t:
//   1. the carry step du takes the shell vertices close to a collider that comes closer along
//      with it, by the same rigid motion, so those pairs keep their distance
//      (ContactTerm::carry);
//   2. additive CCD over the joint straight move (the shell by du, the colliders' vertices to
//      φ(X, t')) gives the safe fraction α (ContactTerm::obstacle_step_limit);
//   3. with α = 1 both moves are taken; otherwise t' shrinks to t_now + α (t' − t_now) and the
//      check repeats (a rotation's chord differs from its arc), a few times at most. A collider
//      that cannot move at all waits for the next solve, which lets the barrier push the shell
//      away.
// The step's time-stepper repeats its solves until the colliders have arrived
// (time_stepper.hpp), so the step ends in equilibrium with every collider in its place. Every
// intermediate place is intersection-free by CCD, the shell's own steps by the solvers' CCD.
//
// This is the kinematic alternative to paper 2 §4.6's augmented Lagrangian on obstacle
// degrees of freedom: mlshell's unknowns are the shell's alone, so the colliders are moved by
// the driver instead of by the solver.
#pragma once

#include <petscvec.h>

#include <vector>

#include "mlshell/contact/contact_term.hpp"
#include "mlshell/prescribed_motion.hpp"
#include "mlshell/time_stepper.hpp"

namespace mlshell {

class ColliderMotion final : public StepKinematics {
 public:
  /// `motions[k]` moves obstacle k of `contact` (an empty function: it stays). The obstacles'
  /// current places are their reference X.
  ColliderMotion(ContactTerm& contact, std::vector<PrescribedMotion> motions, Vec like);
  ~ColliderMotion() override;
  ColliderMotion(const ColliderMotion&) = delete;
  ColliderMotion& operator=(const ColliderMotion&) = delete;

  /// Puts the colliders at their places at `time` at once (the start of a run, which is
  /// audited, not swept).
  void place_at(double time);
  PetscErrorCode advance(double time, Vec u, bool* reached) override;
  /// The time the colliders are at.
  double time() const { return time_; }
  /// Moves taken so far, and of them those CCD cut short of the step's time.
  long moves() const { return moves_; }
  long cut_moves() const { return cut_moves_; }

 private:
  std::vector<std::vector<Point3>> places(double time) const;

  ContactTerm& contact_;
  std::vector<PrescribedMotion> motions_;
  std::vector<std::vector<Point3>> reference_;
  double time_ = 0.0;
  long moves_ = 0, cut_moves_ = 0;
  Vec du_ = nullptr;
};

}  // namespace mlshell
