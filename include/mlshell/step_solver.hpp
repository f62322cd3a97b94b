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
//
// Energy floor (every solver: each TAO type's convergence test and SNES's are wrapped): a
// solve stops as DIVERGED_ENERGY_UNBOUNDED once its objective falls below
//   f₀ − B,  B = kUnboundedEnergyFactor (S + |f₀|),
// f₀ the objective where the solve began and S the scene's energy scale (set_energy_scale;
// step_failure.hpp): the problem has no minimum near there, and iterating on only drives the
// energy towards −∞ (a balloon beyond its limit pressure: E = −4e101 J after 1,000 iterations).
// A PETSc line search that extrapolates along such a ray may fail with a PETSc error instead
// (bnls's Moré–Thuente: "dx * (stp-stx) >= 0.0"); after a trial point below the floor that error
// ends the solve as DIVERGED_ENERGY_UNBOUNDED too, silently.
#pragma once

#include <petscsnes.h>
#include <petsctao.h>

#include <cmath>
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
  /// The solve stopped because its objective fell below energy_start − energy_bound (the
  /// energy floor, see above); `energy` is where it stopped.
  bool unbounded = false;
  double energy_start = 0.0;  ///< f₀, the objective where that solve began
  double energy_bound = 0.0;  ///< B
};

/// mlshell's options of the step solver, read by one PetscOptionsBegin/End group ("mlshell:
/// step solver" in -help):
///   -mlshell_step_solver tao|snes  TAO minimises f (default), SNES solves grad f = 0
///   -mlshell_hessian_psd           every non-convex element Hessian (membranes, hinges, the
///                                  shell material) is projected onto the PSD cone before
///                                  assembly (projected Newton, paper 2 §4.5); default: on for
///                                  -tao_type pnewton, off otherwise
///   -mlshell_pressure_psd          with -mlshell_hessian_psd, the pressure's Hessian too, per edge
///                                  (pressure_term.cpp); default off: its exact Hessian keeps
///                                  Newton quadratic on a stable balloon (docs/solvers.md)
///   -mlshell_force_rtol 1e-8       |g| < max(-tao_gatol, this × ‖f_ext‖)
struct StepSolverOptions {
  bool snes = false;
  /// "snes" with -mlshell_step_solver snes, else the TAO type (-tao_type if given, else the
  /// default "rmtr").
  std::string type = "rmtr";
  bool hessian_psd = false;
  bool pressure_psd = false;
  PetscReal force_rtol = 1e-8;
  /// -mlshell_coarse_energy own|proxy: what RMTR's first-order coarse models minimise on the
  /// coarse levels of a triangle hierarchy: each coarse mesh's own energy, or paper 2's proxy
  /// Ψ(P^l(x_l)) of the finest energy (proxy_energy.hpp).
  bool proxy_coarse_energy = false;
  /// Reads the group (invalid values: std::invalid_argument naming the option and value).
  static StepSolverOptions from_options(MPI_Comm comm);
};

/// B = kUnboundedEnergyFactor (S + |f₀|). S is the energy of unit strain of the whole membrane
/// plus the loads' work over the surface's size (and over the motions and the free flight the
/// scene allows): physical solutions stay within a small multiple of it (strains of order 1,
/// displacements of the order of the size; a balloon at its limit pressure inflated 5-fold in
/// radius: 7 S). Falling 10⁶ S would take a membrane stretched 1000-fold (its energy grows as
/// λ²) or loads carrying the shell a million times its size, in one step. A divergent solve
/// passes it within a few dozen iterations, as its energy falls super-exponentially (a balloon
/// at 50 times its limit pressure: rmtr after 4 iterations, bntr 6, tr 8, bnls within its
/// first line search; pnewton, whose PSD-projected Hessian keeps its steps short, after 94,
/// and after 75 at 250 times): a larger factor would cost those few iterations more, a smaller
/// one would bring no earlier stop worth the lost margin.
constexpr double kUnboundedEnergyFactor = 1e6;

/// The default of -mlshell_hessian_psd for a solver type: on for pnewton.
bool hessian_projection_default(const std::string& solver_type);

/// Whether the energy term named `term` projects its element Hessians: every term under
/// -mlshell_hessian_psd except the pressure, which needs -mlshell_pressure_psd as well (its
/// exact Hessian keeps projected Newton quadratic on a stable balloon, docs/solvers.md).
bool term_hessian_projection(const StepSolverOptions& options, const std::string& term);

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
  /// The scene's energy scale S (J, > 0) of the energy floor; without it (or with +inf) a
  /// solve has no floor.
  void set_energy_scale(double scale) { floor_.scale = scale; }

  /// The energy floor shared by the TAO and SNES convergence tests.
  struct EnergyFloor {
    Objective* problem = nullptr;
    double scale = INFINITY;  // S
    double start = NAN;       // f₀: the first value a convergence test sees in a solve
    double last = NAN;        // SNES: f at the last residual evaluation
    bool crossed = false;
    /// A trial point below the floor (it stops no solve: a wild trial step proves no
    /// divergence), and the lowest f of such points.
    bool trial_crossed = false;
    double trial_low = INFINITY;
    double bound() const { return kUnboundedEnergyFactor * (scale + std::abs(start)); }
    /// Whether f of an iterate is below the floor (the first call of a solve sets f₀ = f).
    bool below(double f);
    /// Notes f of any point the solver evaluates.
    void observe(double f);
  };

 private:
  PetscErrorCode solve_snes(Vec u, SolveReport& report);
  void report_floor(SolveReport& report) const;

  Objective& problem_;
  Tao tao_ = nullptr;
  SNES snes_ = nullptr;
  Vec residual_ = nullptr;
  Mat H_ = nullptr;
  PetscReal gatol_ = 1e-7, force_rtol_ = 1e-8;  // absolute and force-relative tolerances
  EnergyFloor floor_;
};

}  // namespace mlshell
