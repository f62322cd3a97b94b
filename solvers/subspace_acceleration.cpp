// Subspace acceleration of V-cycles (see subspace_acceleration.hpp).
#include "mlshell/subspace_acceleration.hpp"

#include <petscmat.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace mlshell {

namespace {
/// A V-cycle whose correction is at most this share of the radius was not limited by it.
constexpr PetscReal kLocalShare = 0.5;
/// Bounds on the reach, the subspace step's radius as a multiple of the correction's length.
constexpr PetscReal kMinReach = 0.25, kMaxReach = 1e3;
}  // namespace

SmallTrustRegionStep solve_small_trust_region(const Eigen::MatrixXd& A, const Eigen::VectorXd& b,
                                              double radius) {
  const Eigen::Index r = b.size();
  SmallTrustRegionStep out;
  out.a = Eigen::VectorXd::Zero(r);
  if (r == 0 || !(radius > 0.0)) return out;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (A + A.transpose()));
  const Eigen::VectorXd& lambda = eig.eigenvalues();  // ascending
  const Eigen::MatrixXd& V = eig.eigenvectors();
  const Eigen::VectorXd c = V.transpose() * b;
  const double scale = std::max(lambda.cwiseAbs().maxCoeff(), 1e-300);
  // a(μ) = −V (Λ + μ)⁻¹ c, its coordinates in the eigenbasis; zero where λ + μ vanishes.
  auto coordinates = [&](double mu) {
    Eigen::VectorXd y(r);
    for (Eigen::Index i = 0; i < r; ++i) {
      const double d = lambda(i) + mu;
      y(i) = d > 1e-14 * scale ? -c(i) / d : 0.0;
    }
    return y;
  };
  const double lo = std::max(0.0, -lambda(0));
  Eigen::VectorXd y;
  if (lambda(0) > 1e-14 * scale && (y = coordinates(0.0)).norm() <= radius) {
    out.a = V * y;  // the interior Newton point
  } else {
    y = coordinates(lo);
    if (y.norm() <= radius) {
      // The hard case: c has (almost) no component along the lowest eigenvectors, and (Λ + μ)⁻¹c
      // stays inside at μ = −λ_min; the boundary is reached along the lowest eigenvector.
      const double tau = std::sqrt(std::max(0.0, radius * radius - y.squaredNorm()));
      y(0) += tau;
    } else {
      // ‖a(μ)‖ decreases from > radius at lo to ≤ radius at hi = lo + ‖b‖/radius.
      double a = lo, h = lo + b.norm() / radius;
      for (int k = 0; k < 200 && h - a > 1e-15 * std::max(h, 1e-300); ++k) {
        const double mid = 0.5 * (a + h);
        (coordinates(mid).norm() > radius ? a : h) = mid;
      }
      y = coordinates(h);
    }
    out.a = V * y;
    out.boundary = true;
  }
  out.model = b.dot(out.a) + 0.5 * out.a.dot(A * out.a);
  if (!(out.model < 0.0)) {  // nothing to gain (b = 0, or round-off): no step
    out.a.setZero();
    out.model = 0.0;
    out.boundary = false;
  }
  return out;
}

SubspaceAcceleration::SubspaceAcceleration(int depth) : depth_(std::max(1, depth)) {}

SubspaceAcceleration::~SubspaceAcceleration() {
  for (Vec& v : history_) VecDestroy(&v);
  for (Vec& v : products_) VecDestroy(&v);
  VecDestroy(&correction_);
  VecDestroy(&step_);
}

PetscErrorCode SubspaceAcceleration::allocate(Vec like) {
  PetscFunctionBeginUser;
  if (correction_) PetscFunctionReturn(0);
  PetscCall(VecDuplicate(like, &correction_));
  PetscCall(VecDuplicate(like, &step_));
  history_.assign(depth_ - 1, nullptr);
  for (Vec& v : history_) PetscCall(VecDuplicate(like, &v));
  products_.assign(depth_, nullptr);
  for (Vec& v : products_) PetscCall(VecDuplicate(like, &v));
  PetscFunctionReturn(0);
}

PetscErrorCode SubspaceAcceleration::step(LocalTrustRegion& tr, Vec start,
                                          const TrustRegionParameters& p, PetscReal delta,
                                          SubspaceStep* out) {
  PetscFunctionBeginUser;
  *out = SubspaceStep{};
  PetscCall(allocate(start));
  PetscCall(VecWAXPY(correction_, -1.0, start, tr.solution()));  // s = z − y
  PetscReal s_norm;
  PetscCall(VecNorm(correction_, NORM_2, &s_norm));
  PetscReal s_level = 0.0;
  if (s_norm > 0.0) PetscCall(tr.level_norm(correction_, &s_level));
  // While the radius limits the V-cycle's steps (globalisation), the quadratic model is poor
  // beyond them: no step, and only this cycle's change is kept for the next (the earlier ones
  // are forgotten).
  const bool local = s_norm > 0.0 && s_level <= kLocalShare * delta;
  if (!local) stored_ = 0;
  if (local && tr.finite()) {
    directions_.assign(1, correction_);
    for (int j = 0; j < stored_; ++j) directions_.push_back(history_[j]);
    const PetscInt m = static_cast<PetscInt>(directions_.size());
    Mat H;
    PetscCall(tr.model_hessian(&H));
    for (PetscInt i = 0; i < m; ++i) PetscCall(MatMult(H, directions_[i], products_[i]));
    // The small problem in the coordinates α of d = Dα: G = DᵀD, A = DᵀHD, b = Dᵀ∇f(z).
    Eigen::MatrixXd G(m, m), A(m, m);
    Eigen::VectorXd b(m);
    std::vector<PetscScalar> dots(m);
    for (PetscInt i = 0; i < m; ++i) {
      PetscCall(VecMDot(directions_[i], m, directions_.data(), dots.data()));
      for (PetscInt j = 0; j < m; ++j) G(i, j) = PetscRealPart(dots[j]);
      PetscCall(VecMDot(products_[i], m, directions_.data(), dots.data()));
      for (PetscInt j = 0; j < m; ++j) A(i, j) = PetscRealPart(dots[j]);
    }
    PetscCall(VecMDot(tr.gradient(), m, directions_.data(), dots.data()));
    for (PetscInt i = 0; i < m; ++i) b(i) = PetscRealPart(dots[i]);
    // ℓ₂-orthonormal coordinates β (α = Tβ, ‖Dα‖₂ = ‖β‖) over the directions D spans: drop
    // the Gram matrix's eigenvalues below 1e-10 of its largest (nearly parallel changes).
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> gram(0.5 * (G + G.transpose()));
    const double top = gram.eigenvalues()(m - 1);
    std::vector<Eigen::Index> kept;
    for (Eigen::Index i = 0; i < m; ++i)
      if (gram.eigenvalues()(i) > 1e-10 * top) kept.push_back(i);
    Eigen::MatrixXd T(m, static_cast<Eigen::Index>(kept.size()));
    for (size_t k = 0; k < kept.size(); ++k)
      T.col(k) = gram.eigenvectors().col(kept[k]) / std::sqrt(gram.eigenvalues()(kept[k]));
    // The ℓ₂ radius: Δ translated from the level norm along the correction, capped at reach_
    // times the correction's length (the step's own trust region).
    const PetscReal radius = std::min(delta * s_norm / s_level, reach_ * s_norm);
    const SmallTrustRegionStep small =
        solve_small_trust_region(T.transpose() * A * T, T.transpose() * b, radius);
    Eigen::VectorXd alpha = T * small.a;
    double model = small.model;
    PetscReal d_level = 0.0, d_norm = 0.0;
    if (model < 0.0 && alpha.allFinite()) {
      PetscCall(VecSet(step_, 0.0));
      std::vector<PetscScalar> coefficients(alpha.data(), alpha.data() + m);
      PetscCall(VecMAXPY(step_, m, coefficients.data(), directions_.data()));
      PetscCall(tr.level_norm(step_, &d_level));
      // Shorten to the level-norm radius, and to an admissible step (contact); m(tα) < 0 for
      // t ∈ (0, 1] is rechecked below.
      PetscReal t = d_level > delta ? delta / d_level : 1.0, admissible = 1.0;
      PetscCall(VecScale(step_, t));
      PetscCall(tr.objective().max_step(tr.solution(), step_, &admissible));
      if (admissible < 1.0) PetscCall(VecScale(step_, admissible));
      t *= admissible;
      PetscCall(VecNorm(step_, NORM_2, &d_norm));
      if (t < 1.0) {
        alpha *= t;
        model = b.dot(alpha) + 0.5 * alpha.dot(A * alpha);
      }
    }
    if (model < 0.0 && std::isfinite(model)) {
      const PetscReal predicted = -model;
      PetscReal ft;
      out->tried = true;
      out->relaxation = alpha(0);
      PetscCall(tr.evaluate_trial(step_, true, &ft));
      out->rho = -PETSC_INFINITY;
      if (std::isfinite(ft)) {
        PetscReal actual;
        bool trapezoidal;
        PetscCall(tr.trial_reduction(predicted, &actual, &trapezoidal));
        out->rho = actual / predicted;
      }
      if (out->rho > p.eta1) {
        PetscCall(tr.accept_trial());
        out->accepted = true;
      }
      // Alg. 4.1's radius rule on the reach (see the header).
      if (!(out->rho > p.eta1))
        reach_ = std::max<PetscReal>(kMinReach, p.gamma1 * std::min(reach_, d_norm / s_norm));
      else if (out->rho > p.eta2 && small.boundary)
        reach_ = std::min<PetscReal>(kMaxReach, p.gamma2 * reach_);
    }
  }
  // The change of this cycle, y_{k+1} − y_k, becomes the newest history entry.
  if (depth_ > 1) {
    PetscCall(VecWAXPY(step_, -1.0, start, tr.solution()));
    PetscReal norm;
    PetscCall(VecNorm(step_, NORM_2, &norm));
    if (norm > 0.0) {
      std::rotate(history_.begin(), history_.end() - 1, history_.end());
      PetscCall(VecCopy(step_, history_[0]));
      stored_ = std::min(stored_ + 1, depth_ - 1);
    }
  }
  PetscFunctionReturn(0);
}

}  // namespace mlshell
