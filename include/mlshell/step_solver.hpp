// Solves one step's minimisation problem with a PETSc TAO solver (options prefix `-tao_`), or,
// with -mlshell_step_solver snes, its first-order condition ∇f(u) = 0 with a PETSc SNES
// (prefix `-snes_`, Jacobian = the Hessian).
//
// Defaults (all overridable from the command line or an options file, which win):
//   -tao_type rmtr -tao_gatol 1e-7 (paper eq. 7.1) -tao_gttol 1e-10 -tao_grtol 0 -tao_max_it 1000
//   -mlshell_force_rtol 1e-8: each step's gradient tolerance is max(gatol, 1e-8 ‖f_ext‖), with
//   ‖f_ext‖ the norm of the external forces (gravity, loads), so that it holds for any units
//   and size; the paper's scenes (‖f_ext‖ < 1) keep gatol.
// i.e. the recursive multilevel trust region on every level it is given (one level: Local_TR),
// configured as petsc-options/rmtr-patch-dogleg.yaml spells out (the keys are set in
// step_solver.cpp, and cli.options_files checks the two agree; RMTR's own defaults are the
// paper's).
// For the KSP of whichever Newton-type PETSc solver is chosen instead (prefix tao_bnk_ for
// bntr/bnls/bqnkls..., tao_nls_ for nls, ...): ksp_type stcg, pc_type lu,
// pc_factor_mat_solver_type mumps.
// SNES defaults: -snes_type newtonls -snes_atol 1e-7 -snes_rtol 1e-10 (the TAO tolerances on
// ‖∇f‖) -snes_stol 0 (a short Newton step is not convergence) -snes_max_it 1000, and a
// MUMPS LU as its linear solver (-ksp_type preonly -pc_type lu); e.g. -ksp_type cg
// -pc_type hypre for BoomerAMG.
#pragma once

#include <petscsnes.h>
#include <petsctao.h>

#include <string>

#include "mlshell/multilevel_objective.hpp"
#include "mlshell/objective.hpp"
#include "mlshell/trust_region.hpp"

namespace mlshell {

struct SolveReport {
  bool converged = false;
  std::string reason;  ///< TAO's converged reason, e.g. CONVERGED_GATOL
  int iterations = 0;
  int linear_iterations = 0;
  int solves = 1;              ///< minimisations in the step (quasistatic: proximal solves)
  int multiplier_updates = 0;  ///< augmented-Lagrangian outer iterations in the step
  double energy = 0.0;
  double gradient_norm = 0.0;
  double gradient_tolerance = 0.0;  ///< max(-tao_gatol, -mlshell_force_rtol × ‖f_ext‖)
  double force_scale = 0.0;         ///< ‖f_ext‖₂
  RmtrStatistics rmtr;              ///< for -tao_type rmtr
};

/// mlshell's options of the step solver, read by one PetscOptionsBegin/End group ("mlshell:
/// step solver" in -help):
///   -mlshell_step_solver tao|snes  TAO minimises f (default), SNES solves grad f = 0
///   -mlshell_hessian_psd           every non-convex element Hessian (membranes, hinges, the
///                                  shell material) is projected onto the PSD cone before
///                                  assembly (projected Newton, paper 2 §4.5); default: on for
///                                  -tao_type pnewton, off otherwise
///   -mlshell_force_rtol 1e-8       |g| < max(-tao_gatol, this × ‖f_ext‖)
struct StepSolverOptions {
  bool snes = false;
  /// "snes" with -mlshell_step_solver snes, else the TAO type (-tao_type if given, else the
  /// default "rmtr").
  std::string type = "rmtr";
  bool hessian_psd = false;
  PetscReal force_rtol = 1e-8;
  /// Reads the group (invalid values: std::invalid_argument naming the option and value).
  static StepSolverOptions from_options(MPI_Comm comm);
};

/// The default of -mlshell_hessian_psd for a solver type: on for pnewton.
bool hessian_projection_default(const std::string& solver_type);

/// For `mlshell -help`: the options of the solver that `options` (as read already) choose
/// (TAO's type, rmtr by default, with mlshell's defaults in place; or SNES), printed by PETSc's
/// help as a run would read them.
PetscErrorCode step_solver_options_help(MPI_Comm comm, const StepSolverOptions& options);

class StepSolver {
 public:
  /// Minimises `problem` (which must create its Hessian matrix, Objective::create_hessian);
  /// `levels` (finest = problem) are given to RMTR if that is the type. `options`: mlshell's
  /// step-solver options as read already (the simulation reads them once), or nullptr to read
  /// them here.
  explicit StepSolver(Objective& problem, MultilevelObjective* levels = nullptr,
                      const StepSolverOptions* options = nullptr);
  ~StepSolver();
  StepSolver(const StepSolver&) = delete;
  StepSolver& operator=(const StepSolver&) = delete;

  /// Minimises from the displacement in `u`, leaving the result there.
  PetscErrorCode solve(Vec u, SolveReport& report);
  Tao tao() const { return tao_; }  ///< null for SNES
  /// The TAO type, or "snes-<type>" (e.g. snes-newtonls).
  std::string type() const;

 private:
  PetscErrorCode solve_snes(Vec u, SolveReport& report);

  Objective& problem_;
  Tao tao_ = nullptr;
  SNES snes_ = nullptr;
  Vec residual_ = nullptr;
  Mat H_ = nullptr;
  PetscReal gatol_ = 1e-7, force_rtol_ = 1e-8;  // absolute and force-relative tolerances
};

}  // namespace mlshell
