// Projection onto the PSD cone: known 2×2 and 3×3 cases, random indefinite matrices (dynamic and
// fixed 9×9, 12×12) land on the cone at the optimal Frobenius distance, PSD input is returned
// unchanged, and degenerate inputs (zero, negative definite, non-finite, blocks) behave.
#include "mlshell/psd_projection.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "element_fixtures.hpp"
#include "mlshell/triangle/membrane.hpp"

using namespace mlshell;
using mlshell::test::random_rotation;

namespace {

template <class Matrix>
Matrix random_symmetric(std::mt19937& rng, int n) {
  std::normal_distribution<double> g(0.0, 1.0);
  Matrix A(n, n);
  for (int i = 0; i < n * n; ++i) A.data()[i] = g(rng);
  return A + A.transpose();
}

/// Projected P of a symmetric H: PSD to round-off, keeps the positive eigenvalues, and its
/// distance from H is that of the nearest PSD matrix, sqrt(Σ_{λ<0} λ²).
template <class Matrix>
void expect_projection(const Matrix& H, const Matrix& P) {
  const Eigen::SelfAdjointEigenSolver<Matrix> before(H), after(P);
  const double scale = H.norm();
  EXPECT_GE(after.eigenvalues().minCoeff(), -1e-12 * scale) << after.eigenvalues().transpose();
  EXPECT_LE((P - P.transpose()).norm(), 1e-15 * scale);
  double distance2 = 0.0;
  for (int i = 0; i < H.rows(); ++i) {
    const double l = before.eigenvalues()[i];
    if (l < 0) distance2 += l * l;
    EXPECT_NEAR(after.eigenvalues()[i], std::max(l, 0.0), 1e-12 * scale);
  }
  EXPECT_NEAR((H - P).norm(), std::sqrt(distance2), 1e-12 * scale);
}

}  // namespace

TEST(PsdProjection, KnownTwoByTwoAndThreeByThree) {
  // [[1, 2], [2, 1]] = 3 u uᵀ − v vᵀ with u = (1, 1)/√2, v = (1, −1)/√2 → 3 u uᵀ.
  Eigen::MatrixXd A(2, 2);
  A << 1, 2, 2, 1;
  project_to_psd(A);
  Eigen::MatrixXd expected(2, 2);
  expected << 1.5, 1.5, 1.5, 1.5;
  EXPECT_LE((A - expected).norm(), 1e-15);
  // Q diag(2, −1, 3) Qᵀ → Q diag(2, 0, 3) Qᵀ.
  std::mt19937 rng(61);
  const Eigen::Matrix3d Q = random_rotation(rng);
  Eigen::Matrix3d B = Q * Eigen::Vector3d(2, -1, 3).asDiagonal() * Q.transpose();
  project_to_psd(B);
  const Eigen::Matrix3d B_expected = Q * Eigen::Vector3d(2, 0, 3).asDiagonal() * Q.transpose();
  EXPECT_LE((B - B_expected).norm(), 1e-14);
  // A tiny negative eigenvalue is removed too.
  Eigen::Matrix3d C = Q * Eigen::Vector3d(2, -1e-9, 3).asDiagonal() * Q.transpose();
  project_to_psd(C);
  EXPECT_LE((C - B_expected).norm(), 1e-14);
  // Only the symmetric part counts: adding a skew-symmetric matrix changes nothing.
  Eigen::Matrix3d K;
  K << 0, 1, -2, -1, 0, 0.5, 2, -0.5, 0;
  Eigen::Matrix3d D = Q * Eigen::Vector3d(2, -1, 3).asDiagonal() * Q.transpose() + K;
  project_to_psd(D);
  EXPECT_LE((D - B_expected).norm(), 1e-14);
  Eigen::Matrix3d E = Q * Eigen::Vector3d(2, 1, 3).asDiagonal() * Q.transpose();
  const Eigen::Matrix3d E0 = E;
  E += K;
  project_to_psd(E);
  EXPECT_LE((E - E0).norm(), 1e-15);
}

TEST(PsdProjection, RandomIndefiniteMatricesLandOnTheCone) {
  std::mt19937 rng(67);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::MatrixXd H = random_symmetric<Eigen::MatrixXd>(rng, 20);
    Eigen::MatrixXd P = H;
    project_to_psd(P);
    expect_projection(H, P);
    const Eigen::Matrix<double, 9, 9> H9 = random_symmetric<Eigen::Matrix<double, 9, 9>>(rng, 9);
    Eigen::Matrix<double, 9, 9> P9 = H9;
    project_to_psd(P9);
    expect_projection(H9, P9);
    Eigen::MatrixXd P9_dynamic = H9;
    project_to_psd(P9_dynamic);
    EXPECT_LE((P9_dynamic - P9).norm(), 1e-13 * H9.norm());
    // Mostly negative spectra take the other branch (sum of the positive part).
    const Eigen::Matrix<double, 12, 12> H12 =
        random_symmetric<Eigen::Matrix<double, 12, 12>>(rng, 12) -
        3.0 * Eigen::Matrix<double, 12, 12>::Identity();
    Eigen::Matrix<double, 12, 12> P12 = H12;
    project_to_psd(P12);
    expect_projection(H12, P12);
  }
}

TEST(PsdProjection, PsdInputIsUnchanged) {
  std::mt19937 rng(71);
  std::normal_distribution<double> g(0.0, 1.0);
  for (int rank : {12, 9, 3}) {
    Eigen::MatrixXd B(rank, 12);
    for (int i = 0; i < B.size(); ++i) B.data()[i] = g(rng);
    const Eigen::MatrixXd H = B.transpose() * B;  // PSD of rank `rank`
    Eigen::MatrixXd P = H;
    project_to_psd(P);
    EXPECT_LE((P - H).norm(), 1e-14 * H.norm()) << "rank " << rank;
    if (rank == 12) {
      EXPECT_EQ(P, H);  // positive definite: bit for bit
    }
  }
  Eigen::Matrix<double, 12, 12> Z = Eigen::Matrix<double, 12, 12>::Zero();
  project_to_psd(Z);
  EXPECT_EQ(Z, (Eigen::Matrix<double, 12, 12>::Zero()));
}

TEST(PsdProjection, DegenerateInputs) {
  // Negative definite → exactly 0.
  Eigen::Matrix<double, 9, 9> N = -Eigen::Matrix<double, 9, 9>::Identity();
  N(0, 1) = N(1, 0) = 0.3;
  project_to_psd(N);
  EXPECT_EQ(N, (Eigen::Matrix<double, 9, 9>::Zero()));
  // Non-finite entries: left as they were, no new NaN.
  Eigen::MatrixXd F = Eigen::MatrixXd::Identity(3, 3);
  F(0, 0) = -1.0;
  F(2, 2) = std::numeric_limits<double>::infinity();
  const Eigen::MatrixXd F0 = F;
  project_to_psd(F);
  EXPECT_EQ(F, F0);
  F(2, 2) = std::numeric_limits<double>::quiet_NaN();
  project_to_psd(F);
  EXPECT_EQ(F(0, 0), -1.0);
  EXPECT_EQ(F(1, 1), 1.0);
  EXPECT_TRUE(std::isnan(F(2, 2)));
  Eigen::MatrixXd R(2, 3);
  EXPECT_THROW(project_to_psd(R), std::invalid_argument);
  // A block of a larger matrix, in place; the rest is untouched.
  Eigen::MatrixXd big = Eigen::MatrixXd::Constant(5, 5, 7.0);
  big.block(1, 1, 2, 2) << 1, 2, 2, 1;
  project_to_psd(big.block(1, 1, 2, 2));
  EXPECT_NEAR(big(1, 1), 1.5, 1e-15);
  EXPECT_NEAR(big(2, 1), 1.5, 1e-15);
  EXPECT_EQ(big(0, 0), 7.0);
  EXPECT_EQ(big(3, 2), 7.0);
  EXPECT_EQ(big(1, 3), 7.0);
}

// The use case: the Neo-Hookean Hessian of a compressed triangle is indefinite (in-plane
// buckling modes); its projection is PSD and leaves the stiff directions alone.
TEST(PsdProjection, ProjectsACompressedMembraneHessian) {
  const TriangleRest rest = TriangleRest::from(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0),
                                               Eigen::Vector3d(0.3, 0.9, 0));
  const MembraneParameters params{1.0, 1.0, 0.1};
  Matrix9 H;
  const double E =
      neo_hookean_membrane(rest, params, Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(0.6, 0, 0),
                           Eigen::Vector3d(0.18, 0.54, 0), nullptr, &H);
  ASSERT_TRUE(std::isfinite(E));
  ASSERT_LT(Eigen::SelfAdjointEigenSolver<Matrix9>(H).eigenvalues()[0], -1e-6 * H.norm());
  Matrix9 P = H;
  project_to_psd(P);
  expect_projection(H, P);
}

namespace {

// A symmetric matrix on K points with the three translations in its null space: random in the
// 3(K − 1) motions orthogonal to them, shifted so that it is indefinite.
template <int K>
Eigen::Matrix<double, 3 * K, 3 * K> random_translation_free(std::mt19937& rng, double shift) {
  constexpr int N = 3 * K;
  using Matrix = Eigen::Matrix<double, N, N>;
  Matrix Q;
  // The projector onto the complement of the translations: I − (1/K) Σ_c t_c t_cᵀ.
  for (int i = 0; i < N; ++i)
    for (int j = 0; j < N; ++j) Q(i, j) = (i == j) - (i % 3 == j % 3 ? 1.0 / K : 0.0);
  const Matrix R = random_symmetric<Matrix>(rng, N) - shift * Matrix::Identity();
  return Q * R * Q;
}

template <int K>
void expect_stencil_projection_matches(std::mt19937& rng, double shift) {
  using Matrix = Eigen::Matrix<double, 3 * K, 3 * K>;
  const Matrix H = random_translation_free<K>(rng, shift);
  Matrix full = H, stencil = H;
  project_to_psd(full);
  project_stencil_hessian_to_psd(stencil);
  expect_projection(H, stencil);
  EXPECT_LE((stencil - full).norm(), 1e-12 * H.norm()) << "K = " << K << ", shift " << shift;
}

}  // namespace

// project_stencil_hessian_to_psd works on the motions orthogonal to the translations only; where
// they are in H's null space it equals the full projection, for every stencil size and both of
// its branches (a few negative eigenvalues, or mostly negative ones).
TEST(PsdProjection, StencilHessiansProjectOnTheMotionsThatAreNotTranslations) {
  std::mt19937 rng(73);
  for (int trial = 0; trial < 10; ++trial)
    for (double shift : {0.0, 3.0}) {
      expect_stencil_projection_matches<3>(rng, shift);
      expect_stencil_projection_matches<4>(rng, shift);
      expect_stencil_projection_matches<6>(rng, shift);
    }
  // A real one: the compressed membrane's Hessian (translation-free by construction).
  const TriangleRest rest = TriangleRest::from(Eigen::Vector3d(0, 0, 0), Eigen::Vector3d(1, 0, 0),
                                               Eigen::Vector3d(0.3, 0.9, 0));
  Matrix9 H;
  neo_hookean_membrane(rest, {1.0, 1.0, 0.1}, Eigen::Vector3d(0.2, -0.1, 0.4),
                       Eigen::Vector3d(0.8, -0.1, 0.4), Eigen::Vector3d(0.38, 0.44, 0.4), nullptr,
                       &H);
  Matrix9 full = H, stencil = H;
  project_to_psd(full);
  project_stencil_hessian_to_psd(stencil);
  expect_projection(H, stencil);
  EXPECT_LE((stencil - full).norm(), 1e-12 * H.norm());
}

TEST(PsdProjection, StencilProjectionKeepsPsdInputAndProjectsOtherMatricesWhole) {
  std::mt19937 rng(79);
  // PSD on the complement: returned bit for bit.
  Eigen::Matrix<double, 12, 12> H = random_translation_free<4>(rng, 0.0);
  H = (H * H).eval();
  H = (0.5 * (H + H.transpose())).eval();  // .eval(): H is on both sides
  Eigen::Matrix<double, 12, 12> P = H;
  project_stencil_hessian_to_psd(P);
  EXPECT_EQ(P, H);
  // Translations not in the null space (an energy tied to a fixed point): the full projection,
  // bit for bit, not a projection that silently drops the translations.
  const Eigen::Matrix<double, 12, 12> A = random_symmetric<Eigen::Matrix<double, 12, 12>>(rng, 12);
  Eigen::Matrix<double, 12, 12> full = A, stencil = A;
  project_to_psd(full);
  project_stencil_hessian_to_psd(stencil);
  EXPECT_EQ(stencil, full);
  expect_projection(A, stencil);
  // Non-finite entries: left as they were.
  Eigen::Matrix<double, 9, 9> F = -Eigen::Matrix<double, 9, 9>::Identity();
  F(4, 4) = std::numeric_limits<double>::infinity();
  const Eigen::Matrix<double, 9, 9> F0 = F;
  project_stencil_hessian_to_psd(F);
  EXPECT_EQ(F, F0);
}
