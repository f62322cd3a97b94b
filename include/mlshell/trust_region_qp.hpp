// Trust-region subproblems (paper eq. 4.1): approximately minimise the quadratic model
//   m(s) = gᵀs + ½ sᵀHs   subject to ‖s‖ ≤ Δ,
// with a sufficient decrease (SDC). Two strategies (paper §7.3):
//
//  * Dogleg (Powell; Nocedal & Wright, Numerical Optimization, §4.1): the path from the Cauchy
//    point p_C = −(gᵀg / gᵀHg) g to the Newton point p_N = −H⁻¹g, cut at the boundary. The
//    Newton point comes from a sparse direct factorisation through PETSc (options prefix
//    `<prefix>`, default Cholesky (LDLᵀ) by MUMPS; `<prefix>pc_type redundant` with
//    `<prefix>redundant_pc_type cholesky` and `<prefix>redundant_pc_factor_mat_solver_type
//    mumps` factorises each rank's whole copy of H alone, the same in every run, where MUMPS
//    over several ranks varies in the last bits from run to run; `redundant` makes that the
//    default, which `<prefix>pc_type` overrides). If H is indefinite or singular
//    (negative eigenvalues in the inertia of the LDLᵀ factor, or a failed factorisation), p_N is
//    taken from H + λI instead, with the least λ on a decade grid that makes the factor positive
//    definite (the modified Newton point of Nocedal & Wright §3.4): the grid starts a decade
//    below the last such λ of this solver, the first time at 10⁻¹⁰‖H‖∞, and rises tenfold.
//    Cloth Hessians are indefinite wherever the fabric is compressed, and the plain Cauchy
//    fallback then degenerates into steepest descent. The step is never worse than the Cauchy
//    point in the true model: if the path gives less decrease, or p_N is not a descent
//    direction, the Cauchy point is taken (steepest descent to the boundary when gᵀHg ≤ 0), so
//    a step is never NaN. With InexactNewton the Newton point comes from preconditioned CG
//    instead, shifted on the same grid wherever CG meets negative curvature (no factorisation).
//  * Steihaug–Toint CG: PETSc's KSPSTCG with the radius, a maximum iteration count (10 as a
//    smoother) and the model value from KSPCGGetObjFcn; it stops at the boundary on negative
//    curvature. With a preconditioner M (symmetric positive definite, e.g. PC "vpatch") the
//    iteration is preconditioned CG; the radius still bounds the Euclidean ‖s‖₂, the level
//    norm RMTR's radii are measured in (PETSc's STCG by default; `<prefix>ksp_cg_dtype
//    preconditioned` would bound ‖s‖_M instead).
#pragma once

#include <petscksp.h>

#include <string>

namespace mlshell {

struct QpResult {
  PetscReal model_decrease = 0.0;  ///< m(0) − m(s) (≥ 0 for an acceptable step)
  PetscReal step_norm = 0.0;
  /// The least radius for which the subproblem returns this same step: the radius itself for a
  /// step on the boundary, the step's length in the radius' norm for one inside (Dogleg: the
  /// longer of the Cauchy and Newton points; STCG: ‖s‖₂, the norm its radius bounds, in which
  /// plain CG's iterates lengthen monotonically; preconditioned ones need not, and a radius
  /// just above ‖s‖₂ may then stop an earlier iterate at the boundary instead).
  PetscReal radius_needed = 0.0;
  int iterations = 0;      ///< CG iterations (STCG) or Newton solves (Dogleg)
  int factorisations = 0;  ///< sparse direct factorisations (Dogleg; shifted ones included)
  const char* kind = "";   ///< "newton", "dogleg", "shifted" (Newton/dogleg with H + λI),
                           ///< "cauchy", "boundary", "interior"
};

class TrustRegionQp {
 public:
  virtual ~TrustRegionQp() = default;
  /// Computes s for the model (g, H) and radius Δ. H must not change between set_operator calls.
  virtual PetscErrorCode set_operator(Mat H) = 0;
  virtual PetscErrorCode solve(Vec g, PetscReal radius, Vec s, QpResult& result) = 0;
  /// A step whose model gradient ‖g + Hs‖₂ is at most `target` is good enough: an iterative
  /// solver may stop there (0, the default: as accurately as it can). Direct solvers ignore it.
  virtual void set_gradient_target(PetscReal target) { (void)target; }
};

/// How Dogleg computes its Newton point: by the factorisation (the default), or inexactly by
/// preconditioned CG (`pc_type` not PCNONE; at most `max_iterations`, relative tolerance
/// `rtol`). CG that meets negative curvature starts over on H + λI, λ up by decades from a
/// tenth of the last one that sufficed (first 10⁻¹⁰‖H‖∞), preconditioned by H's own PC (PC
/// vpatch is positive definite for any symmetric H); a Newton point that has used up its
/// iterations is taken as it is (the comparison with the Cauchy point guards the step).
struct InexactNewton {
  const char* pc_type = PCNONE;
  int max_iterations = 60;
  PetscReal rtol = 1e-2;
  bool iterative() const { return std::string(pc_type) != PCNONE; }
};

class DoglegQp final : public TrustRegionQp {
 public:
  /// `redundant`: the factorisation gathers H whole onto every rank (PC redundant, MUMPS Cholesky
  /// inside) unless `<prefix>pc_type` is given; for small problems such as RMTR's coarsest level.
  DoglegQp(MPI_Comm comm, const std::string& prefix, InexactNewton newton = {},
           bool redundant = false);
  ~DoglegQp() override;
  PetscErrorCode set_operator(Mat H) override;
  PetscErrorCode solve(Vec g, PetscReal radius, Vec s, QpResult& result) override;

 private:
  PetscErrorCode factor();
  PetscErrorCode factor_operator();
  /// The first λ of the decade grid for H + λI (see the .cpp).
  PetscReal first_shift(PetscReal norm) const;
  /// shifted_ = H + λI.
  PetscErrorCode shift_operator(PetscReal lambda);
  int factorisations_ = 0;  // factor_operator calls since the last solve() began
  /// The inexact Newton point −(H + λI)⁻¹g into pN, λ raised while CG meets negative curvature.
  PetscErrorCode iterative_newton(Vec g, Vec pN, QpResult& result, KSPConvergedReason* reason);
  bool iterative_ = false;
  KSP ksp_ = nullptr, ksp_shifted_ = nullptr, active_ = nullptr;  // H, H + λI, the one in use
  Mat H_ = nullptr, shifted_ = nullptr;
  PetscObjectState nonzero_state_ = 0;  ///< H_'s when shifted_ was made
  PetscReal shift_ = 0.0;       // λ of the factorised H + λI (0: H itself)
  PetscReal last_shift_ = 0.0;  // the last λ that made H + λI definite (0: none yet)
  bool factored_ = false, factor_failed_ = false, indefinite_ = false;
};

class SteihaugTointQp final : public TrustRegionQp {
 public:
  /// `pc_type`: the preconditioner (PCNONE: plain CG, as in the paper); `<prefix>pc_type`
  /// overrides it.
  SteihaugTointQp(MPI_Comm comm, const std::string& prefix, int max_iterations,
                  const char* pc_type = PCNONE);
  ~SteihaugTointQp() override;
  PetscErrorCode set_operator(Mat H) override;
  PetscErrorCode solve(Vec g, PetscReal radius, Vec s, QpResult& result) override;
  /// The KSP's absolute tolerance becomes max(target, `<prefix>ksp_atol`).
  void set_gradient_target(PetscReal target) override { target_ = target; }

 private:
  KSP ksp_ = nullptr;
  PetscReal rtol_ = 0.0, atol_ = 0.0, dtol_ = 0.0;  // the KSP's tolerances from the options
  PetscInt max_it_ = 0;
  PetscReal target_ = 0.0;
};

/// m(s) = gᵀs + ½ sᵀHs.
PetscErrorCode quadratic_model(Mat H, Vec g, Vec s, PetscReal* m);

}  // namespace mlshell
