// The clamped log barrier of IPC (Li et al. 2020) on squared distances, as the IPC
// Toolkit writes it (its barrier.hpp): with d a squared distance and d̂ the squared activation
// distance,
//   b(d, d̂) = −(d − d̂)² ln(d / d̂)   for 0 < d < d̂,      b = 0   for d ≥ d̂,
//   b'(d)  = (d̂ − d) (2 ln(d / d̂) − d̂/d + 1),
//   b''(d) = −2 ln(d / d̂) − 4 (d − d̂)/d + (d − d̂)²/d².
// b, b' and b'' all vanish at d = d̂, so b is C² there; on (0, d̂) b > 0, b' < 0, b'' > 0 and
// b → +∞ as d → 0⁺. For d ≤ 0 (touching or interpenetrating) b = +∞, b' = −∞, b'' = +∞, the
// limits at 0⁺: the barrier is undefined there and callers (the line search capped by CCD)
// never evaluate it there; the infinity makes a step that would get there rejected, never NaN.
//
// Thickness offset (Codimensional IPC, Li et al. 2021; Codim-IPC's code and the IPC
// Toolkit's `dmin` write the same): shells' mid-surfaces stay apart by a thickness ξ, and the
// barrier activates within a gap ĝ beyond it, at distance ξ + ĝ. Without square roots, on the
// squared distance d:
//   b_ξ(d) = b(d − ξ², (ξ + ĝ)² − ξ²) = b(d − ξ², 2ξĝ + ĝ²),
// so b_ξ'(d) = b'(d − ξ², ·) and b_ξ''(d) = b''(d − ξ², ·) (the shift has derivative 1); b_ξ → +∞
// as the distance falls to ξ, and ξ = 0 gives b(d, ĝ²).
#pragma once

namespace mlshell {

/// b(d, d̂) of the file comment (+∞ for d ≤ 0).
double barrier(double d, double dhat);
/// b'(d) of the file comment (0 for d ≥ d̂, −∞ for d ≤ 0).
double barrier_first_derivative(double d, double dhat);
/// b''(d) of the file comment (0 for d ≥ d̂, +∞ for d ≤ 0).
double barrier_second_derivative(double d, double dhat);

/// The barrier with a thickness offset b_ξ of the file comment, on squared distances.
struct ContactBarrier {
  double thickness = 0.0;  ///< ξ ≥ 0, the distance the mid-surfaces keep
  double gap = 0.0;        ///< ĝ > 0, the activation gap beyond ξ (distance, not squared)

  /// Throws std::invalid_argument unless ξ ≥ 0 and ĝ > 0 are finite.
  static ContactBarrier from(double thickness, double gap);

  /// The squared distance (ξ + ĝ)² below which the barrier is active.
  double activation_squared_distance() const;
  /// b_ξ(d), b_ξ'(d), b_ξ''(d) for a squared distance d (+∞, −∞, +∞ for d ≤ ξ²).
  double value(double d) const;
  double first_derivative(double d) const;
  double second_derivative(double d) const;
};

}  // namespace mlshell
