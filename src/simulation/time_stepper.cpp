// Implicit Euler and quasistatic stepping (see time_stepper.hpp).
#include "mlshell/time_stepper.hpp"

namespace mlshell {

namespace {
/// A proximal solve that ends at the limiting accuracy ends the step as converged if ‖∇E‖ is
/// within this factor of the tolerance (the solvers' own -tao_*_limiting_factor default).
constexpr double kLimitingFactor = 100.0;
/// Augmented-Lagrangian multiplier updates per implicit Euler step before giving up.
constexpr int kMaxMultiplierUpdates = 50;
/// Solves per implicit Euler step while kinematics have not arrived, before giving up.
constexpr int kMaxKinematicSolves = 100;

/// `next` after `before` in one step: the totals of both, the rest of `next`.
SolveReport after(const SolveReport& before, SolveReport next) {
  next.iterations += before.iterations;
  next.linear_iterations += before.linear_iterations;
  next.rmtr += before.rmtr;
  next.solves = before.solves + 1;
  next.multiplier_updates = before.multiplier_updates;
  return next;
}
}  // namespace

ImplicitEuler::ImplicitEuler(MultilevelProblem& levels, StepSolver& solver, double dt)
    : levels_(levels), solver_(solver), dt_(dt) {
  Vec u = levels.state(levels.num_levels() - 1);
  PetscCallAbort(PetscObjectComm(reinterpret_cast<PetscObject>(u)), VecDuplicate(u, &u_prev_));
}

ImplicitEuler::~ImplicitEuler() { VecDestroy(&u_prev_); }

PetscErrorCode ImplicitEuler::advance(double time, Vec u, Vec v, SolveReport& report) {
  PetscFunctionBeginUser;
  PetscCall(VecCopy(u, u_prev_));
  // Every level to time t, with the inertia predictor û = u_n + dt v_n (projected on the
  // coarse levels).
  PetscCall(levels_.synchronize(time, u, v));
  bool arrived = true;
  if (kinematics_) PetscCall(kinematics_->advance(time, u, &arrived));
  PetscCall(solver_.solve(u, report));
  report.solves = 1;
  // Kinematics that could not arrive before the solve move on after it (the predictor û stays).
  while (report.converged && !arrived) {
    if (report.solves == kMaxKinematicSolves) {
      report.converged = false;
      report.reason = "DIVERGED_COLLIDER_MOTION";
      break;
    }
    PetscCall(kinematics_->advance(time, u, &arrived));
    SolveReport again;
    PetscCall(solver_.solve(u, again));
    report = after(report, again);
  }
  // An augmented Lagrangian tightens its constraints by re-solving the same step.
  LevelProblem& finest = levels_.level(levels_.num_levels() - 1);
  for (bool met = false; report.converged;) {
    PetscCall(finest.update_multipliers(u, &met));
    if (met) break;
    if (report.multiplier_updates == kMaxMultiplierUpdates) {
      report.converged = false;
      report.reason = "DIVERGED_CONSTRAINT_TOLERANCE";
      break;
    }
    SolveReport again;
    PetscCall(solver_.solve(u, again));
    report = after(report, again);
    ++report.multiplier_updates;
  }
  // v_{n+1} = (u_{n+1} − u_n) / dt
  PetscCall(VecWAXPY(v, -1.0, u_prev_, u));
  PetscCall(VecScale(v, 1.0 / dt_));
  PetscFunctionReturn(0);
}

Quasistatic::Quasistatic(MultilevelProblem& levels, StepSolver& solver, const EnergyTerm& proximal,
                         int max_solves)
    : levels_(levels), solver_(solver), proximal_(proximal), max_solves_(max_solves) {
  Vec u = levels.state(levels.num_levels() - 1);
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(u));
  PetscCallAbort(comm, VecDuplicate(u, &zero_));
  PetscCallAbort(comm, VecZeroEntries(zero_));
  PetscCallAbort(comm, VecDuplicate(u, &gradient_));
}

Quasistatic::~Quasistatic() {
  VecDestroy(&zero_);
  VecDestroy(&gradient_);
}

PetscErrorCode Quasistatic::advance(double time, Vec u, Vec v, SolveReport& report) {
  PetscFunctionBeginUser;
  LevelProblem& finest = levels_.level(levels_.num_levels() - 1);
  SolveReport total;
  PetscReal energy_gradient = PETSC_INFINITY;
  bool limiting = false, arrived = true;
  for (int k = 0; k < max_solves_; ++k) {
    // Kinematics first (they may carry the shell), then the proximal centre x^k is the current
    // state, on every level.
    if (kinematics_) PetscCall(kinematics_->advance(time, u, &arrived));
    PetscCall(levels_.synchronize(time, u, zero_));
    SolveReport solve;
    PetscCall(solver_.solve(u, solve));
    total.iterations += solve.iterations;
    total.linear_iterations += solve.linear_iterations;
    total.rmtr += solve.rmtr;
    total.solves = k + 1;
    total.gradient_tolerance = solve.gradient_tolerance;
    total.force_scale = solve.force_scale;
    total.reason = solve.reason;
    total.converged = solve.converged;
    PetscReal energy;
    PetscCall(finest.objective_without(proximal_, u, &energy, gradient_));
    PetscCall(VecNorm(gradient_, NORM_2, &energy_gradient));
    total.energy = energy;
    total.gradient_norm = energy_gradient;
    if (solve.unbounded) {  // the energy fell through the floor: where it stopped, as solved
      total.unbounded = true;
      total.energy = solve.energy;
      total.energy_start = solve.energy_start;
      total.energy_bound = solve.energy_bound;
    }
    if (!solve.converged) break;
    if (!arrived) {  // not in its final place yet: solve again after the next move
      energy_gradient = PETSC_INFINITY;
      continue;
    }
    // At the round-off floor: done if ‖∇E‖ is there too; a solve that could not move at all
    // ends the step (another one would start from the same point).
    limiting = solve.reason == "CONVERGED_LIMITING_ACCURACY" &&
               energy_gradient <= kLimitingFactor * solve.gradient_tolerance;
    if (energy_gradient <= solve.gradient_tolerance || limiting) {
      // In equilibrium: an augmented Lagrangian may still have to tighten its constraints.
      bool met;
      PetscCall(finest.update_multipliers(u, &met));
      if (met) break;
      ++total.multiplier_updates;
      energy_gradient = PETSC_INFINITY;
      limiting = false;
      continue;
    }
    if (solve.reason == "CONVERGED_LIMITING_ACCURACY" && solve.iterations == 0) break;
  }
  if (total.converged && !(energy_gradient <= total.gradient_tolerance) && !limiting) {
    total.converged = false;
    total.reason = !arrived                   ? "DIVERGED_COLLIDER_MOTION"
                   : total.solves < max_solves_ ? "DIVERGED_QUASISTATIC_ROUNDOFF"
                                                 : "DIVERGED_QUASISTATIC_MAX_SOLVES";
  }
  report = total;
  PetscCall(VecZeroEntries(v));
  PetscFunctionReturn(0);
}

}  // namespace mlshell
