// Subspace acceleration of a multilevel iteration: after each V-cycle, one more trust-region
// step of the level, in the span of the V-cycle's correction and the level's last total changes
// (-tao_rmtr_subspace m: the correction and m − 1 earlier changes).
//
// A V-cycle whose error propagation has a few slowly contracted modes leaves its corrections
// nearly parallel to them: once the fast modes are gone, a correction s_k from y_k is about
// (1 − c) e along the slow error e, c the contraction. Minimising the model over the span of s_k
// and the previous changes p_j = y_{j+1} − y_j is what Krylov acceleration of multigrid does for
// a linear problem (with m = 2 and a fixed symmetric V-cycle, preconditioned CG's recurrence);
// with m = 1 it is the optimal step length along the correction (1/(1 − c) for one slow mode).
// Here the step is a Local_TR iteration (paper Alg. 4.1) at z = y_k + s_k:
//   min  m(d) = ∇f(z)ᵀd + ½ dᵀHd   over d = Dα, ‖d‖ ≤ min(Δ, r‖s_k‖),   D = [s_k, p_{k−1}, …],
// with H the Hessian of the level's last subproblem (no extra assembly: its post-smoothing
// model), solved exactly in the (at most m) dimensions D spans (ℓ₂-orthonormalised by the Gram
// matrix DᵀD; Moré–Sorensen on the small eigendecomposition, the hard case included). The trial
// z + d is accepted when ρ = (f(z) − f(z + d)) / (m(0) − m(d)) > η₁, as any trust-region step:
// the energy never rises. The reach r is the step's own radius, in multiples of the correction:
// it starts at 1, doubles after a step with ρ > η₂ on its boundary and shrinks below a rejected
// step's length (Alg. 4.1's rule), within [¼, 1000]. Hanging cloth needs it: its remaining error
// near the solution is a sway, a rotation, and the energy along the straight line z + t·d leaves
// its quadratic model within a few corrections' lengths (ρ = −1 to −15 at 3–10 of them on the
// re-entrant corner at ‖g‖ ≈ 10⁻³). The level's radius Δ is left alone (the V-cycle's own
// iterations govern it), and while Δ limits the V-cycle's corrections (longer than ½Δ:
// globalisation, where the model is poor beyond them) no step is tried and only the latest
// change is kept. Costs per V-cycle: m Hessian-vector products, a few reductions and one
// evaluation of f and ∇f (whose gradient serves the next pre-smoothing step if accepted).
#pragma once

#include <petscvec.h>

#include <Eigen/Dense>
#include <vector>

#include "mlshell/local_trust_region.hpp"

namespace mlshell {

/// The exact minimiser of bᵀa + ½ aᵀAa subject to ‖a‖₂ ≤ radius, A symmetric (any inertia).
struct SmallTrustRegionStep {
  Eigen::VectorXd a;
  double model = 0.0;     ///< bᵀa + ½ aᵀAa (≤ 0)
  bool boundary = false;  ///< ‖a‖ = radius
};
SmallTrustRegionStep solve_small_trust_region(const Eigen::MatrixXd& A, const Eigen::VectorXd& b,
                                              double radius);

/// What one acceleration step did.
struct SubspaceStep {
  bool tried = false;     ///< a step with a positive predicted reduction was evaluated
  bool accepted = false;  ///< ρ > η₁
  PetscReal rho = 0.0;
  /// The coefficient of the V-cycle's correction in the step: z + d = y + (1 + this) s + …
  PetscReal relaxation = 0.0;
};

class SubspaceAcceleration {
 public:
  /// `depth` m ≥ 1: the V-cycle's correction and m − 1 earlier changes.
  explicit SubspaceAcceleration(int depth);
  ~SubspaceAcceleration();
  SubspaceAcceleration(const SubspaceAcceleration&) = delete;
  SubspaceAcceleration& operator=(const SubspaceAcceleration&) = delete;
  /// Forgets the earlier changes (a new start of the level).
  void reset() {
    stored_ = 0;
    reach_ = 1.0;
  }
  /// One step of `tr` after a V-cycle that started at `start` (y_k) and left tr at z; `delta` is
  /// the level's radius Δ. The change y_{k+1} − y_k joins the history.
  PetscErrorCode step(LocalTrustRegion& tr, Vec start, const TrustRegionParameters& p,
                      PetscReal delta, SubspaceStep* out);

 private:
  PetscErrorCode allocate(Vec like);
  int depth_;
  int stored_ = 0;                 // earlier changes held in history_[0 .. stored_)
  PetscReal reach_ = 1.0;          // the step's radius over the correction's ℓ₂ length
  std::vector<Vec> history_;       // newest first
  std::vector<Vec> directions_;    // D: the correction, then history_ (not owned beyond [0])
  std::vector<Vec> products_;      // H D
  Vec correction_ = nullptr, step_ = nullptr;
};

}  // namespace mlshell
