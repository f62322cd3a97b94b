// Lanczos estimates of the extreme eigenvalues of a symmetric matrix (see hessian_spectrum.hpp).
#include "mlshell/hessian_spectrum.hpp"

#include <petscksp.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

namespace mlshell {

namespace {

using Operator = std::function<PetscErrorCode(Vec, Vec)>;

/// Ritz value of largest magnitude of `op` after each Lanczos step (full reorthogonalisation).
PetscErrorCode lanczos_largest(const Operator& op, Vec start, int steps,
                               std::vector<double>* history) {
  PetscFunctionBeginUser;
  std::vector<Vec> q;
  std::vector<double> alpha, beta;
  Vec w;
  PetscCall(VecDuplicate(start, &w));
  Vec q0;
  PetscCall(VecDuplicate(start, &q0));
  PetscCall(VecCopy(start, q0));
  PetscReal norm;
  PetscCall(VecNormalize(q0, &norm));
  q.push_back(q0);
  history->clear();
  for (int k = 0; k < steps; ++k) {
    PetscCall(op(q[k], w));
    PetscScalar a;
    PetscCall(VecDot(w, q[k], &a));
    alpha.push_back(PetscRealPart(a));
    // Full reorthogonalisation against every earlier vector, twice (classical Gram–Schmidt).
    std::vector<PetscScalar> dots(q.size());
    for (int pass = 0; pass < 2; ++pass) {
      PetscCall(VecMDot(w, static_cast<PetscInt>(q.size()), q.data(), dots.data()));
      for (auto& d : dots) d = -d;
      PetscCall(VecMAXPY(w, static_cast<PetscInt>(q.size()), dots.data(), q.data()));
    }
    const int m = k + 1;
    Eigen::MatrixXd T = Eigen::MatrixXd::Zero(m, m);
    for (int i = 0; i < m; ++i) T(i, i) = alpha[i];
    for (int i = 0; i + 1 < m; ++i) T(i, i + 1) = T(i + 1, i) = beta[i];
    const Eigen::VectorXd theta = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(T).eigenvalues();
    history->push_back(std::abs(theta(0)) > std::abs(theta(m - 1)) ? theta(0) : theta(m - 1));
    PetscReal b;
    PetscCall(VecNorm(w, NORM_2, &b));
    // An invariant subspace: the Ritz values are exact.
    if (!(b > 1e-14 * std::abs(history->back())) || k + 1 == steps) break;
    beta.push_back(b);
    Vec next;
    PetscCall(VecDuplicate(start, &next));
    PetscCall(VecAXPBY(next, 1.0 / b, 0.0, w));
    q.push_back(next);
  }
  for (Vec& v : q) PetscCall(VecDestroy(&v));
  PetscCall(VecDestroy(&w));
  PetscFunctionReturn(0);
}

bool settled(const std::vector<double>& h) {
  const size_t n = h.size();
  return n >= 2 && std::abs(h[n - 1] - h[n - 2]) <= 1e-6 * std::abs(h[n - 1]);
}

}  // namespace

PetscErrorCode estimate_spectrum(Mat H, int steps, SpectrumEstimate* out) {
  MPI_Comm comm;
  PetscFunctionBeginUser;
  PetscCall(PetscObjectGetComm(reinterpret_cast<PetscObject>(H), &comm));
  Vec start;
  PetscCall(MatCreateVecs(H, &start, nullptr));
  // A fixed, smooth-plus-rough start vector: 1 + sin(global index) has components along
  // both ends of the spectrum.
  PetscInt lo, hi;
  PetscCall(VecGetOwnershipRange(start, &lo, &hi));
  PetscScalar* s;
  PetscCall(VecGetArray(start, &s));
  for (PetscInt i = lo; i < hi; ++i) s[i - lo] = 1.0 + std::sin(static_cast<double>(i));
  PetscCall(VecRestoreArray(start, &s));

  std::vector<double> high, low;
  PetscCall(lanczos_largest([&](Vec x, Vec y) { return MatMult(H, x, y); }, start, steps, &high));

  KSP ksp;
  PetscCall(KSPCreate(comm, &ksp));
  PetscCall(KSPSetOptionsPrefix(ksp, "mlshell_condition_"));
  PetscCall(KSPSetOperators(ksp, H, H));
  PetscCall(KSPSetType(ksp, KSPPREONLY));
  PC pc;
  PetscCall(KSPGetPC(ksp, &pc));
  PetscCall(PCSetType(pc, PCCHOLESKY));
  PetscCall(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS));
  PetscCall(KSPSetFromOptions(ksp));
  PetscCall(KSPSetUp(ksp));
  PetscCall(lanczos_largest([&](Vec x, Vec y) { return KSPSolve(ksp, x, y); }, start, steps, &low));
  PetscCall(KSPDestroy(&ksp));
  PetscCall(VecDestroy(&start));

  out->lambda_max = high.back();
  out->lambda_min = 1.0 / low.back();
  out->condition = std::abs(out->lambda_max / out->lambda_min);
  out->steps = static_cast<int>(std::max(high.size(), low.size()));
  // A Lanczos run that stopped early found an invariant subspace: its Ritz values are exact.
  const auto done = [&](const std::vector<double>& h) {
    return settled(h) || static_cast<int>(h.size()) < steps;
  };
  out->converged = done(high) && done(low);
  PetscFunctionReturn(0);
}

}  // namespace mlshell
