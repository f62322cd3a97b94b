// TAO as the step solver (see step_solver.hpp for the defaults).
#include "mlshell/step_solver.hpp"

#include <string>

namespace mlshell {

namespace {

PetscErrorCode objective_and_gradient(Tao, Vec u, PetscReal* f, Vec g, void* ctx) {
  return static_cast<LevelProblem*>(ctx)->objective(u, f, g);
}

PetscErrorCode objective_only(Tao, Vec u, PetscReal* f, void* ctx) {
  return static_cast<LevelProblem*>(ctx)->objective(u, f, nullptr);
}

PetscErrorCode hessian(Tao, Vec u, Mat H, Mat, void* ctx) {
  return static_cast<LevelProblem*>(ctx)->hessian(u, H);
}

/// Sets `name` to `value` unless the user already gave it (the command line wins).
PetscErrorCode default_option(const char* name, const char* value) {
  PetscBool set;
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsHasName(nullptr, nullptr, name, &set));
  if (!set) PetscCall(PetscOptionsSetValue(nullptr, name, value));
  PetscFunctionReturn(0);
}

}  // namespace

std::string step_solver_type() {
  char type[256] = "rmtr";
  PetscCallAbort(PETSC_COMM_WORLD,
                 PetscOptionsGetString(nullptr, nullptr, "-tao_type", type, sizeof type, nullptr));
  return type;
}

StepSolver::StepSolver(LevelProblem& problem, MultilevelObjective* levels) : problem_(problem) {
  MPI_Comm comm = problem.layout().comm();
  PetscCallAbort(comm, default_option("-tao_type", "rmtr"));
  PetscCallAbort(comm, default_option("-tao_gatol", "1e-7"));
  PetscCallAbort(comm, default_option("-tao_gttol", "1e-10"));
  PetscCallAbort(comm, default_option("-tao_grtol", "0"));
  PetscCallAbort(comm, default_option("-tao_max_it", "1000"));
  // RMTR's own default smoother is the paper's ten STCG iterations; on cloth they stall on
  // fine-scale bending modes (trampoline, 1,083 dofs: |g| = 3e-3 after 200 V-cycles), while
  // Dogleg smoothing converges in 3. See petsc-options/rmtr-paper.yaml for the paper's setup.
  PetscCallAbort(comm, default_option("-tao_rmtr_smoother_qp", "dogleg"));
  PetscCallAbort(comm, register_trust_region_tao_types());
  PetscCallAbort(comm, register_newton_baseline_tao_types());
  PetscCallAbort(comm, TaoCreate(comm, &tao_));
  PetscCallAbort(comm, problem.create_matrix(&H_));
  PetscCallAbort(comm,
                 TaoSetObjectiveAndGradient(tao_, nullptr, objective_and_gradient, &problem_));
  PetscCallAbort(comm, TaoSetObjective(tao_, objective_only, &problem_));
  PetscCallAbort(comm, TaoSetHessian(tao_, H_, H_, hessian, &problem_));
  PetscCallAbort(comm, TaoSetFromOptions(tao_));
  // Newton-type TAO solvers own a KSP whose prefix depends on the type (tao_bnk_, tao_nls_, ...):
  // default it to Steihaug–Toint CG with a direct factorisation unless the user chose otherwise.
  KSP ksp = nullptr;
  PetscCallAbort(comm, TaoGetKSP(tao_, &ksp));
  if (ksp) {
    const char* prefix = nullptr;
    PetscCallAbort(comm, KSPGetOptionsPrefix(ksp, &prefix));
    const std::string p = std::string("-") + (prefix ? prefix : "");
    PetscCallAbort(comm, default_option((p + "ksp_type").c_str(), "stcg"));
    PetscCallAbort(comm, default_option((p + "pc_type").c_str(), "lu"));
    PetscCallAbort(comm, default_option((p + "pc_factor_mat_solver_type").c_str(), "mumps"));
    PetscCallAbort(comm, KSPSetFromOptions(ksp));
  }
  if (levels && type() == "rmtr") PetscCallAbort(comm, rmtr_set_levels(tao_, levels));
}

StepSolver::~StepSolver() {
  TaoDestroy(&tao_);
  MatDestroy(&H_);
}

std::string StepSolver::type() const {
  TaoType t;
  TaoGetType(tao_, &t);
  return t ? t : "";
}

PetscErrorCode StepSolver::solve(Vec u, SolveReport& report) {
  PetscFunctionBeginUser;
  PetscCall(TaoSetSolution(tao_, u));
  PetscCall(TaoSolve(tao_));
  TaoConvergedReason reason;
  PetscInt its;
  PetscReal f, gnorm, cnorm, xdiff;
  PetscCall(TaoGetSolutionStatus(tao_, &its, &f, &gnorm, &cnorm, &xdiff, &reason));
  PetscInt lits = 0;
  PetscCall(TaoGetLinearSolveIterations(tao_, &lits));
  report.converged = reason > 0;
  report.reason = TaoConvergedReasons[reason];
  report.iterations = static_cast<int>(its);
  report.linear_iterations = static_cast<int>(lits);
  report.energy = f;
  report.gradient_norm = gnorm;
  if (type() == "rmtr") PetscCall(rmtr_statistics(tao_, &report.rmtr));
  PetscFunctionReturn(0);
}

}  // namespace mlshell
