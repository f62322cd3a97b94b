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

/// The same P(½ (H + Hᵀ)) for the Hessian of an energy of K = 3, 4 or 6 points that sees only
/// their differences (a triangle's membrane, a hinge, a mid-edge element, a contact pair), so that
/// the three common translations t are in its null space, H t = 0. The eigen-decomposition then
/// runs on the 3(K − 1) motions orthogonal to them: 12 × 12 becomes 9 × 9, about 2.4× fewer
/// operations. The result equals project_to_psd's to round-off, and where H has no negative
/// eigenvalue on them it is ½ (H + Hᵀ) bit for bit. An H that moves under translations by more than
/// round-off (10⁻⁸ K of its largest entry) is projected whole, as project_to_psd does.
void project_stencil_hessian_to_psd(Eigen::Matrix<double, 9, 9>& H);
void project_stencil_hessian_to_psd(Eigen::Matrix<double, 12, 12>& H);
void project_stencil_hessian_to_psd(Eigen::Matrix<double, 18, 18>& H);

}  // namespace mlshell
