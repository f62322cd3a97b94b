// Midedge-normal bending of one triangle (`bending: midedge`): a rotation-free Kirchhoff plate
// element whose curvature is the triangle's second fundamental form built from the normals at
// its edge midpoints (Grinspun, Gingold, Reisman and Zorin 2006, "Computing discrete shape
// operators on general meshes"; the averaged midedge normals of Chen et al. 2018, libshell).
// 18 dofs: the triangle's vertices x0, x1, x2 (counter-clockwise seen from the normal side) and
// the wing vertex x_{3+i} across edge i (the edge opposite x_i, from x_{i+1} to x_{i+2}).
//
// Second fundamental form. Interpolate the normal linearly between the midedge normals n_i.
// In the basis a₁ = x1 − x0, a₂ = x2 − x0, with n_i ⊥ edge i and the tilts
//   t_i = n_i · (x_i − m_i)   (m_i the midpoint of edge i),
// II_αβ = −∂_α n · a_β is
//   II = 2 [[t₀ + t₁, t₀], [t₀, t₀ + t₂]],   i.e.  II(e_i, e_i) = 2 (t_j + t_k) along each edge.
// The averaged normal n_i = (n + n')/|n + n'| of the triangle and its neighbour across edge i is
// turned from n by half the dihedral angle θ_i of that hinge (hinge_bending.hpp), so
// t_i = −h_i sin(θ_i/2) with h_i the height of x_i over edge i. At a clamped edge the midedge
// normal is the clamp's, turned from n by the whole angle θ_i to the clamp's virtual triangle
// (x_{i+1}, x_{i+2}, mirror of x_i): t_i = −h_i sin θ_i. Linearised in the deviation from the
// rest angle, as the hinge energy is, with the rest heights h̄_i:
//   δt_i = −c_i h̄_i δθ_i,   δθ_i = wrap(θ_i − θ̄_i),   c_i = ½ (neighbour) or 1 (clamp).
//
// Energy. Kirchhoff's plate energy on the rest area Ā with M = Ā⁻¹ (II − ĪI) (Ā the rest
// metric in the same basis) and D = E τ³ / (12 (1 − ν²)):
//   W = Ā D/2 [ν tr(M)² + (1 − ν) tr(M²)] = ½ δθᵀ K δθ,
//   K_ij = c_i h̄_i c_j h̄_j Ā D [ν tr(Ā⁻¹G_i) tr(Ā⁻¹G_j) + (1 − ν) tr(Ā⁻¹G_i Ā⁻¹G_j)],
// G₀ = 2 [[1, 1], [1, 1]], G₁ = 2 [[1, 0], [0, 0]], G₂ = 2 [[0, 0], [0, 1]] (II = Σ t_i G_i).
// K is positive definite for −1 < ν < 1.
//
// Free boundary edges. A boundary edge without a clamp has no neighbour to fix its midedge
// normal: its tilt is a free variable of this element alone (the natural boundary condition,
// no bending moment across a free edge), eliminated by minimising W over it. W is quadratic in
// the tilts, so the elimination is a constant Schur complement: with a the edges that have a
// wing and f the free ones, W = ½ δθ_aᵀ (K_aa − K_af K_ff⁻¹ K_fa) δθ_a.
//
// What it reproduces (tests): Kirchhoff's energy D/2 [ν (κ₁ + κ₂)² + (1 − ν)(κ₁² + κ₂²)] of
// every constant-curvature state where the two triangles at each edge form a parallelogram
// (structured meshes with parallel diagonals), and of cylindrical bending along the grid on
// structured meshes with alternating diagonals as well; a cantilever to 0.1 % of
// Euler–Bernoulli. Where edge neighbours are not parallelograms, twist is not reproduced
// (alternating diagonals: twice the energy), and on irregular meshes the element does not
// converge to Kirchhoff's plate; the hinge energy has the same defect on every mesh.
#pragma once

#include <Eigen/Core>
#include <array>

#include "mlshell/triangle/element_types.hpp"

namespace mlshell {

using Vector18 = Eigen::Matrix<double, 18, 1>;
using Matrix18 = Eigen::Matrix<double, 18, 18>;

/// What lies across each edge of a triangle.
enum class EdgeWing {
  kFree,       ///< a boundary edge with no clamp: its tilt is eliminated (natural condition)
  kNeighbour,  ///< the neighbouring triangle's opposite vertex (c = ½)
  kClamp,      ///< the clamp's virtual vertex, the rest mirror of x_i through the edge (c = 1)
};

/// Rest-state quantities of one element.
struct MidedgeRest {
  Eigen::Matrix3d stiffness = Eigen::Matrix3d::Zero();  ///< K (condensed; zero for free edges)
  std::array<double, 3> angles{};                       ///< θ̄_i (0 for free edges)
  std::array<bool, 3> active{};                         ///< edge i has a wing
  /// From the rest positions X (x0, x1, x2, then the wing vertex of each edge; ignored for free
  /// edges), the wing kinds and the plate stiffness D with Poisson's ratio ν. Throws
  /// std::invalid_argument if a used position is not finite, the triangle is degenerate (the
  /// criterion of TriangleRest::from) or a rest hinge has a zero normal.
  static MidedgeRest from(const std::array<Eigen::Vector3d, 6>& X,
                          const std::array<EdgeWing, 3>& wings, double plate_stiffness,
                          double poisson_ratio);
};

/// The plate stiffness D = E τ³ / (12 (1 − ν²)).
double plate_stiffness(double E, double nu, double thickness);

/// ½ δθᵀ K δθ and, where the pointers are not null, its gradient and Hessian in the 18 stacked
/// positions (zero in the wing slots of free edges). Returns +infinity, writing neither, when a
/// used position is not finite, a deformed hinge has a zero edge or normal, or a result would
/// not be finite.
double midedge_bending(const MidedgeRest& rest, const std::array<Eigen::Vector3d, 6>& x,
                       Vector18* grad, Matrix18* hess);

}  // namespace mlshell
