// The nonlinear response functions of the woven-cloth material (paper eq. 3.4),
//   φ(u) = Σ_i μ_i/α_i ((u+1)^α_i − 1),
// made finite and C² for every argument a solver can try.
//
// A fitted φ is only meaningful on the range it was fitted on. Table 1's φ₃ (denim weft) rises
// up to u ≈ 0.078 (|Ẽ22| ≈ 28 %), then φ₃' falls to zero at u ≈ 0.10 and φ₃ → −∞, because its
// largest exponent (α₃₄ = 30.07) has a negative coefficient. Every φ is therefore continued
// beyond a point u_s, with the C² cubic
//   φ̂(u) = φ_s + φ'_s t + ½ φ''_s t² + a t³/6,  t = u − u_s,  a = max(0, −φ''_s) · |φ''_s| / φ'_s,
// whose slope φ̂' = φ'_s + φ''_s t + ½ a t² stays ≥ φ'_s / 2 > 0 (the minimum of the quadratic).
//   - If φ' has a zero on (0, u_max], u_s is the last maximum of φ' before it (there φ''_s = 0,
//     so the continuation is the tangent line: the fitted stiffness at its peak is kept).
//   - Otherwise u_s = u_max = 1 (strain 100 %), far outside any fitted range, so that no
//     exponential can overflow: φ stays finite for every finite argument.
// An argument that may be negative (φ₂'s Ẽ11·Ẽ22) is continued the same way below u = −½,
// where (u+1)^α is still defined. A linear φ (φ₂ of Table 1) is exact everywhere.
//
// `ratio` gives r(u) = φ(u)/u with two derivatives, accurate down to u = 0 (a Taylor series
// below |u| = 1e-8): the coupling limit of the material needs it at Ẽ11 = 0 or Ẽ22 = 0.
#pragma once

#include <vector>

namespace mlshell {

/// φ and its first two derivatives at one argument.
struct PhiValue {
  double f = 0.0, df = 0.0, ddf = 0.0;
};

class ResponseFunction {
 public:
  /// Throws std::invalid_argument (with a message naming φ_`index`) if φ'(0) = Σ μ_i ≤ 0, or if
  /// φ' falls from u = 0 to a zero without a maximum (no rising range to continue from).
  ResponseFunction(std::vector<double> mu, std::vector<double> alpha, bool signed_argument,
                   int index);

  /// The continued φ̂ (what the material uses).
  PhiValue operator()(double u) const;
  /// The fit as printed, Σ μ_i/α_i ((u+1)^α_i − 1), for u > −1.
  PhiValue fitted(double u) const;
  /// r(u) = φ̂(u)/u, r(0) = φ'(0); `at` is φ̂(u) when the caller has it already.
  PhiValue ratio(double u, const PhiValue* at = nullptr) const;
  /// Whether u lies in the continuation (outside the fitted range [lower, upper]).
  bool continued(double u) const { return u > upper_.u || u < lower_.u; }
  double upper_limit() const { return upper_.u; }
  double lower_limit() const { return lower_.u; }
  bool linear() const { return linear_; }

  /// The argument up to which fits are trusted without a zero of φ' (strain 100 %).
  static constexpr double kMaxArgument = 1.0;

 private:
  struct Continuation {
    double u = 0.0, a = 0.0;  // start and cubic coefficient
    PhiValue at;              // φ at the start
  };
  Continuation make_continuation(double u) const;
  static PhiValue extend(const Continuation& c, double t);
  std::vector<double> mu_, alpha_;
  bool linear_ = true;
  Continuation upper_, lower_;
  double taylor_[5] = {};  // φ^(n)(0) at index n = 1..4; φ^(5)(0) at index 0
  double taylor_limit_ = 0.0;
};

}  // namespace mlshell
