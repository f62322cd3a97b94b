// Nearest positive semi-definite matrix by eigen-decomposition (see psd_projection.hpp).
#include "mlshell/psd_projection.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace mlshell {

namespace {

// P(S) = Σ max(λ_i, 0) v_i v_iᵀ from S's eigenvalues λ (ascending) and orthonormal
// eigenvectors V (all of them, or all but a null space S leaves alone), into H. Written from
// whichever side has fewer terms, S − Σ_{λ_i < 0} λ_i v_i v_iᵀ or Σ_{λ_i > 0} λ_i v_i v_iᵀ, so
// that the result carries the round-off of the smaller part only (a nearly-PSD H changes by
// O(ε |λ_neg|), a negative definite one becomes exactly 0).
template <class Matrix, class Values, class Vectors, class Out>
void write_projection(const Matrix& S, const Values& lambda, const Vectors& V, Out&& H) {
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
    Matrix P = Matrix::Zero(S.rows(), S.cols());
    for (Eigen::Index i = n - positive; i < n; ++i)
      P.noalias() += lambda[i] * V.col(i) * V.col(i).transpose();
    H = 0.5 * (P + P.transpose());
  }
}

// P(½ (H + Hᵀ)) by the eigen-decomposition of the whole matrix.
template <class Matrix, class Map>
void project(Map H) {
  if (!H.allFinite()) return;
  const Matrix S = 0.5 * (H + H.transpose());
  Eigen::SelfAdjointEigenSolver<Matrix> eig(S);
  if (eig.info() != Eigen::Success) return;
  write_projection(S, eig.eigenvalues(), eig.eigenvectors(), H);
}

// Helmert's orthonormal basis of the K-vectors whose entries sum to zero, times I₃: the
// 3K × 3(K − 1) matrix T whose columns span every motion of K points but their common
// translation. Column (j, c), j = 1..K−1, moves points 0..j−1 by s_j and point j by −j s_j along
// axis c, s_j = 1/√(j(j+1)). Its products are prefix and suffix sums, O(K) per row, not O(K²).
double helmert(int j) {
  return 1.0 / std::sqrt(static_cast<double>(j) * (j + 1));
}

/// A T for the 3K-row A: the columns (j, c) are s_j (Σ_{p<j} A_(p,c) − j A_(j,c)).
template <int K, class Matrix>
Eigen::Matrix<double, Matrix::RowsAtCompileTime, 3 * (K - 1)> times_t(const Matrix& A) {
  Eigen::Matrix<double, Matrix::RowsAtCompileTime, 3 * (K - 1)> out;
  for (int c = 0; c < 3; ++c) {
    auto prefix = A.col(c).eval();
    for (int j = 1; j < K; ++j) {
      out.col(3 * (j - 1) + c) = helmert(j) * (prefix - j * A.col(3 * j + c));
      prefix += A.col(3 * j + c);
    }
  }
  return out;
}

/// T V for the 3(K − 1)-row V: point p, axis c gets Σ_{j>p} s_j V_(j,c) − p s_p V_(p,c).
template <int K, class Matrix>
Eigen::Matrix<double, 3 * K, Matrix::ColsAtCompileTime> t_times(const Matrix& V) {
  Eigen::Matrix<double, 3 * K, Matrix::ColsAtCompileTime> out;
  for (int c = 0; c < 3; ++c) {
    Eigen::Matrix<double, 1, Matrix::ColsAtCompileTime> suffix =
        Eigen::Matrix<double, 1, Matrix::ColsAtCompileTime>::Zero();
    for (int p = K - 1; p >= 0; --p) {
      out.row(3 * p + c) = suffix;
      if (p >= 1) {
        out.row(3 * p + c) -= p * helmert(p) * V.row(3 * (p - 1) + c);
        suffix += helmert(p) * V.row(3 * (p - 1) + c);
      }
    }
  }
  return out;
}

// P(S) of S = ½ (H + Hᵀ) where S t = 0 for the three translations t: S = T R Tᵀ with
// R = Tᵀ S T, and P(S) = T P(R) Tᵀ. The eigen-decomposition is 3(K − 1)-square, not 3K-square.
// As in project(), the smaller of the negative and positive parts is the one written.
template <int K>
void project_translation_free(Eigen::Matrix<double, 3 * K, 3 * K>& H) {
  constexpr int N = 3 * K, M = 3 * (K - 1);
  using Matrix = Eigen::Matrix<double, N, N>;
  if (!H.allFinite()) return;
  const Matrix S = 0.5 * (H + H.transpose());
  // An energy that sees more than its points' differences (a clamp's fixed target, say) has
  // translations outside the null space, by far more than round-off: project it whole.
  const double scale = S.cwiseAbs().maxCoeff();
  for (int c = 0; c < 3; ++c) {
    double moved = 0.0;
    for (int i = 0; i < N; ++i) {
      double sum = 0.0;
      for (int p = 0; p < K; ++p) sum += S(i, 3 * p + c);
      moved = std::max(moved, std::abs(sum));
    }
    if (moved > 1e-8 * K * scale) {
      project<Matrix, Matrix&>(H);
      return;
    }
  }
  const Eigen::Matrix<double, N, M> ST = times_t<K>(S);
  const Eigen::Matrix<double, M, M> R = times_t<K>(Eigen::Matrix<double, M, N>(ST.transpose()));
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, M, M>> eig(R);
  if (eig.info() != Eigen::Success) return;
  // S's eigenvectors are T's images of R's.
  write_projection(S, eig.eigenvalues(), t_times<K>(eig.eigenvectors()), H);
}

}  // namespace

void project_stencil_hessian_to_psd(Eigen::Matrix<double, 9, 9>& H) {
  project_translation_free<3>(H);
}

void project_stencil_hessian_to_psd(Eigen::Matrix<double, 12, 12>& H) {
  project_translation_free<4>(H);
}

void project_stencil_hessian_to_psd(Eigen::Matrix<double, 18, 18>& H) {
  project_translation_free<6>(H);
}

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
