// TAO as the step solver (see step_solver.hpp for the defaults).
#include "mlshell/step_solver.hpp"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <utility>

namespace mlshell {

namespace {

PetscErrorCode objective_and_gradient(Tao, Vec u, PetscReal* f, Vec g, void* ctx) {
  auto* floor = static_cast<StepSolver::EnergyFloor*>(ctx);
  PetscFunctionBeginUser;
  PetscCall(floor->problem->objective(u, f, g));
  floor->observe(*f);
  PetscFunctionReturn(0);
}

PetscErrorCode objective_only(Tao tao, Vec u, PetscReal* f, void* ctx) {
  return objective_and_gradient(tao, u, f, nullptr, ctx);
}

PetscErrorCode hessian(Tao, Vec u, Mat H, Mat, void* ctx) {
  return static_cast<Objective*>(ctx)->hessian(u, H);
}

/// SNES residual F(u) = ∇f(u); a trial point outside the material's domain (f = +inf) is a
/// domain error, which makes newtonls's line search shorten the step. f is kept for the energy
/// floor.
PetscErrorCode gradient_residual(SNES snes, Vec u, Vec g, void* ctx) {
  auto* floor = static_cast<StepSolver::EnergyFloor*>(ctx);
  PetscReal f;
  PetscFunctionBeginUser;
  PetscCall(floor->problem->objective(u, &f, g));
  floor->last = f;
  if (f >= PETSC_INFINITY) PetscCall(SNESSetFunctionDomainError(snes));
  PetscFunctionReturn(0);
}

PetscErrorCode hessian_jacobian(SNES, Vec u, Mat H, Mat, void* ctx) {
  return static_cast<Objective*>(ctx)->hessian(u, H);
}

/// Each SNES iterate after the first is accepted (the objective's terms adapt: contact's κ). If
/// that changed the objective, F and its norm are those of the objective as it now is: the
/// convergence test (floor_then_default_snes_test reads the norm back) and the next Newton step
/// see them.
PetscErrorCode accept_iterate(SNES snes, PetscInt it, PetscReal, void* ctx) {
  PetscFunctionBeginUser;
  if (it == 0) PetscFunctionReturn(0);
  Vec u, F;
  PetscCall(SNESGetSolution(snes, &u));
  auto* objective = static_cast<Objective*>(ctx);
  const long revision = objective->revision();
  PetscCall(objective->accepted(u));
  if (objective->revision() == revision) PetscFunctionReturn(0);
  PetscCall(SNESGetFunction(snes, &F, nullptr, nullptr));
  PetscCall(SNESComputeFunction(snes, u, F));
  PetscReal norm;
  PetscCall(VecNorm(F, NORM_2, &norm));
  PetscCall(SNESSetFunctionNorm(snes, norm));
  PetscFunctionReturn(0);
}

/// newtonls's line search tries u − λ y, λ ≤ 1: the direction is cut to the objective's
/// admissible step first (contact: CCD), so that no trial point lies beyond it.
PetscErrorCode admissible_direction(SNESLineSearch, Vec u, Vec y, PetscBool* changed, void* ctx) {
  PetscFunctionBeginUser;
  PetscReal alpha;
  PetscCall(VecScale(y, -1.0));
  PetscCall(static_cast<Objective*>(ctx)->max_step(u, y, &alpha));
  PetscCall(VecScale(y, -1.0));
  *changed = alpha < 1.0 ? PETSC_TRUE : PETSC_FALSE;
  if (*changed) PetscCall(VecScale(y, alpha));
  PetscFunctionReturn(0);
}

/// Whether the user set `option`, without counting as reading it: a default's check is no
/// read, so that an option the chosen solver then ignores is still reported as never used
/// (unused_options.hpp). PETSc marks an option read when it finds it; one that nothing had read
/// before is set again, unread.
PetscErrorCode option_given(const std::string& option, PetscBool* set) {
  PetscBool read_before;
  const char* value = nullptr;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsUsed(nullptr, option.c_str() + 1, &read_before));
  PetscCall(PetscOptionsFindPair(nullptr, nullptr, option.c_str(), &value, set));
  if (*set && !read_before) {
    const bool has_value = value != nullptr;
    const std::string kept = has_value ? value : "";
    PetscCall(PetscOptionsClearValue(nullptr, option.c_str()));
    PetscCall(PetscOptionsSetValue(nullptr, option.c_str(), has_value ? kept.c_str() : nullptr));
  }
  PetscFunctionReturn(0);
}

/// Every TAO type's convergence test: the energy floor, then TAO's default test. Solvers call
/// it after each iteration with f of the new iterate (tao->fc, set by TaoMonitor).
PetscErrorCode floor_then_default_test(Tao tao, void* ctx) {
  PetscReal f;
  PetscFunctionBeginUser;
  PetscCall(TaoGetSolutionStatus(tao, nullptr, &f, nullptr, nullptr, nullptr, nullptr));
  if (static_cast<StepSolver::EnergyFloor*>(ctx)->below(f)) {
    PetscCall(TaoSetConvergedReason(tao, TAO_DIVERGED_USER));
    PetscFunctionReturn(0);
  }
  PetscCall(TaoDefaultConvergenceTest(tao, nullptr));
  PetscFunctionReturn(0);
}

/// SNES's convergence test: the energy floor at the last residual's f, then SNES's default.
PetscErrorCode floor_then_default_snes_test(SNES snes, PetscInt it, PetscReal xnorm,
                                            PetscReal snorm, PetscReal fnorm,
                                            SNESConvergedReason* reason, void* ctx) {
  auto* floor = static_cast<StepSolver::EnergyFloor*>(ctx);
  PetscFunctionBeginUser;
  if (floor->below(floor->last)) {
    *reason = SNES_DIVERGED_DTOL;
    PetscFunctionReturn(0);
  }
  // The residual's norm as the monitors left it: accept_iterate recomputes it when accepting
  // the iterate changed the objective.
  if (it > 0) PetscCall(SNESGetFunctionNorm(snes, &fnorm));
  PetscCall(SNESConvergedDefault(snes, it, xnorm, snorm, fnorm, reason, nullptr));
  PetscFunctionReturn(0);
}

/// Sets each option `prefix + name` to its value unless the user already gave it (the command
/// line wins).
PetscErrorCode default_options(
    const std::string& prefix,
    std::initializer_list<std::pair<const char*, const char*>> defaults) {
  PetscFunctionBeginUser;
  for (const auto& [name, value] : defaults) {
    const std::string option = prefix + name;
    PetscBool set;
    PetscCall(option_given(option, &set));
    if (!set) PetscCall(PetscOptionsSetValue(nullptr, option.c_str(), value));
  }
  PetscFunctionReturn(0);
}

/// The group "mlshell: step solver"; the default of -mlshell_hessian_psd follows the type.
PetscErrorCode read_step_solver_options(MPI_Comm comm, StepSolverOptions* o, char* kind,
                                        size_t kind_size) {
  PetscBool psd_given = PETSC_FALSE, psd = PETSC_FALSE;
  char coarse_energy[16] = "own";
  PetscFunctionBeginUser;
  PetscOptionsBegin(comm, nullptr, "mlshell: step solver", "");
  PetscCall(PetscOptionsString("-mlshell_step_solver",
                               "tao: minimise f with TAO (-tao_type, default rmtr); snes: solve "
                               "grad f = 0 with SNES (newtonls, MUMPS LU; -snes_*, -ksp_*, -pc_*)",
                               "", kind, kind, kind_size, nullptr));
  PetscCall(PetscOptionsBool("-mlshell_hessian_psd",
                             "project every non-convex element Hessian onto the PSD cone "
                             "(default: on for -tao_type pnewton, off otherwise)",
                             "", psd, &psd, &psd_given));
  PetscBool pressure_psd = PETSC_FALSE;
  PetscCall(PetscOptionsBool("-mlshell_pressure_psd",
                             "with -mlshell_hessian_psd, project the pressure's Hessian too, per "
                             "edge (off: its exact Hessian, shifted where indefinite)",
                             "", pressure_psd, &pressure_psd, nullptr));
  o->pressure_psd = pressure_psd;
  PetscCall(PetscOptionsReal("-mlshell_force_rtol",
                             "gradient tolerance relative to the external forces: "
                             "|g| < max(-tao_gatol, this * |f_ext|)",
                             "", o->force_rtol, &o->force_rtol, nullptr));
  PetscCall(PetscOptionsString("-mlshell_coarse_energy",
                               "own|proxy: what RMTR's first-order coarse models minimise on "
                               "triangle hierarchies: each coarse mesh's own energy, or the "
                               "finest energy at the direct prolongation (paper 2 eq. 2)",
                               "", coarse_energy, coarse_energy, sizeof coarse_energy, nullptr));
  PetscOptionsEnd();
  if (std::string(coarse_energy) != "own" && std::string(coarse_energy) != "proxy")
    throw std::invalid_argument("-mlshell_coarse_energy: must be own or proxy; got '" +
                                std::string(coarse_energy) + "'");
  o->proxy_coarse_energy = std::string(coarse_energy) == "proxy";
  o->snes = std::string(kind) == "snes";
  if (o->snes) {
    o->type = "snes";
  } else {
    char type[256] = "rmtr";
    PetscCall(PetscOptionsGetString(nullptr, nullptr, "-tao_type", type, sizeof type, nullptr));
    o->type = type;
  }
  o->hessian_psd = psd_given ? static_cast<bool>(psd) : hessian_projection_default(o->type);
  PetscFunctionReturn(0);
}

/// mlshell's defaults for a SNES step solver.
PetscErrorCode snes_defaults() {
  return default_options("-", {{"snes_type", "newtonls"},
                               {"snes_atol", "1e-7"},
                               {"snes_rtol", "1e-10"},
                               {"snes_stol", "0"},
                               {"snes_max_it", "1000"},
                               {"snes_max_funcs", "1000000"},
                               {"ksp_type", "preonly"},
                               {"pc_type", "lu"},
                               {"pc_factor_mat_solver_type", "mumps"}});
}

/// mlshell's defaults for a TAO step solver. RMTR's own defaults are the paper's (ten STCG
/// iterations per smoothing step), which stall on cloth (petsc-options/rmtr-paper.yaml).
/// mlshell's default smooths with Dogleg steps whose Newton point comes from
/// vertex-patch-preconditioned CG (no factorisation above the coarsest level), with Galerkin
/// coarse models, subspace steps and retried smoothing steps after the full-multigrid start:
/// faster than factorised Dogleg smoothing on every scene measured from 13,467 dofs up (within
/// 6 % below), the fastest on free-hanging cloth but for one resolution, second on the nearly
/// linear trampoline, whose scene names rmtr-patch.yaml (docs/solvers.md;
/// petsc-options/rmtr-patch-dogleg.yaml is this default spelled out, rmtr.yaml the factorised
/// Dogleg smoothing that was the default before). Options files state what they change.
PetscErrorCode tao_defaults() {
  PetscFunctionBeginUser;
  PetscCall(default_options("-tao_", {{"type", "rmtr"},
                                      {"gatol", "1e-7"},
                                      {"gttol", "1e-10"},
                                      {"grtol", "0"},
                                      {"max_it", "1000"},
                                      {"rmtr_smoother_qp", "dogleg"},
                                      {"rmtr_smoother_pc", "vpatch"},
                                      {"rmtr_stcg_max_it", "60"},
                                      {"rmtr_newton_rtol", "1e-2"},
                                      {"rmtr_coarse_model", "galerkin"},
                                      {"rmtr_subspace", "5"},
                                      {"rmtr_retries", "3"},
                                      {"rmtr_stagnation_window", "6"}}));
  PetscCall(register_trust_region_tao_types());
  PetscCall(register_newton_baseline_tao_types());
  PetscCall(register_projected_newton_tao_type());
  PetscFunctionReturn(0);
}

/// Newton-type TAO solvers own a KSP whose prefix depends on the type (tao_bnk_, tao_nls_, ...):
/// default it to Steihaug–Toint CG with a direct factorisation unless the user chose otherwise.
PetscErrorCode ksp_defaults(KSP ksp) {
  const char* prefix = nullptr;
  PetscFunctionBeginUser;
  PetscCall(KSPGetOptionsPrefix(ksp, &prefix));
  PetscCall(default_options(std::string("-") + (prefix ? prefix : ""),
                            {{"ksp_type", "stcg"},
                             {"pc_type", "lu"},
                             {"pc_factor_mat_solver_type", "mumps"}}));
  PetscFunctionReturn(0);
}

}  // namespace

bool hessian_projection_default(const std::string& solver_type) {
  PetscBool on = solver_type == "pnewton" ? PETSC_TRUE : PETSC_FALSE;
  return on;
}

bool term_hessian_projection(const StepSolverOptions& options, const std::string& term) {
  return options.hessian_psd && (term != "pressure" || options.pressure_psd);
}

StepSolverOptions StepSolverOptions::from_options(MPI_Comm comm) {
  StepSolverOptions o;
  char kind[64] = "tao";
  PetscCallAbort(comm, read_step_solver_options(comm, &o, kind, sizeof kind));
  const std::string k = kind;
  if (k != "tao" && k != "snes")
    throw std::invalid_argument("-mlshell_step_solver: must be tao or snes; got '" + k + "'");
  if (!(o.force_rtol >= 0.0))
    throw std::invalid_argument("-mlshell_force_rtol: must be >= 0; got '" +
                                std::to_string(o.force_rtol) + "'");
  return o;
}

PetscErrorCode step_solver_options_help(MPI_Comm comm, const StepSolverOptions& options) {
  PetscFunctionBeginUser;
  if (options.snes) {
    SNES snes;
    PetscCall(snes_defaults());
    PetscCall(SNESCreate(comm, &snes));
    PetscCall(SNESSetFromOptions(snes));
    PetscCall(SNESDestroy(&snes));
    PetscFunctionReturn(0);
  }
  Tao tao;
  KSP ksp = nullptr;
  PetscCall(tao_defaults());
  PetscCall(TaoCreate(comm, &tao));
  PetscCall(TaoSetFromOptions(tao));
  PetscCall(TaoGetKSP(tao, &ksp));
  if (ksp) {
    PetscCall(ksp_defaults(ksp));
    PetscCall(KSPSetFromOptions(ksp));
  }
  PetscCall(TaoDestroy(&tao));
  PetscFunctionReturn(0);
}

namespace {

/// Reading options checks their values identically on every rank, so a refused value is invalid
/// input: thrown (the program reports PETSc's message and exits 2), not an MPI abort.
void options_read(PetscErrorCode error, const char* what) {
  if (error)
    throw std::invalid_argument(std::string(what) + " refused an option value (PETSc error " +
                                std::to_string(error) + ")");
}

}  // namespace

bool StepSolver::EnergyFloor::below(double f) {
  if (std::isnan(start)) start = f;
  // NaN never crosses (the solvers report it themselves); -inf does.
  crossed = crossed || f < start - bound();
  return crossed;
}

void StepSolver::EnergyFloor::observe(double f) {
  if (std::isnan(start) || !(f < start - bound())) return;
  // From here on an error (a PETSc line search failing on the way down) ends the solve as
  // DIVERGED_ENERGY_UNBOUNDED, silently: PETSc's return-only handler until TaoSolve returns.
  // Before, errors go to whichever handler was in place (an option's value refused at set-up
  // is invalid input, main's handler).
  if (!trial_crossed) PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
  trial_crossed = true;
  trial_low = std::min(trial_low, f);
}

StepSolver::StepSolver(Objective& problem, MultilevelObjective* levels,
                       const StepSolverOptions* options)
    : problem_(problem) {
  floor_.problem = &problem;
  PetscCallAbort(PETSC_COMM_WORLD, problem.create_hessian(&H_));
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(H_));
  const StepSolverOptions o = options ? *options : StepSolverOptions::from_options(comm);
  force_rtol_ = o.force_rtol;
  if (o.snes) {
    PetscCallAbort(comm, snes_defaults());
    PetscCallAbort(comm, SNESCreate(comm, &snes_));
    PetscCallAbort(comm, MatCreateVecs(H_, &residual_, nullptr));
    PetscCallAbort(comm, SNESSetFunction(snes_, residual_, gradient_residual, &floor_));
    PetscCallAbort(comm, SNESSetJacobian(snes_, H_, H_, hessian_jacobian, &problem_));
    options_read(SNESSetFromOptions(snes_), "SNESSetFromOptions");
    PetscCallAbort(comm, SNESSetConvergenceTest(snes_, floor_then_default_snes_test, &floor_,
                                                nullptr));
    SNESLineSearch line_search;
    PetscCallAbort(comm, SNESGetLineSearch(snes_, &line_search));
    PetscCallAbort(comm,
                   SNESLineSearchSetPreCheck(line_search, admissible_direction, &problem_));
    PetscCallAbort(comm, SNESMonitorSet(snes_, accept_iterate, &problem_, nullptr));
    return;
  }
  PetscCallAbort(comm, tao_defaults());
  PetscCallAbort(comm, TaoCreate(comm, &tao_));
  PetscCallAbort(comm,
                 TaoSetObjectiveAndGradient(tao_, nullptr, objective_and_gradient, &floor_));
  PetscCallAbort(comm, TaoSetObjective(tao_, objective_only, &floor_));
  PetscCallAbort(comm, TaoSetHessian(tao_, H_, H_, hessian, &problem_));
  options_read(TaoSetFromOptions(tao_), "TaoSetFromOptions");
  PetscCallAbort(comm, TaoSetConvergenceTest(tao_, floor_then_default_test, &floor_));
  KSP ksp = nullptr;
  PetscCallAbort(comm, TaoGetKSP(tao_, &ksp));
  if (ksp) {
    PetscCallAbort(comm, ksp_defaults(ksp));
    options_read(KSPSetFromOptions(ksp), "KSPSetFromOptions");
  }
  if (levels && type() == "rmtr") options_read(rmtr_set_levels(tao_, levels), "rmtr_set_levels");
  PetscReal grtol, gttol;
  PetscCallAbort(comm, TaoGetTolerances(tao_, &gatol_, &grtol, &gttol));
  PetscCallAbort(comm, trust_region_set_error_source(tao_, &problem_));
}

StepSolver::~StepSolver() {
  TaoDestroy(&tao_);
  SNESDestroy(&snes_);
  VecDestroy(&residual_);
  MatDestroy(&H_);
}

std::string StepSolver::type() const {
  if (snes_) {
    SNESType t;
    SNESGetType(snes_, &t);
    return std::string("snes-") + (t ? t : "");
  }
  TaoType t;
  TaoGetType(tao_, &t);
  return t ? t : "";
}

void StepSolver::report_floor(SolveReport& report) const {
  if (!floor_.crossed) return;
  report.converged = false;
  report.unbounded = true;
  report.reason = "DIVERGED_ENERGY_UNBOUNDED";
  report.energy_start = floor_.start;
  report.energy_bound = floor_.bound();
}

PetscErrorCode StepSolver::solve_snes(Vec u, SolveReport& report) {
  PetscFunctionBeginUser;
  PetscCall(SNESSolve(snes_, nullptr, u));
  SNESConvergedReason reason;
  PetscInt its, lits;
  PetscCall(SNESGetConvergedReason(snes_, &reason));
  PetscCall(SNESGetIterationNumber(snes_, &its));
  PetscCall(SNESGetLinearSolveIterations(snes_, &lits));
  PetscReal f;
  PetscCall(problem_.objective(u, &f, nullptr));
  PetscCall(SNESGetFunctionNorm(snes_, &report.gradient_norm));
  PetscReal atol, rtol, stol;
  PetscInt maxit, maxf;
  PetscCall(SNESGetTolerances(snes_, &atol, &rtol, &stol, &maxit, &maxf));
  report.gradient_tolerance = atol;  // what -snes_atol promises of ‖∇f‖
  report.converged = reason > 0;
  report.reason = SNESConvergedReasons[reason];
  report.iterations = static_cast<int>(its);
  report.linear_iterations = static_cast<int>(lits);
  report.energy = f;
  report_floor(report);
  PetscFunctionReturn(0);
}

PetscErrorCode StepSolver::solve(Vec u, SolveReport& report) {
  PetscFunctionBeginUser;
  floor_.start = floor_.last = NAN;
  floor_.crossed = floor_.trial_crossed = false;
  floor_.trial_low = INFINITY;
  if (snes_) PetscFunctionReturn(solve_snes(u, report));
  // |g| < max(gatol, force_rtol |f_ext|): the absolute (7.1) and one relative to the forces.
  PetscReal force, gatol, grtol, gttol;
  PetscCall(problem_.force_scale(u, &force));
  PetscCall(TaoGetTolerances(tao_, &gatol, &grtol, &gttol));
  report.gradient_tolerance = std::max(gatol_, force_rtol_ * force);
  report.force_scale = force;
  PetscCall(TaoSetTolerances(tao_, report.gradient_tolerance, grtol, gttol));
  PetscCall(TaoSetSolution(tao_, u));
  PetscInt its;
  const PetscErrorCode error = TaoSolve(tao_);
  if (floor_.trial_crossed) PetscCall(PetscPopErrorHandler());  // pushed by observe()
  if (error && floor_.trial_crossed) {  // a PETSc line search failed on the way down
    floor_.crossed = true;
    PetscCall(TaoGetSolutionStatus(tao_, &its, nullptr, nullptr, nullptr, nullptr, nullptr));
    report.iterations = static_cast<int>(its);
    report.energy = floor_.trial_low;
    report.gradient_norm = 0.0;
    report_floor(report);
    PetscFunctionReturn(0);
  }
  PetscCall(error);
  TaoConvergedReason reason;
  PetscReal f, gnorm, cnorm, xdiff;
  PetscCall(TaoGetSolutionStatus(tao_, &its, &f, &gnorm, &cnorm, &xdiff, &reason));
  PetscInt lits = 0;
  PetscCall(TaoGetLinearSolveIterations(tao_, &lits));
  report.converged = reason > 0;
  report.reason = trust_region_converged_reason(tao_);
  report.iterations = static_cast<int>(its);
  report.linear_iterations = static_cast<int>(lits);
  report.energy = f;
  report.gradient_norm = gnorm;
  if (type() == "rmtr") PetscCall(rmtr_statistics(tao_, &report.rmtr));
  // A solve that failed may end at an iterate below the floor that no convergence test saw
  // (RMTR's full-multigrid start moves the iterate before its first V-cycle): one evaluation.
  if (!report.converged && !std::isnan(floor_.start)) {
    PetscReal at_end;
    PetscCall(problem_.objective(u, &at_end, nullptr));
    if (floor_.below(at_end)) report.energy = at_end;
  }
  report_floor(report);
  PetscFunctionReturn(0);
}

}  // namespace mlshell
