// The round-off floor (paper §7.2): a trust-region solve keeps a meaningful ρ below the noise
// of f (trapezoidal actual reduction), stops as converged at the limiting accuracy when even
// the gradient is noise, and still fails when the radius collapses far above the floor.
#include <gtest/gtest.h>
#include <petsctao.h>

#include <cmath>
#include <cstdint>
#include <cstring>

#include "mlshell/local_trust_region.hpp"
#include "mlshell/trust_region.hpp"
#include "mlshell/trust_region_qp.hpp"

using namespace mlshell;

namespace {

/// Deterministic noise in [−1, 1] from the bits of x (the same x gives the same value, as with
/// a real rounding error).
double noise(const PetscScalar* x, PetscInt n, std::uint64_t salt) {
  std::uint64_t h = 1469598103934665603ull ^ salt;
  for (PetscInt i = 0; i < n; ++i) {
    std::uint64_t b;
    std::memcpy(&b, &x[i], sizeof b);
    h = (h ^ b) * 1099511628211ull;
    h ^= h >> 29;
  }
  return static_cast<double>(h % 2000001) / 1e6 - 1.0;
}

/// f(x) = c + ½ Σ d_i x_i² − Σ x_i on 50 unknowns (d from 1 to 1e4; the Hessian handed to the
/// solver is off by up to 50 %; c = `f_offset`), with noise of absolute size
/// `f_noise` in f, `g_noise` in each gradient entry, a constant `g_bias` added to ∇f and a
/// `g_sign` multiplying it (wrong gradients).
struct NoisyQuadratic final : Objective {
  double f_noise = 0.0, g_noise = 0.0, g_bias = 0.0, g_sign = 1.0, f_offset = 0.0;
  double hessian_scale = 0.0;  // H = this × ∇²f (> 1: every step a fraction of Newton's,
                               // every one accepted); 0: 50 % off on some entries
  int evaluations = 0, gradients = 0;  // objective() calls, and those with a gradient
  static constexpr PetscInt n = 50;
  static double d(PetscInt i) { return std::pow(1e4, static_cast<double>(i) / (n - 1)); }
  PetscErrorCode objective(Vec x, PetscReal* f, Vec g) override {
    const PetscScalar* a;
    PetscFunctionBeginUser;
    ++evaluations;
    gradients += g != nullptr;
    PetscCall(VecGetArrayRead(x, &a));
    double v = 0.0;
    for (PetscInt i = 0; i < n; ++i) v += 0.5 * d(i) * a[i] * a[i] - a[i];
    *f = f_offset + v + f_noise * noise(a, n, 1);
    if (g) {
      PetscScalar* ga;
      PetscCall(VecGetArray(g, &ga));
      for (PetscInt i = 0; i < n; ++i)
        ga[i] = g_sign * (d(i) * a[i] - 1.0) + g_bias + g_noise * noise(a, n, 100 + i);
      PetscCall(VecRestoreArray(g, &ga));
    }
    PetscCall(VecRestoreArrayRead(x, &a));
    PetscFunctionReturn(0);
  }
  PetscErrorCode hessian(Vec, Mat H) override {
    PetscFunctionBeginUser;
    // 50 % off on some entries (or a multiple of ∇²f), so that the solve converges linearly.
    for (PetscInt i = 0; i < n; ++i)
      PetscCall(MatSetValue(H, i, i,
                            d(i) * (hessian_scale > 0 ? hessian_scale : 1.0 + 0.5 * std::sin(i)),
                            INSERT_VALUES));
    PetscCall(MatAssemblyBegin(H, MAT_FINAL_ASSEMBLY));
    PetscCall(MatAssemblyEnd(H, MAT_FINAL_ASSEMBLY));
    PetscFunctionReturn(0);
  }
  PetscReal evaluation_error() const override { return f_noise; }
};

PetscErrorCode fg(Tao, Vec x, PetscReal* f, Vec g, void* c) {
  return static_cast<NoisyQuadratic*>(c)->objective(x, f, g);
}
PetscErrorCode fonly(Tao, Vec x, PetscReal* f, void* c) {
  return static_cast<NoisyQuadratic*>(c)->objective(x, f, nullptr);
}
PetscErrorCode hess(Tao, Vec x, Mat H, Mat, void* c) {
  return static_cast<NoisyQuadratic*>(c)->hessian(x, H);
}

struct Outcome {
  std::string reason;
  bool converged = false;
  double gnorm = 0.0;
};

/// Solves with mlshell's TAO type `type` ("tr" or "rmtr" on one level) from x = 0.
Outcome solve(NoisyQuadratic& q, const char* type, double gatol) {
  Tao tao;
  Vec x;
  Mat H;
  Outcome out;
  register_trust_region_tao_types();
  VecCreateSeq(PETSC_COMM_SELF, NoisyQuadratic::n, &x);
  MatCreateSeqAIJ(PETSC_COMM_SELF, NoisyQuadratic::n, NoisyQuadratic::n, 1, nullptr, &H);
  MatSetOption(H, MAT_SYMMETRIC, PETSC_TRUE);
  TaoCreate(PETSC_COMM_SELF, &tao);
  TaoSetType(tao, type);
  TaoSetObjectiveAndGradient(tao, nullptr, fg, &q);
  TaoSetObjective(tao, fonly, &q);
  TaoSetHessian(tao, H, H, hess, &q);
  TaoSetFromOptions(tao);
  TaoSetTolerances(tao, gatol, 0.0, 0.0);
  TaoSetMaximumIterations(tao, 500);
  trust_region_set_error_source(tao, &q);
  VecSet(x, 0.0);
  TaoSetSolution(tao, x);
  TaoSolve(tao);
  TaoConvergedReason reason;
  TaoGetConvergedReason(tao, &reason);
  out.converged = reason > 0;
  out.reason = trust_region_converged_reason(tao);
  PetscInt its;
  PetscReal f, cnorm, xdiff;
  TaoGetSolutionStatus(tao, &its, &f, &out.gnorm, &cnorm, &xdiff, &reason);
  TaoDestroy(&tao);
  MatDestroy(&H);
  VecDestroy(&x);
  return out;
}

}  // namespace

TEST(LimitingAccuracy, GradientsKeepRhoMeaningfulBelowTheNoiseOfTheEnergy) {
  // |f| ≈ 0.25; energy noise 1e-9 hides every reduction below |g|² / d_max ~ 1e-9, i.e.
  // |g| ≲ 3e-3, but the gradients are exact: the solve must reach |g| < 1e-10 regardless.
  for (const char* type : {"tr", "rmtr"}) {
    NoisyQuadratic q;
    q.f_noise = 1e-9;
    const Outcome o = solve(q, type, 1e-10);
    EXPECT_EQ(o.reason, "CONVERGED_GATOL") << type;
    EXPECT_LT(o.gnorm, 1e-10) << type;
  }
}

TEST(LimitingAccuracy, ARadiusCollapseAtTheFloorIsConvergence) {
  // Gradient entries carry noise of 1e-12 (|g| floor ≈ 1e-11 over 50 entries), above the
  // tolerance 1e-12 but within its factor 100: converged at the limiting accuracy.
  for (const char* type : {"tr", "rmtr"}) {
    NoisyQuadratic q;
    q.f_noise = 1e-9;
    q.g_noise = 1e-12;
    const Outcome o = solve(q, type, 1e-12);
    EXPECT_EQ(o.reason, "CONVERGED_LIMITING_ACCURACY") << type;
    EXPECT_TRUE(o.converged) << type;
    EXPECT_LT(o.gnorm, 1e-10) << type;
  }
}

TEST(LimitingAccuracy, StallingFarAboveTheFloorStaysAFailure) {
  // A gradient with a constant error of 1e-3 per entry and an energy accurate to 1e-15: no step
  // along it lowers f once the true gradient is small; the solve fails (radius collapse or
  // iteration limit) with |g| ≫ 100 × the tolerance, never at the limiting accuracy.
  for (const char* type : {"tr", "rmtr"}) {
    NoisyQuadratic q;
    q.f_noise = 1e-15;
    q.g_bias = 1e-3;
    const Outcome o = solve(q, type, 1e-10);
    EXPECT_EQ(o.reason.rfind("DIVERGED_", 0), 0u) << type << ": " << o.reason;
    EXPECT_FALSE(o.converged) << type;
    EXPECT_GT(o.gnorm, 1e-5) << type;
  }
}

TEST(LimitingAccuracy, ARadiusCollapseFarAboveTheFloorStaysAFailure) {
  // A gradient of the wrong sign: every step the model proposes raises f, so the radius
  // collapses at x = 0 with |g| = 7.07, far above 100 × the tolerance: a failure, not the floor.
  for (const char* type : {"tr", "rmtr"}) {
    NoisyQuadratic q;
    q.f_noise = 1e-15;
    q.g_sign = -1.0;
    const Outcome o = solve(q, type, 1e-8);
    EXPECT_EQ(o.reason, "DIVERGED_TR_REDUCTION") << type;
    EXPECT_FALSE(o.converged) << type;
    EXPECT_NEAR(o.gnorm, std::sqrt(50.0), 1e-6) << type;
  }
}

TEST(LimitingAccuracy, AnIterationThatStillLowersTheGradientHasNotStagnated) {
  // Radius 1e20 (Newton's regime) and a decrease of f below 1e-12 |f|: stagnation by the paper's
  // (7.1), unless ‖g‖ is still falling: one of the last 3 iterations took it below 0.9 times its
  // lowest value before. V-cycles contracting ‖g‖ by 0.5 near a soft mode lower f by less than
  // its resolution, one of them may raise ‖g‖ a little, and they still converge.
  const double f = -1.4, df = 1e-13, dx = 1e-6, xnorm = 1.0;
  {
    StoppingRule rule;
    double g = 0.0;
    for (int k = 0; k < 10; ++k) {
      g = 1e-3 * std::pow(0.5, k);
      EXPECT_FALSE(rule.stagnated(1e20, df, f, dx, xnorm, g)) << k;
    }
    // a setback does not end it, nor a second iteration without a new low ...
    EXPECT_FALSE(rule.stagnated(1e20, df, f, dx, xnorm, 1.04 * g));
    EXPECT_FALSE(rule.stagnated(1e20, df, f, dx, xnorm, 0.95 * g));
    // ... and a new low starts the count again ...
    EXPECT_FALSE(rule.stagnated(1e20, df, f, dx, xnorm, 0.85 * g));
    EXPECT_FALSE(rule.stagnated(1e20, df, f, dx, xnorm, 0.85 * g));
    EXPECT_FALSE(rule.stagnated(1e20, df, f, dx, xnorm, 0.80 * g));
    // ... so the third iteration without one ends the solve
    EXPECT_TRUE(rule.stagnated(1e20, df, f, dx, xnorm, 0.78 * g));
    rule.reset();  // a new solve starts afresh
    EXPECT_FALSE(rule.stagnated(1e20, df, f, dx, xnorm, g));
  }
  {
    StoppingRule rule;  // ‖g‖ at its floor: the third iteration without a new low stagnates
    for (int k = 0; k < 3; ++k) EXPECT_FALSE(rule.stagnated(1e20, df, f, dx, xnorm, 1e-7)) << k;
    EXPECT_TRUE(rule.stagnated(1e20, df, f, dx, xnorm, 0.95e-7));
  }
  {
    StoppingRule rule;  // slow progress, 2 % per iteration, is stagnation
    double g = 1e-3;
    int k = 0;
    for (; k < 10 && !rule.stagnated(1e20, df, f, dx, xnorm, g); ++k) g *= 0.98;
    EXPECT_EQ(k, 3);
  }
  StoppingRule rule;  // the other conditions of (7.1), with no progress in ‖g‖
  for (int k = 0; k < 3; ++k) rule.stagnated(1e20, df, f, dx, xnorm, 1.0);
  EXPECT_FALSE(rule.stagnated(1e10, df, f, dx, xnorm, 1.0));        // not yet Newton's regime
  EXPECT_FALSE(rule.stagnated(1e20, 1e-6, 1.0, 1e-6, xnorm, 1.0));  // f and x still move
  EXPECT_TRUE(rule.stagnated(1e20, 1e-6, 1.0, 1e-14, xnorm, 1.0));  // x no longer does
}

TEST(LimitingAccuracy, StagnationIsConvergenceOnlyNearTheTolerance) {
  // The second part of (7.1) ends a solve; with ‖g‖ within the limiting factor (100) of the
  // tolerance that is convergence (CONVERGED_STEPTOL), above it a failure.
  Tao tao;
  TaoCreate(PETSC_COMM_SELF, &tao);
  TaoSetTolerances(tao, 1e-7, 0.0, 1e-10);
  StoppingRule rule;
  TaoConvergedReason reason;
  rule.end_stagnated(tao, 9e-6, 1.0);
  TaoGetConvergedReason(tao, &reason);
  EXPECT_EQ(reason, TAO_CONVERGED_STEPTOL);
  rule.end_stagnated(tao, 2e-5, 1.0);
  TaoGetConvergedReason(tao, &reason);
  EXPECT_EQ(reason, TAO_DIVERGED_USER);
  rule.end_stagnated(tao, 2e-5, 1e6);  // the relative tolerance 1e-10 ‖g₀‖ = 1e-4 governs
  TaoGetConvergedReason(tao, &reason);
  EXPECT_EQ(reason, TAO_CONVERGED_STEPTOL);
  TaoDestroy(&tao);
}

TEST(LimitingAccuracy, StagnationFarAboveTheToleranceIsAFailure) {
  // f = 1e6 + a quadratic, from a radius of 1e16 (the regime the paper's (7.1) takes for
  // Newton's): with 50 times the true Hessian every step is a fiftieth of Newton's and accepted
  // (ρ = 1.98), so the radius stays above 1e15 while ‖g‖ falls by only 2 % per iteration (an
  // rmtr iteration on one level is two such steps: 100 times), too slowly to count as progress
  // (10 % within 3 iterations), and a step lowers f by less than 1e-12 |f| = 1e-6 once
  // ‖g‖ ≲ 1e-2, far above the tolerance 1e-10.
  // Stagnation there is no convergence: DIVERGED_STAGNATION, with ‖g‖ as it was. (With twice
  // the Hessian, ‖g‖ halves per step: that is progress below the resolution of f, and the solve
  // goes on to converge.)
  for (const char* type : {"tr", "rmtr"}) {
    const std::string radius = std::string("-tao_") + type + "_delta0";
    PetscOptionsSetValue(nullptr, radius.c_str(), "1e16");
    NoisyQuadratic q;
    q.f_offset = 1e6;
    q.f_noise = 1e-10;  // the rounding of f near 1e6
    q.hessian_scale = std::string(type) == "tr" ? 50.0 : 100.0;
    const Outcome o = solve(q, type, 1e-10);
    PetscOptionsClearValue(nullptr, radius.c_str());
    EXPECT_EQ(o.reason, "DIVERGED_STAGNATION") << type;
    EXPECT_FALSE(o.converged) << type;
    EXPECT_GT(o.gnorm, 1e-8) << type;
  }
}

TEST(LimitingAccuracy, SlowSteadyProgressBelowTheNoiseIsNoFloor) {
  // StoppingRule::at_floor, fed one iteration at a time with energy noise 1e-12 and ‖g‖ within
  // the limiting factor of the tolerance 1e-7. At the floor the decreases of f scatter within
  // the noise and the gradient does not fall: the solve ends after floor_iterations (20). A slow
  // solve (‖g‖ falling by 0.3 % per iteration, too little to halve within the window; the
  // re-entrant corner's V-cycles were stopped so 2e-4 above the minimum) lowers f by less than
  // the noise per iteration but steadily: it must go on.
  Tao tao;
  TaoCreate(PETSC_COMM_SELF, &tao);
  TaoSetTolerances(tao, 1e-7, 0.0, 0.0);
  const double f_error = 1e-12;
  StoppingRule floor;
  int ended = 0;
  for (int i = 1; i <= 100 && !ended; ++i)
    if (floor.at_floor(tao, (i % 2 ? 4.0 : -4.0) * f_error, f_error, 5e-6, 1.0)) ended = i;
  EXPECT_EQ(ended, 20);
  StoppingRule slow;
  double gnorm = 6e-6;
  for (int i = 1; i <= 200; ++i, gnorm *= 0.997)
    EXPECT_FALSE(slow.at_floor(tao, 4.0 * f_error, f_error, gnorm, 1.0)) << "iteration " << i;
  TaoDestroy(&tao);
}

// The serial iterate, step and (unused) Hessian of a LocalTrustRegion on a NoisyQuadratic, and
// Σ d_i, the quadratic's curvature sum.
struct SeqWorkspace {
  Vec x = nullptr, s = nullptr;
  Mat H = nullptr;
  double sum_d = 0.0;
  SeqWorkspace() {
    VecCreateSeq(PETSC_COMM_SELF, NoisyQuadratic::n, &x);
    VecDuplicate(x, &s);
    MatCreateSeqAIJ(PETSC_COMM_SELF, NoisyQuadratic::n, NoisyQuadratic::n, 1, nullptr, &H);
    for (PetscInt i = 0; i < NoisyQuadratic::n; ++i) sum_d += NoisyQuadratic::d(i);
  }
  ~SeqWorkspace() {
    MatDestroy(&H);
    VecDestroy(&s);
    VecDestroy(&x);
  }
  SeqWorkspace(const SeqWorkspace&) = delete;
  SeqWorkspace& operator=(const SeqWorkspace&) = delete;
};

TEST(LimitingAccuracy, TheTrialReductionComesFromTheGradientsBelowTheNoiseOfTheEnergy) {
  // LocalTrustRegion::trial_reduction, which Local_TR and RMTR's coarse corrections both use:
  // from x = 0 along s = t (1, …, 1), the exact reduction of the quadratic is
  // t Σ 1 − ½ t² Σ d_i, which the trapezoidal rule reproduces exactly. With energy noise 1e-6,
  // a predicted reduction below 1e3 × 1e-6 takes it (∇f at x + s evaluated once, and no
  // evaluation when the point is then accepted); a larger one takes f(x) − f(x + s).
  NoisyQuadratic q;
  q.f_noise = 1e-6;
  SeqWorkspace w;
  Vec x = w.x, s = w.s;
  const double sum_d = w.sum_d;
  {
    LocalTrustRegion tr(q, x, w.H, std::make_unique<DoglegQp>(PETSC_COMM_SELF, "lat_"));
    VecSet(x, 0.0);
    tr.start(x);
    for (double t : {1e-7, 1e-3}) {
      const double exact = t * NoisyQuadratic::n - 0.5 * t * t * sum_d;
      VecSet(s, t);
      PetscReal ft, actual;
      bool trapezoidal;
      const int before = q.evaluations;
      ASSERT_EQ(tr.evaluate_trial(s, false, &ft), 0);
      ASSERT_EQ(tr.trial_reduction(exact, &actual, &trapezoidal), 0);
      if (t < 1e-5) {  // exact ≈ 5e-6 < 1e-3: below the noise
        EXPECT_TRUE(trapezoidal);
        EXPECT_NEAR(actual, exact, 1e-12 * std::abs(exact));
        EXPECT_EQ(q.evaluations - before, 2);  // the value, then the value with its gradient
      } else {                                 // exact ≈ 0.05
        EXPECT_FALSE(trapezoidal);
        EXPECT_NEAR(actual, exact, 3e-6);  // two evaluations' noise
        EXPECT_EQ(q.evaluations - before, 1);
      }
    }
    // A trial point evaluated with its gradient is accepted without another evaluation.
    VecSet(s, 1e-4);
    PetscReal ft;
    ASSERT_EQ(tr.evaluate_trial(s, true, &ft), 0);
    const int before = q.evaluations;
    ASSERT_EQ(tr.accept_trial(), 0);
    EXPECT_EQ(q.evaluations, before);
    EXPECT_EQ(tr.value(), ft);
    PetscReal xmax;
    VecMax(tr.solution(), nullptr, &xmax);
    EXPECT_EQ(xmax, 1e-4);
  }
}

TEST(LimitingAccuracy, TheReductionSinceTheStartSumsTheAcceptedStepsAsTheirTrialsMeasuredThem) {
  // RMTR's coarse reduction h(x₀) − h(x*) (tao_rmtr.cpp): below the noise of f the difference
  // of the two values is round-off of either sign, and a sound coarse correction would be
  // rejected on it. LocalTrustRegion::reduction() sums the accepted steps' measured reductions:
  // three steps of s = 1e-8 (1, …, 1) from x = 0, each reducing f by ≈ 5e-7 under energy noise
  // 1e-6, add up to the exact 3 t n − ½ (3t)² Σ d_i (the trapezoidal rule is exact on a
  // quadratic); a start resets the sum.
  NoisyQuadratic q;
  q.f_noise = 1e-6;
  SeqWorkspace w;
  Vec x = w.x, s = w.s;
  const double sum_d = w.sum_d;
  {
    LocalTrustRegion tr(q, x, w.H, std::make_unique<DoglegQp>(PETSC_COMM_SELF, "lar_"));
    VecSet(x, 0.0);
    ASSERT_EQ(tr.start(x), 0);
    EXPECT_EQ(tr.reduction(), 0.0);
    const double t = 1e-8;
    VecSet(s, t);
    for (int k = 0; k < 3; ++k) {
      PetscReal ft, actual;
      bool trapezoidal;
      ASSERT_EQ(tr.evaluate_trial(s, false, &ft), 0);
      ASSERT_EQ(tr.trial_reduction(t * NoisyQuadratic::n, &actual, &trapezoidal), 0);
      EXPECT_TRUE(trapezoidal);
      ASSERT_EQ(tr.accept_trial(), 0);
    }
    const double exact = 3 * t * NoisyQuadratic::n - 0.5 * (3 * t) * (3 * t) * sum_d;
    EXPECT_NEAR(tr.reduction(), exact, 1e-9 * exact);
    ASSERT_EQ(tr.start(x), 0);
    EXPECT_EQ(tr.reduction(), 0.0);
  }
}
