// How a simulation moves from one step to the next: each step is one or more minimisations
// solved by a StepSolver (DESIGN.md, "TimeStepper").
//
//   implicit Euler (paper 1 eq. 3.2)  u_{n+1} = argmin ρ/(2dt²)‖u − û‖²_M + E(u), û = u_n + dt v_n,
//                                     v_{n+1} = (u_{n+1} − u_n)/dt
//   quasistatic (paper 2 eq. 1)       x^{k+1} = argmin ½h⁻²‖x − x^k‖²_M + E(x) with the artificial
//                                     step h (the scene's `proximal` term), repeated from the
//                                     last step's state until ‖∇E(x)‖ ≤ ε; no velocity
//
// Both move every level of the problem to the step's time (boundary motion, load ramps) and
// give each level its predictor (projected from the finest level) before each solve. Terms with
// augmented-Lagrangian multipliers (dirichlet with a tolerance) get an outer loop: once a solve
// is in equilibrium, multipliers whose constraint is violated by more than its tolerance are
// updated and the step is solved again (at most 50 times for implicit Euler; within the
// proximal solves for quasistatics). Kinematics (scripted colliders) move before every solve,
// and a step is solved again until they have arrived (at most 100 solves for implicit Euler;
// within the proximal solves for quasistatics).
#pragma once

#include <petscvec.h>

#include <string>

#include "mlshell/multilevel_problem.hpp"
#include "mlshell/step_solver.hpp"

namespace mlshell {

/// What moves within a step besides the shell's unknowns: scripted colliders
/// (collider_motion.hpp).
class StepKinematics {
 public:
  virtual ~StepKinematics() = default;
  /// Moves as far towards the places at `time` as is safe before a solve, and the shell (u)
  /// along where it must; *reached: everything is there.
  virtual PetscErrorCode advance(double time, Vec u, bool* reached) = 0;
};

class TimeStepper {
 public:
  virtual ~TimeStepper() = default;
  /// "implicit_euler" or "quasistatic".
  virtual std::string name() const = 0;
  /// From the state (u, v) of the last step to that at `time`, in place; the report covers all
  /// of the step's solves.
  virtual PetscErrorCode advance(double time, Vec u, Vec v, SolveReport& report) = 0;
  /// Kinematics moved before every solve; a step is solved again until they have arrived
  /// (not owned; null: none).
  void set_kinematics(StepKinematics* k) { kinematics_ = k; }

 protected:
  StepKinematics* kinematics_ = nullptr;
};

class ImplicitEuler final : public TimeStepper {
 public:
  ImplicitEuler(MultilevelProblem& levels, StepSolver& solver, double dt);
  ~ImplicitEuler() override;
  std::string name() const override { return "implicit_euler"; }
  PetscErrorCode advance(double time, Vec u, Vec v, SolveReport& report) override;

 private:
  MultilevelProblem& levels_;
  StepSolver& solver_;
  double dt_;
  Vec u_prev_ = nullptr;
};

class Quasistatic final : public TimeStepper {
 public:
  /// `proximal` is the term ½h⁻²‖x − x^k‖²_M of the finest level; at most `max_solves`
  /// proximal solves per step.
  Quasistatic(MultilevelProblem& levels, StepSolver& solver, const EnergyTerm& proximal,
              int max_solves);
  ~Quasistatic() override;
  std::string name() const override { return "quasistatic"; }
  /// The report's gradient_norm is ‖∇E‖ (without the proximal term); converged when it is
  /// within the solver's gradient tolerance, or when a proximal solve ends at the limiting
  /// accuracy (CONVERGED_LIMITING_ACCURACY) with ‖∇E‖ within 100 times of it.
  PetscErrorCode advance(double time, Vec u, Vec v, SolveReport& report) override;

 private:
  MultilevelProblem& levels_;
  StepSolver& solver_;
  const EnergyTerm& proximal_;
  int max_solves_;
  Vec zero_ = nullptr, gradient_ = nullptr;
};

}  // namespace mlshell
