// Nearest positive semi-definite matrix by eigen-decomposition (see psd_projection.hpp).
#include "mlshell/psd_projection.hpp"

#include <Eigen/Eigenvalues>
#include <stdexcept>

namespace mlshell {

namespace {

// P(S) = Σ max(λ_i, 0) v_i v_iᵀ for S = ½ (H + Hᵀ). Written from whichever side has fewer
// terms, S − Σ_{λ_i < 0} λ_i v_i v_iᵀ or Σ_{λ_i > 0} λ_i v_i v_iᵀ, so that the result carries the
// round-off of the smaller part only (a nearly-PSD H changes by O(ε |λ_neg|), a negative
// definite one becomes exactly 0).
template <class Matrix, class Map>
void project(Map H) {
  if (!H.allFinite()) return;
  const Matrix S = 0.5 * (H + H.transpose());
  Eigen::SelfAdjointEigenSolver<Matrix> eig(S);
  if (eig.info() != Eigen::Success) return;
  const auto& lambda = eig.eigenvalues();  // ascending
  const auto& V = eig.eigenvectors();
  const Eigen::Index n = lambda.size();
  Eigen::Index negative = 0;
  while (negative < n && lambda[negative] < 0.0) ++negative;
  if (negative == 0) {
    H = S;  // bit for bit H itself when H is symmetric
    return;
  }
  Eigen::Index positive = 0;
  for (Eigen::Index i = negative; i < n; ++i) positive += lambda[i] > 0.0;
  if (negative <= positive) {
    Matrix P = S;
    for (Eigen::Index i = 0; i < negative; ++i)
      P.noalias() -= lambda[i] * V.col(i) * V.col(i).transpose();
    H = 0.5 * (P + P.transpose());
  } else {
    Matrix P = Matrix::Zero(n, n);
    for (Eigen::Index i = n - positive; i < n; ++i)
      P.noalias() += lambda[i] * V.col(i) * V.col(i).transpose();
    H = 0.5 * (P + P.transpose());
  }
}

}  // namespace

void project_to_psd(Eigen::Ref<Eigen::MatrixXd> H) {
  if (H.rows() != H.cols()) throw std::invalid_argument("project_to_psd: matrix is not square");
  project<Eigen::MatrixXd, Eigen::Ref<Eigen::MatrixXd>>(H);
}

void project_to_psd(Eigen::Matrix<double, 9, 9>& H) {
  project<Eigen::Matrix<double, 9, 9>, Eigen::Matrix<double, 9, 9>&>(H);
}

void project_to_psd(Eigen::Matrix<double, 12, 12>& H) {
  project<Eigen::Matrix<double, 12, 12>, Eigen::Matrix<double, 12, 12>&>(H);
}

}  // namespace mlshell
