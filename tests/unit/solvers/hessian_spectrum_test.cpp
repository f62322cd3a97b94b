// The Lanczos estimate of extreme eigenvalues and cond₂ (hessian_spectrum.hpp) on matrices with
// known spectra.
#include "mlshell/hessian_spectrum.hpp"

#include <gtest/gtest.h>
#include <petscmat.h>

#include <cmath>
#include <vector>

namespace mlshell {
namespace {

/// An n×n AIJ matrix with diagonal `d` and `off` on the first off-diagonals.
Mat tridiagonal(const std::vector<double>& d, double off) {
  const PetscInt n = static_cast<PetscInt>(d.size());
  Mat A;
  MatCreateAIJ(PETSC_COMM_SELF, n, n, n, n, 3, nullptr, 0, nullptr, &A);
  for (PetscInt i = 0; i < n; ++i) {
    MatSetValue(A, i, i, d[i], INSERT_VALUES);
    if (off != 0.0 && i + 1 < n) {
      MatSetValue(A, i, i + 1, off, INSERT_VALUES);
      MatSetValue(A, i + 1, i, off, INSERT_VALUES);
    }
  }
  MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY);
  MatSetOption(A, MAT_SYMMETRIC, PETSC_TRUE);
  return A;
}

TEST(HessianSpectrum, DiagonalSpectrumIsExactWhenStepsCoverTheDimension) {
  std::vector<double> d;
  for (int i = 0; i < 20; ++i) d.push_back(std::pow(10.0, 0.5 * i));  // 1 ... 10^9.5
  Mat A = tridiagonal(d, 0.0);
  SpectrumEstimate e;
  ASSERT_EQ(estimate_spectrum(A, 40, &e), 0);
  EXPECT_NEAR(e.lambda_max / d.back(), 1.0, 1e-10);
  EXPECT_NEAR(e.lambda_min / d.front(), 1.0, 1e-10);
  EXPECT_NEAR(e.condition / std::pow(10.0, 9.5), 1.0, 1e-10);
  EXPECT_TRUE(e.converged);
  MatDestroy(&A);
}

TEST(HessianSpectrum, LaplacianConditionNumberFromFewSteps) {
  // 1-D Laplacian tridiag(-1, 2, -1), n = 400: λ_k = 2 − 2 cos(kπ/(n+1)).
  const int n = 400;
  Mat A = tridiagonal(std::vector<double>(n, 2.0), -1.0);
  const double lmin = 2.0 - 2.0 * std::cos(M_PI / (n + 1));
  const double lmax = 2.0 - 2.0 * std::cos(n * M_PI / (n + 1));
  SpectrumEstimate e;
  ASSERT_EQ(estimate_spectrum(A, 80, &e), 0);
  // H⁻¹'s largest eigenvalue is well separated: Lanczos finds it to round-off.
  EXPECT_NEAR(e.lambda_min / lmin, 1.0, 1e-8);
  // H's largest sits in a cluster: a few digits after 80 steps, never above the truth.
  EXPECT_NEAR(e.lambda_max / lmax, 1.0, 1e-3);
  EXPECT_LE(e.lambda_max, lmax * (1 + 1e-12));
  EXPECT_NEAR(e.condition / (lmax / lmin), 1.0, 1e-3);
  MatDestroy(&A);
}

TEST(HessianSpectrum, IndefiniteMatrixGivesSignedExtremesAndMagnitudeCondition) {
  Mat A = tridiagonal({-50.0, 0.5, 2.0, 3.0, -1.0, 7.0}, 0.0);
  SpectrumEstimate e;
  ASSERT_EQ(estimate_spectrum(A, 10, &e), 0);
  EXPECT_NEAR(e.lambda_max, -50.0, 1e-9);
  EXPECT_NEAR(e.lambda_min, 0.5, 1e-12);
  EXPECT_NEAR(e.condition, 100.0, 1e-9);
  MatDestroy(&A);
}

}  // namespace
}  // namespace mlshell
