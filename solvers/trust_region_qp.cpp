// Dogleg and Steihaug–Toint CG trust-region subproblem solvers (see trust_region_qp.hpp).
#include "mlshell/trust_region_qp.hpp"

#include <algorithm>
#include <cmath>
#include <string>

namespace mlshell {

PetscErrorCode quadratic_model(Mat H, Vec g, Vec s, PetscReal* m) {
  Vec Hs;
  PetscReal gs, sHs;
  PetscFunctionBeginUser;
  PetscCall(VecDuplicate(s, &Hs));
  PetscCall(MatMult(H, s, Hs));
  PetscCall(VecDot(g, s, &gs));
  PetscCall(VecDot(s, Hs, &sHs));
  PetscCall(VecDestroy(&Hs));
  *m = gs + 0.5 * sHs;
  PetscFunctionReturn(0);
}

// ---------------------------------------------------------------------------------------------
// Dogleg

namespace {

/// A direct solve (KSPPREONLY + Cholesky, MUMPS) configurable under `prefix`; with `redundant`,
/// on more than one rank and without -<prefix>pc_type, each rank factorises its whole copy of the
/// operator (PC redundant, Cholesky by MUMPS inside, -<prefix>redundant_...).
KSP create_direct_solver(MPI_Comm comm, const std::string& prefix, bool redundant) {
  KSP ksp;
  PC pc;
  PetscMPIInt ranks;
  PetscBool pc_given;
  PetscCallAbort(comm, MPI_Comm_size(comm, &ranks));
  PetscCallAbort(comm, PetscOptionsHasName(nullptr, prefix.c_str(), "-pc_type", &pc_given));
  PetscCallAbort(comm, KSPCreate(comm, &ksp));
  PetscCallAbort(comm, KSPSetOptionsPrefix(ksp, prefix.c_str()));
  PetscCallAbort(comm, KSPSetType(ksp, KSPPREONLY));
  PetscCallAbort(comm, KSPGetPC(ksp, &pc));
  if (redundant && ranks > 1 && !pc_given) {
    KSP inner;
    PetscCallAbort(comm, PCSetType(pc, PCREDUNDANT));
    PetscCallAbort(comm, PCRedundantGetKSP(pc, &inner));
    PetscCallAbort(comm, KSPGetPC(inner, &pc));
  }
  PetscCallAbort(comm, PCSetType(pc, PCCHOLESKY));
  PetscCallAbort(comm, PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscCallAbort(comm, KSPSetFromOptions(ksp));
  return ksp;
}

/// Whether MUMPS's factorisation F failed for want of workspace that ICNTL(14) enlarges
/// (INFOG(1) = -8, -9, -11, -12, -14, -15, -17 or -20; not -13, a failed allocation).
bool mumps_workspace_short(Mat F) {
  PetscInt info = 0;
  if (MatMumpsGetInfog(F, 1, &info)) return false;
  for (PetscInt code : {-8, -9, -11, -12, -14, -15, -17, -20})
    if (info == code) return true;
  return false;
}

/// An inexact Newton solve (CG with `newton.pc_type`) configurable under `prefix`.
KSP create_iterative_solver(MPI_Comm comm, const std::string& prefix, const InexactNewton& newton) {
  KSP ksp;
  PC pc;
  PetscCallAbort(comm, KSPCreate(comm, &ksp));
  PetscCallAbort(comm, KSPSetOptionsPrefix(ksp, prefix.c_str()));
  PetscCallAbort(comm, KSPSetType(ksp, KSPCG));
  PetscCallAbort(comm, KSPSetTolerances(ksp, newton.rtol, PETSC_DEFAULT, PETSC_DEFAULT,
                                        newton.max_iterations));
  PetscCallAbort(comm, KSPGetPC(ksp, &pc));
  PetscCallAbort(comm, PCSetType(pc, newton.pc_type));
  PetscCallAbort(comm, KSPSetFromOptions(ksp));
  return ksp;
}

}  // namespace

DoglegQp::DoglegQp(MPI_Comm comm, const std::string& prefix, InexactNewton newton, bool redundant)
    : iterative_(newton.iterative()),
      ksp_(newton.iterative() ? create_iterative_solver(comm, prefix, newton)
                              : create_direct_solver(comm, prefix, redundant)),
      ksp_shifted_(newton.iterative() ? nullptr : create_direct_solver(comm, prefix, redundant)) {}

DoglegQp::~DoglegQp() {
  KSPDestroy(&ksp_);
  KSPDestroy(&ksp_shifted_);
  MatDestroy(&shifted_);
}

PetscErrorCode DoglegQp::set_operator(Mat H) {
  PetscFunctionBeginUser;
  // A new matrix, or a new pattern under the same handle (contact pairs: LevelProblem::hessian).
  PetscObjectState nonzero_state;
  PetscCall(MatGetNonzeroState(H, &nonzero_state));
  if (H != H_ || nonzero_state != nonzero_state_) PetscCall(MatDestroy(&shifted_));
  H_ = H;
  nonzero_state_ = nonzero_state;
  PetscCall(KSPSetOperators(ksp_, H, H));
  factored_ = factor_failed_ = indefinite_ = false;
  shift_ = 0.0;
  PetscFunctionReturn(0);
}

// The least λ on a decade grid that makes H + λI positive definite: a larger shift damps the soft
// modes (bending, inertia), whose eigenvalues lie many decades below ‖H‖∞, and leaves the step no
// longer than the shift allows, whatever the radius. The grid starts a decade below the previous
// Hessian's λ (shifts change slowly along a solve), the first time at 10⁻¹⁰‖H‖∞; H + λI is
// definite by λ = ‖H‖∞ (Gershgorin).
PetscReal DoglegQp::first_shift(PetscReal norm) const {
  return std::max(1e-14 * norm, last_shift_ > 0 ? last_shift_ / 10 : 1e-10 * norm);
}

PetscErrorCode DoglegQp::shift_operator(PetscReal lambda) {
  PetscFunctionBeginUser;
  if (!shifted_) {  // the shifted matrices share one nonzero pattern
    PetscCall(MatDuplicate(H_, MAT_DO_NOT_COPY_VALUES, &shifted_));
    PetscCall(MatSetOption(shifted_, MAT_SYMMETRIC, PETSC_TRUE));  // for Cholesky
  }
  PetscCall(MatCopy(H_, shifted_, SAME_NONZERO_PATTERN));
  PetscCall(MatShift(shifted_, lambda));
  PetscFunctionReturn(0);
}

PetscErrorCode DoglegQp::factor() {
  PetscFunctionBeginUser;
  factored_ = true;
  active_ = ksp_;
  PetscCall(factor_operator());
  if (!iterative_ && (factor_failed_ || indefinite_)) {
    // The shifted matrices share one nonzero pattern: one symbolic factorisation for all λ.
    PetscReal norm;
    PetscCall(MatNorm(H_, NORM_INFINITY, &norm));
    for (PetscReal lambda = first_shift(norm);
         (factor_failed_ || indefinite_) && lambda <= 10 * norm; lambda *= 10) {
      PetscCall(shift_operator(lambda));
      // After a failed factorisation MUMPS must start over (symbolic phase included).
      if (factor_failed_ && active_ == ksp_shifted_) PetscCall(KSPReset(ksp_shifted_));
      active_ = ksp_shifted_;
      PetscCall(KSPSetOperators(active_, shifted_, shifted_));
      PetscCall(factor_operator());
      shift_ = lambda;
    }
    if (!factor_failed_ && !indefinite_) last_shift_ = shift_;
  }
  PetscFunctionReturn(0);
}

namespace {

/// The KSP whose PC factorises H in `ksp`: `ksp` itself, or under -<prefix>pc_type redundant the
/// inner one, which factorises every rank's whole copy of H alone (set up here, so that its
/// failure and inertia can be read). A sequential factorisation is the same in every run, where
/// MUMPS distributed over ranks schedules its work dynamically and its last bits, and with them
/// a hanging cloth's path through its V-cycles, vary from run to run.
PetscErrorCode factorising_solver(KSP ksp, KSP* factorising) {
  PC pc;
  PetscBool redundant;
  PetscFunctionBeginUser;
  *factorising = ksp;
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PetscObjectTypeCompare(reinterpret_cast<PetscObject>(pc), PCREDUNDANT, &redundant));
  if (redundant) {
    PetscCall(KSPSetUp(ksp));  // gathers H into the inner solver
    PetscCall(PCRedundantGetKSP(pc, factorising));
  }
  PetscFunctionReturn(0);
}

}  // namespace

PetscErrorCode DoglegQp::factor_operator() {
  PetscFunctionBeginUser;
  if (!iterative_) ++factorisations_;
  KSP solver;
  PetscCall(factorising_solver(active_, &solver));
  PC pc;
  PCType type;
  PetscCall(KSPGetPC(solver, &pc));
  PetscCall(PCGetType(pc, &type));
  const bool cholesky = type && std::string(type) == PCCHOLESKY;
  const char* prefix;
  PetscCall(KSPGetOptionsPrefix(solver, &prefix));
  bool mumps = false;
  for (int attempt = 0;; ++attempt) {
    Mat F = nullptr;
    if (cholesky) {
      MatSolverType package = nullptr;
      PetscCall(PCFactorSetUpMatSolverType(pc));
      PetscCall(PCFactorGetMatSolverType(pc, &package));
      PetscCall(PCFactorGetMatrix(pc, &F));
      // The factor reads its options (-<prefix>mat_mumps_icntl_14 ...) under the solver's
      // prefix; PCFactorSetUpMatSolverType leaves it unnamed.
      PetscCall(MatSetOptionsPrefix(F, prefix));
      mumps = package && std::string(package) == MATSOLVERMUMPS;
    }
    if (mumps) {
      // MUMPS reports the inertia of its LDLᵀ factor correctly in parallel only with ICNTL(13) = 1.
      PetscCall(MatMumpsSetIcntl(F, 13, 1));
    }
    PetscCall(KSPSetUp(solver));
    PCFailedReason failed;
    PetscCall(PCGetFailedReason(pc, &failed));
    factor_failed_ = failed != PC_NOERROR;
    if (!factor_failed_ || !mumps || !mumps_workspace_short(F) || attempt == 6) break;
    // The pivots LDLᵀ delays on a nearly singular H (the penalty's stiff rows next to soft
    // bending) outgrow the workspace the analysis estimated: more of it, not a shift, which
    // would damp the soft modes. MUMPS starts over with it (its options are read again, so the
    // larger workspace goes into them), and the solver keeps it for later factorisations.
    PetscInt percent;
    PetscCall(MatMumpsGetIcntl(F, 14, &percent));
    const PetscInt larger = std::max<PetscInt>(100, 2 * percent);
    PetscCall(PetscInfo(active_,
                        "MUMPS ran out of workspace with ICNTL(14) = %" PetscInt_FMT
                        "; factorising again with %" PetscInt_FMT "\n",
                        percent, larger));
    const std::string option = std::string("-") + (prefix ? prefix : "") + "mat_mumps_icntl_14";
    PetscCall(PetscOptionsSetValue(nullptr, option.c_str(), std::to_string(larger).c_str()));
    Mat op;
    PetscCall(KSPGetOperators(solver, &op, nullptr));
    PetscCall(PetscObjectReference(reinterpret_cast<PetscObject>(op)));
    PetscCall(KSPReset(solver));
    PetscCall(KSPSetOperators(solver, op, op));
    PetscCall(MatDestroy(&op));
  }
  if (cholesky && !factor_failed_ && mumps) {
    // A negative eigenvalue of H: no Newton point to go towards. (Zero pivots would need
    // ICNTL(24); a singular H shows up as a failed factorisation or a non-finite Newton point.)
    Mat F;
    PetscInt negative;
    PetscCall(PCFactorGetMatrix(pc, &F));
    PetscCall(MatGetInertia(F, &negative, nullptr, nullptr));
    indefinite_ = negative > 0;
  }
  PetscFunctionReturn(0);
}

PetscErrorCode DoglegQp::iterative_newton(Vec g, Vec pN, QpResult& result,
                                          KSPConvergedReason* reason) {
  PetscFunctionBeginUser;
  // The KSP keeps H + λI (and λ) between the solves of one Hessian; H's PC is set up once.
  PetscCall(KSPSolve(ksp_, g, pN));
  ++result.iterations;
  PetscCall(KSPGetConvergedReason(ksp_, reason));
  if (*reason == KSP_DIVERGED_INDEFINITE_MAT) {
    PetscReal norm;
    PetscCall(MatNorm(H_, NORM_INFINITY, &norm));
    for (PetscReal lambda = std::max(shift_ * 10, first_shift(norm));
         *reason == KSP_DIVERGED_INDEFINITE_MAT && lambda <= 10 * norm; lambda *= 10) {
      PetscCall(shift_operator(lambda));
      PetscCall(KSPSetOperators(ksp_, shifted_, H_));
      PetscCall(KSPSolve(ksp_, g, pN));
      ++result.iterations;
      PetscCall(KSPGetConvergedReason(ksp_, reason));
      shift_ = lambda;
    }
    if (*reason != KSP_DIVERGED_INDEFINITE_MAT) last_shift_ = shift_;
  }
  // Out of iterations: an inexact Newton point, still a usable dogleg end.
  if (*reason == KSP_DIVERGED_ITS) *reason = KSP_CONVERGED_ITS;
  PetscFunctionReturn(0);
}

PetscErrorCode DoglegQp::solve(Vec g, PetscReal radius, Vec s, QpResult& result) {
  PetscFunctionBeginUser;
  PetscReal gnorm, gHg;
  PetscCall(VecNorm(g, NORM_2, &gnorm));
  result = QpResult{};
  factorisations_ = 0;
  if (gnorm == 0.0) {
    PetscCall(VecZeroEntries(s));
    result.kind = "interior";
    PetscFunctionReturn(0);
  }
  Vec Hg, pC, pN;
  PetscCall(VecDuplicate(g, &Hg));
  PetscCall(VecDuplicate(g, &pC));
  PetscCall(VecDuplicate(g, &pN));
  PetscCall(MatMult(H_, g, Hg));
  PetscCall(VecDot(g, Hg, &gHg));
  // Cauchy point: the model's minimiser along −g within the region.
  bool done = false;
  if (!(gHg > 0.0) || gnorm * gnorm / gHg * gnorm >= radius) {
    PetscCall(VecAXPBY(s, -radius / gnorm, 0.0, g));  // to the boundary
    result.kind = "cauchy";
    result.radius_needed = radius;
    done = true;
  } else {
    PetscCall(VecAXPBY(pC, -gnorm * gnorm / gHg, 0.0, g));
    result.radius_needed = gnorm * gnorm / gHg * gnorm;  // ‖p_C‖
  }
  if (!done) {
    // Newton point p_N = −H⁻¹g; the factorisation is computed once per operator.
    if (!factored_) PetscCall(factor());
    bool newton_ok = !factor_failed_ && !indefinite_;  // of H, or of H + λI
    if (newton_ok) {
      KSPConvergedReason reason;
      if (iterative_) {
        PetscCall(iterative_newton(g, pN, result, &reason));
      } else {
        PetscCall(KSPSolve(active_, g, pN));
        ++result.iterations;
        PetscCall(KSPGetConvergedReason(active_, &reason));
      }
      PetscCall(VecScale(pN, -1.0));
      PetscReal gp, pHp, pnorm;
      PetscCall(VecDot(g, pN, &gp));
      PetscCall(quadratic_model(H_, g, pN, &pHp));  // m(p_N) = gᵀp + ½ pᵀHp
      pHp = 2.0 * (pHp - gp);
      PetscCall(VecNorm(pN, NORM_2, &pnorm));
      // Singular H, or negative curvature along p_N: no usable Newton point. (With a shift,
      // pᵀHp may be negative; the comparison with the Cauchy point below guards the step.)
      newton_ok = reason >= 0 && std::isfinite(pnorm) && gp < 0.0 && (shift_ > 0 || pHp > 0.0);
      if (reason < 0) factor_failed_ = true;
    }
    if (!newton_ok) {
      PetscCall(VecCopy(pC, s));
      result.kind = "cauchy";
    } else {
      PetscReal pnorm;
      PetscCall(VecNorm(pN, NORM_2, &pnorm));
      if (pnorm <= radius) {
        PetscCall(VecCopy(pN, s));
        result.kind = shift_ > 0 ? "shifted" : "newton";
        result.radius_needed = std::max(result.radius_needed, pnorm);
      } else {
        // ‖p_C + t (p_N − p_C)‖ = Δ for t ∈ [0, 1].
        Vec d = pN;
        PetscCall(VecAXPY(d, -1.0, pC));
        PetscReal a, b, c;
        PetscCall(VecDot(d, d, &a));
        PetscCall(VecDot(pC, d, &b));
        PetscCall(VecDot(pC, pC, &c));
        b *= 2.0;
        c -= radius * radius;
        const PetscReal t = (-b + std::sqrt(std::max(0.0, b * b - 4.0 * a * c))) / (2.0 * a);
        PetscCall(VecWAXPY(s, t, d, pC));
        result.kind = shift_ > 0 ? "shifted" : "dogleg";
        result.radius_needed = radius;
      }
      // The modified Newton point, or CG's (which may have missed negative curvature), must
      // beat the Cauchy point in the true model.
      if (shift_ > 0 || iterative_) {
        PetscReal ms, mc;
        PetscCall(quadratic_model(H_, g, s, &ms));
        PetscCall(quadratic_model(H_, g, pC, &mc));
        if (!(ms <= mc)) {
          PetscCall(VecCopy(pC, s));
          result.kind = "cauchy";
        }
      }
    }
  }
  PetscReal m;
  PetscCall(quadratic_model(H_, g, s, &m));
  result.factorisations = factorisations_;
  result.model_decrease = -m;
  PetscCall(VecNorm(s, NORM_2, &result.step_norm));
  PetscCall(VecDestroy(&Hg));
  PetscCall(VecDestroy(&pC));
  PetscCall(VecDestroy(&pN));
  PetscFunctionReturn(0);
}

// ---------------------------------------------------------------------------------------------
// Steihaug–Toint CG

SteihaugTointQp::SteihaugTointQp(MPI_Comm comm, const std::string& prefix, int max_iterations,
                                 const char* pc_type) {
  PetscCallAbort(comm, KSPCreate(comm, &ksp_));
  PetscCallAbort(comm, KSPSetOptionsPrefix(ksp_, prefix.c_str()));
  PetscCallAbort(comm, KSPSetType(ksp_, KSPSTCG));
  PetscCallAbort(comm, KSPSetTolerances(ksp_, 1e-10, PETSC_DEFAULT, PETSC_DEFAULT, max_iterations));
  PC pc;
  PetscCallAbort(comm, KSPGetPC(ksp_, &pc));
  PetscCallAbort(comm, PCSetType(pc, pc_type));
  PetscCallAbort(comm, KSPSetFromOptions(ksp_));
  PetscCallAbort(comm, KSPGetTolerances(ksp_, &rtol_, &atol_, &dtol_, &max_it_));
}

SteihaugTointQp::~SteihaugTointQp() { KSPDestroy(&ksp_); }

PetscErrorCode SteihaugTointQp::set_operator(Mat H) {
  PetscFunctionBeginUser;
  PetscCall(KSPSetOperators(ksp_, H, H));
  PetscFunctionReturn(0);
}

PetscErrorCode SteihaugTointQp::solve(Vec g, PetscReal radius, Vec s, QpResult& result) {
  PetscFunctionBeginUser;
  result = QpResult{};
  Vec b;
  PetscCall(VecDuplicate(g, &b));
  PetscCall(VecAXPBY(b, -1.0, 0.0, g));  // STCG minimises ½ sᵀHs − sᵀb
  PetscCall(KSPCGSetRadius(ksp_, radius));
  // STCG measures the unpreconditioned residual b − Hs = −(g + Hs), the model's gradient at s.
  PetscCall(KSPSetTolerances(ksp_, rtol_, std::max(atol_, target_), dtol_, max_it_));
  PetscCall(KSPSolve(ksp_, b, s));
  PetscCall(VecDestroy(&b));
  PetscInt its;
  PetscReal obj;
  KSPConvergedReason reason;
  PetscCall(KSPGetIterationNumber(ksp_, &its));
  PetscCall(KSPCGGetObjFcn(ksp_, &obj));
  PetscCall(KSPGetConvergedReason(ksp_, &reason));
  PetscCall(VecNorm(s, NORM_2, &result.step_norm));
  result.iterations = static_cast<int>(its);
  result.model_decrease = -obj;
  const bool boundary =
      reason == KSP_CONVERGED_CG_NEG_CURVE || reason == KSP_CONVERGED_CG_CONSTRAINED;
  result.kind = boundary ? "boundary" : "interior";
  if (boundary)
    result.radius_needed = radius;
  else
    PetscCall(KSPCGGetNormD(ksp_, &result.radius_needed));  // ‖s‖ in the norm of the radius
  PetscFunctionReturn(0);
}

}  // namespace mlshell
