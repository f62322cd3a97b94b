// Projection of a symmetric matrix onto the positive semi-definite cone, for projected Newton
// (Progressive Shell Quasistatics §4.5; Teran et al. 2005). With the eigen-decomposition
//   H = Σ_i λ_i v_i v_iᵀ,
// the nearest PSD matrix in the Frobenius norm is
//   P(H) = Σ_i max(λ_i, 0) v_i v_iᵀ,   ‖H − P(H)‖_F² = Σ_{λ_i < 0} λ_i².
// Only the symmetric part ½ (H + Hᵀ) is used (P of a non-symmetric H is P of its symmetric part).
#pragma once

#include <Eigen/Core>

namespace mlshell {

/// Replaces the square matrix H by P(½ (H + Hᵀ)). A symmetric H with no negative eigenvalue is
/// left exactly as it was (bit for bit), so PSD inputs come back unchanged; a matrix with a
/// non-finite entry is left as it was, so no NaN is produced from finite input. Throws
/// std::invalid_argument if H is not square.
void project_to_psd(Eigen::Ref<Eigen::MatrixXd> H);

/// Fixed-size versions of the same for the per-triangle and per-hinge Hessians (no allocation).
void project_to_psd(Eigen::Matrix<double, 9, 9>& H);
void project_to_psd(Eigen::Matrix<double, 12, 12>& H);

}  // namespace mlshell
