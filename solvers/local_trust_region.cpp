// Local_TR, paper Alg. 4.1 (see local_trust_region.hpp).
#include "mlshell/local_trust_region.hpp"

#include <petsc/private/taoimpl.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace mlshell {

PetscReal TrustRegionParameters::updated_radius(PetscReal rho, PetscReal delta,
                                                PetscReal used) const {
  if (!(rho > eta1)) {
    // γ₁Δ, γ₁²Δ, ... down to the first radius below the step's need: the larger ones would
    // return the same step and reject it again.
    PetscReal shrunk = gamma1 * delta;
    if (used > 0.0)
      while (shrunk >= used * delta) shrunk *= gamma1;
    return shrunk;
  }
  // Capped far beyond any meaningful step (and the 1e15 of eq. 7.1) so that it never overflows.
  if (rho > eta2) return std::min<PetscReal>(gamma2 * delta, 1e30);
  return delta;
}

PetscErrorCode TrustRegionParameters::validate(MPI_Comm comm, const char* prefix) const {
  PetscFunctionBeginUser;
  PetscCheck(eta1 > 0 && eta1 < eta2 && eta2 < 1, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "%seta1 = %g and %seta2 = %g: need 0 < eta1 < eta2 < 1", prefix, (double)eta1, prefix,
             (double)eta2);
  PetscCheck(gamma1 > 0 && gamma1 < 1 && gamma2 > 1, comm, PETSC_ERR_ARG_OUTOFRANGE,
             "%sgamma1 = %g and %sgamma2 = %g: need 0 < gamma1 < 1 < gamma2", prefix,
             (double)gamma1, prefix, (double)gamma2);
  PetscFunctionReturn(0);
}

bool StoppingRule::stagnated(PetscReal delta, PetscReal df, PetscReal f, PetscReal dx,
                             PetscReal xnorm, PetscReal gnorm) {
  if (gnorm < 0.9 * best_gnorm_) {
    best_gnorm_ = gnorm;
    since_best_ = 0;
  } else {
    ++since_best_;
  }
  if (!(delta > 1e15) || since_best_ < stagnation_window) return false;
  return std::abs(df) <= stagnation * std::abs(f) || dx <= stagnation * xnorm;
}

void StoppingRule::end_stagnated(Tao tao, PetscReal gnorm, PetscReal g0) const {
  tao->reason =
      gnorm <= limiting_factor * tolerance(tao, g0) ? TAO_CONVERGED_STEPTOL : TAO_DIVERGED_USER;
}

bool StoppingRule::collapsed(PetscReal delta, PetscReal xnorm) const {
  return delta < min_radius * std::max<PetscReal>(1.0, xnorm);
}

PetscReal StoppingRule::tolerance(Tao tao, PetscReal g0) const {
  PetscReal gatol, grtol, gttol;
  TaoGetTolerances(tao, &gatol, &grtol, &gttol);
  return std::max(gatol, gttol * g0);
}

void StoppingRule::end_collapsed(Tao tao, PetscReal gnorm, PetscReal g0, bool* limiting) const {
  *limiting = gnorm <= limiting_factor * tolerance(tao, g0);
  tao->reason = *limiting ? TAO_CONVERGED_USER : TAO_DIVERGED_TR_REDUCTION;
}

bool StoppingRule::at_floor(Tao tao, PetscReal df, PetscReal f_error, PetscReal gnorm,
                            PetscReal g0) {
  // Each decrease within the noise, and their sum over the window too: a solve that converges
  // slowly lowers f by less than its noise per iteration but steadily, and is not at the floor.
  const PetscReal noise = 10.0 * f_error;
  const bool meandering = std::abs(df) <= noise && std::abs(floor_decrease_ + df) <= noise &&
                          gnorm <= limiting_factor * tolerance(tao, g0);
  if (!meandering || (floor_count_ > 0 && gnorm < 0.5 * floor_gnorm_)) {
    reset_floor();
    if (!meandering) return false;
  }
  if (floor_count_ == 0) floor_gnorm_ = gnorm;
  floor_decrease_ += df;
  return ++floor_count_ >= floor_iterations;
}

void StoppingRule::end_at_floor(Tao tao, bool* limiting) const {
  *limiting = true;
  tao->reason = TAO_CONVERGED_USER;
}

PetscErrorCode StoppingRule::options(PetscOptionItems* PetscOptionsObject,
                                     const std::string& prefix) {
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsReal((prefix + "stagnation").c_str(),
                             "eq. (7.1): relative floor on |df| and |dx| once the radius is > 1e15",
                             "", stagnation, &stagnation, nullptr));
  PetscCall(PetscOptionsReal((prefix + "min_radius").c_str(),
                             "relative radius at which the solve stops", "", min_radius,
                             &min_radius, nullptr));
  PetscCall(PetscOptionsReal((prefix + "limiting_factor").c_str(),
                             "a radius collapse with |g| below this times the gradient tolerance "
                             "is convergence at the limiting accuracy",
                             "", limiting_factor, &limiting_factor, nullptr));
  PetscCall(PetscOptionsInt((prefix + "floor_iterations").c_str(),
                            "iterations within the noise of f, near the tolerance, that end the "
                            "solve at the limiting accuracy",
                            "", floor_iterations, &floor_iterations, nullptr));
  PetscCall(PetscOptionsInt((prefix + "stagnation_window").c_str(),
                            "the stagnation test of (7.1) ends a solve only if no iteration among "
                            "this many lowered |g| below 0.9 times its lowest value before",
                            "", stagnation_window, &stagnation_window, nullptr));
  PetscCheck(floor_iterations >= 1 && stagnation_window >= 1, PETSC_COMM_WORLD,
             PETSC_ERR_ARG_OUTOFRANGE,
             "%sfloor_iterations and %sstagnation_window must be >= 1, got %" PetscInt_FMT
             " and %" PetscInt_FMT,
             prefix.c_str(), prefix.c_str(), floor_iterations, stagnation_window);
  PetscCheck(stagnation >= 0 && min_radius > 0 && limiting_factor >= 1, PETSC_COMM_WORLD,
             PETSC_ERR_ARG_OUTOFRANGE,
             "%sstagnation must be >= 0, %smin_radius > 0 and %slimiting_factor >= 1; got %g, %g "
             "and %g",
             prefix.c_str(), prefix.c_str(), prefix.c_str(), (double)stagnation, (double)min_radius,
             (double)limiting_factor);
  PetscFunctionReturn(0);
}

PetscErrorCode trust_region_parameter_options(PetscOptionItems* PetscOptionsObject,
                                              const std::string& prefix, TrustRegionParameters* p) {
  PetscFunctionBeginUser;
  PetscCall(PetscOptionsReal((prefix + "eta1").c_str(), "acceptance threshold on rho", "", p->eta1,
                             &p->eta1, nullptr));
  PetscCall(PetscOptionsReal((prefix + "eta2").c_str(), "expansion threshold on rho", "", p->eta2,
                             &p->eta2, nullptr));
  PetscCall(PetscOptionsReal((prefix + "gamma1").c_str(), "radius shrink factor", "", p->gamma1,
                             &p->gamma1, nullptr));
  PetscCall(PetscOptionsReal((prefix + "gamma2").c_str(), "radius expansion factor", "", p->gamma2,
                             &p->gamma2, nullptr));
  PetscFunctionReturn(0);
}

LocalTrustRegion::LocalTrustRegion(Objective& f, Vec like, Mat H, std::unique_ptr<TrustRegionQp> qp,
                                   LevelNorm norm)
    : f_(f), H_(H), qp_(std::move(qp)), norm_(std::move(norm)) {
  MPI_Comm comm = PetscObjectComm(reinterpret_cast<PetscObject>(like));
  PetscCallAbort(comm, VecDuplicate(like, &x_));
  PetscCallAbort(comm, VecDuplicate(like, &g_));
  PetscCallAbort(comm, VecDuplicate(like, &s_));
  PetscCallAbort(comm, VecDuplicate(like, &trial_));
  PetscCallAbort(comm, VecDuplicate(like, &g_trial_));
}

LocalTrustRegion::~LocalTrustRegion() {
  VecDestroy(&x_);
  VecDestroy(&g_);
  VecDestroy(&s_);
  VecDestroy(&trial_);
  VecDestroy(&g_trial_);
}

PetscErrorCode LocalTrustRegion::level_norm(Vec v, PetscReal* norm) const {
  PetscFunctionBeginUser;
  if (norm_)
    PetscCall(norm_(v, norm));
  else
    PetscCall(VecNorm(v, NORM_2, norm));
  PetscFunctionReturn(0);
}

PetscErrorCode LocalTrustRegion::assemble_derivatives(bool force) {
  PetscFunctionBeginUser;
  PetscCall(VecNorm(g_, NORM_2, &gnorm_));
  finite_ = std::isfinite(fx_) && std::isfinite(gnorm_);
  if (!finite_) PetscFunctionReturn(0);
  if (force || kept_ >= hessian_lag_)
    hessian_due_ = true;
  else
    ++kept_;
  PetscFunctionReturn(0);
}

PetscErrorCode LocalTrustRegion::ensure_hessian() {
  PetscFunctionBeginUser;
  if (!hessian_due_) PetscFunctionReturn(0);
  PetscCall(f_.hessian(x_, H_));
  ++counters_.hessians;
  PetscCall(qp_->set_operator(H_));
  kept_ = 0;
  hessian_due_ = false;
  hessian_since_start_ = true;
  PetscFunctionReturn(0);
}

PetscErrorCode LocalTrustRegion::model_hessian(Mat* H) {
  PetscFunctionBeginUser;
  if (!hessian_since_start_) PetscCall(ensure_hessian());
  *H = H_;
  PetscFunctionReturn(0);
}

PetscErrorCode LocalTrustRegion::start(Vec x, const PetscReal* f, Vec g) {
  PetscFunctionBeginUser;
  PetscCall(VecCopy(x, x_));
  reduction_ = 0.0;
  hessian_since_start_ = false;
  if (f && g) {
    fx_ = *f;
    PetscCall(VecCopy(g, g_));
  } else {
    PetscCall(f_.objective(x_, &fx_, g_));
  }
  PetscCall(assemble_derivatives(true));
  PetscFunctionReturn(0);
}

PetscErrorCode LocalTrustRegion::evaluate_trial(Vec s, bool with_gradient, PetscReal* ft) {
  PetscFunctionBeginUser;
  PetscCall(VecWAXPY(trial_, 1.0, s, x_));
  trial_step_ = s;
  PetscCall(f_.objective(trial_, &f_trial_, with_gradient ? g_trial_ : nullptr));
  trial_gradient_ = with_gradient;
  trial_measured_ = fx_ - f_trial_;
  *ft = f_trial_;
  PetscFunctionReturn(0);
}

PetscErrorCode LocalTrustRegion::trial_reduction(PetscReal predicted, PetscReal* actual,
                                                 bool* trapezoidal) {
  PetscFunctionBeginUser;
  const PetscReal direct = fx_ - f_trial_, f_error = f_.evaluation_error();
  *actual = direct;
  *trapezoidal = false;
  // Below the noise of f, trust the gradients, unless f rose by more than its own noise.
  if (predicted < 1e3 * f_error && direct > -10.0 * f_error) {
    if (!trial_gradient_) {
      PetscCall(f_.objective(trial_, &f_trial_, g_trial_));
      trial_gradient_ = true;
    }
    PetscReal gs, gts;
    PetscCall(VecDot(g_, trial_step_, &gs));
    PetscCall(VecDot(g_trial_, trial_step_, &gts));
    *actual = -0.5 * (gs + gts);
    *trapezoidal = true;
  }
  trial_measured_ = *actual;
  PetscFunctionReturn(0);
}

PetscErrorCode LocalTrustRegion::accept_trial() {
  PetscFunctionBeginUser;
  PetscCall(VecCopy(trial_, x_));
  reduction_ += trial_measured_;
  if (trial_gradient_) {  // f and ∇f at x + s are known already
    PetscCall(VecCopy(g_trial_, g_));
    fx_ = f_trial_;
  } else {
    PetscCall(f_.objective(x_, &fx_, g_));
  }
  PetscFunctionReturn(accepted());
}

PetscErrorCode LocalTrustRegion::accepted() {
  PetscFunctionBeginUser;
  ++counters_.accepted;
  const long revision = f_.revision();
  PetscCall(f_.accepted(x_));
  if (f_.revision() != revision) PetscCall(f_.objective(x_, &fx_, g_));  // contact's κ
  PetscCall(assemble_derivatives(false));
  // The trial value was finite, so the same point evaluated with its gradient must be too.
  PetscCheck(finite_, PetscObjectComm((PetscObject)x_), PETSC_ERR_FP,
             "trust region: the gradient is not finite at an accepted point (f = %g, |g| = %g)",
             (double)fx_, (double)gnorm_);
  PetscFunctionReturn(0);
}

PetscErrorCode LocalTrustRegion::iterate(const TrustRegionParameters& p, PetscReal* delta,
                                         TrustRegionIteration* it) {
  PetscFunctionBeginUser;
  *it = TrustRegionIteration{};
  PetscCheck(finite_, PetscObjectComm((PetscObject)x_), PETSC_ERR_ARG_WRONGSTATE,
             "trust region: iterate() at a point where f or its gradient is not finite");
  // The QP works in ℓ₂: translate the level-norm radius with the ratio of the two norms along
  // the steepest-descent direction, where the step starts.
  PetscReal qp_radius = *delta;
  if (norm_ && gnorm_ > 0) {
    PetscReal glevel;
    PetscCall(level_norm(g_, &glevel));
    if (glevel > 0) qp_radius = *delta * gnorm_ / glevel;
  }
  PetscCall(ensure_hessian());
  PetscCall(qp_->solve(g_, qp_radius, s_, it->qp));
  ++counters_.qp_solves;
  counters_.factorisations += it->qp.factorisations;
  PetscReal model_decrease = it->qp.model_decrease;
  it->step_norm = it->qp.step_norm;
  // The share of the radius the step needs: a larger radius would give the same step.
  it->radius_used =
      qp_radius > 0 ? std::min<PetscReal>(1.0, it->qp.radius_needed / qp_radius) : 1.0;
  if (norm_) {
    PetscCall(level_norm(s_, &it->step_norm));
    it->radius_used = std::max(it->radius_used, std::min<PetscReal>(1.0, it->step_norm / *delta));
    if (it->step_norm > *delta) {  // shorten along s: m(ts) < 0 for t ∈ (0, 1] if m(s) < 0
      PetscCall(VecScale(s_, *delta / it->step_norm));
      it->step_norm = *delta;
      PetscReal m;
      PetscCall(quadratic_model(H_, g_, s_, &m));
      model_decrease = -m;
    }
  }
  // An objective with inadmissible regions (contact) caps the step: x + s stays admissible.
  PetscReal alpha = 1.0;
  PetscCall(f_.max_step(x_, s_, &alpha));
  if (alpha < 1.0) {
    PetscCall(VecScale(s_, alpha));
    it->step_norm *= alpha;
    PetscReal m;
    PetscCall(quadratic_model(H_, g_, s_, &m));
    model_decrease = -m;
  }
  PetscReal ft = PETSC_INFINITY;
  it->rho = -PETSC_INFINITY;
  if (model_decrease > 0.0 && std::isfinite(model_decrease)) {
    // ∇f with f when the last step was accepted: the likely next iterate's gradient in the same
    // pass over the elements, instead of a second pass after acceptance.
    PetscCall(evaluate_trial(s_, last_accepted_, &ft));
    ++counters_.objectives;
    if (std::isfinite(ft)) {
      PetscReal actual;
      PetscCall(trial_reduction(model_decrease, &actual, &it->trapezoidal));
      it->rho = actual / model_decrease;
    }
  }
  if (it->rho > p.eta1) {
    const PetscReal f_old = fx_;
    PetscCall(accept_trial());
    it->accepted = true;
    it->decrease = f_old - fx_;
  }
  last_accepted_ = it->accepted;
  *delta = p.updated_radius(it->rho, *delta, it->radius_used);
  PetscFunctionReturn(0);
}

}  // namespace mlshell
