// Extreme eigenvalues and the 2-norm condition number of a symmetric matrix (paper Fig. 9).
//
// Method: Lanczos with full reorthogonalisation, `steps` steps from a fixed start vector,
//   - on H itself for the eigenvalue of largest magnitude (converges from the outside of the
//     spectrum in a few dozen steps), and
//   - on H⁻¹, applied through a sparse direct factorisation (options prefix
//     `-mlshell_condition_`, default MUMPS Cholesky LDLᵀ so that an indefinite H works too), for
//     the eigenvalue of smallest magnitude, which is the largest of H⁻¹.
// cond₂(H) = |λ|max / |λ|min. The Ritz values are interior to the spectrum, so with too few
// steps both estimates err toward a smaller condition number; `converged` reports whether the
// last two Ritz estimates of each agree to 1e-6 relatively.
#pragma once

#include <petscmat.h>

namespace mlshell {

struct SpectrumEstimate {
  double lambda_max = 0.0;  ///< eigenvalue of largest magnitude (signed)
  double lambda_min = 0.0;  ///< eigenvalue of smallest magnitude (signed)
  double condition = 0.0;   ///< |lambda_max| / |lambda_min|
  int steps = 0;            ///< Lanczos steps taken on each operator
  bool converged = false;
};

PetscErrorCode estimate_spectrum(Mat H, int steps, SpectrumEstimate* out);

}  // namespace mlshell
