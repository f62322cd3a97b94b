// Second-order forward-mode automatic differentiation: a value with its gradient and Hessian in
// N independent variables. Used for the shell strains as functions of the 15 local surface
// quantities (a_1, a_2, a_11, a_12, a_22), whose Hessians are awkward to derive by hand.
#pragma once

#include <array>
#include <cmath>

namespace mlshell {

/// With `Second` false only the gradient is propagated (cheaper when no Hessian is needed).
template <int N, bool Second = true>
struct Jet {
  static constexpr bool kSecond = Second;
  double v = 0.0;
  std::array<double, N> g{};
  std::array<double, Second ? N * N : 0> h{};  // full symmetric matrix, row-major

  static Jet constant(double c) {
    Jet j;
    j.v = c;
    return j;
  }
  static Jet variable(double x, int i) {
    Jet j;
    j.v = x;
    j.g[i] = 1.0;
    return j;
  }
  double hess(int i, int k) const { return h[i * N + k]; }
};

template <int N, bool S>
Jet<N, S> operator+(const Jet<N, S>& a, const Jet<N, S>& b) {
  Jet<N, S> r;
  r.v = a.v + b.v;
  for (int i = 0; i < N; ++i) r.g[i] = a.g[i] + b.g[i];
  if constexpr (S)
    for (int i = 0; i < N * N; ++i) r.h[i] = a.h[i] + b.h[i];
  return r;
}

template <int N, bool S>
Jet<N, S> operator-(const Jet<N, S>& a, const Jet<N, S>& b) {
  Jet<N, S> r;
  r.v = a.v - b.v;
  for (int i = 0; i < N; ++i) r.g[i] = a.g[i] - b.g[i];
  if constexpr (S)
    for (int i = 0; i < N * N; ++i) r.h[i] = a.h[i] - b.h[i];
  return r;
}

template <int N, bool S>
Jet<N, S> operator*(double s, const Jet<N, S>& a) {
  Jet<N, S> r;
  r.v = s * a.v;
  for (int i = 0; i < N; ++i) r.g[i] = s * a.g[i];
  if constexpr (S)
    for (int i = 0; i < N * N; ++i) r.h[i] = s * a.h[i];
  return r;
}

template <int N, bool S>
Jet<N, S> operator+(const Jet<N, S>& a, double s) {
  Jet<N, S> r = a;
  r.v += s;
  return r;
}

/// (ab)'' = a'' b + a b'' + a' b'ᵀ + b' a'ᵀ
template <int N, bool S>
Jet<N, S> operator*(const Jet<N, S>& a, const Jet<N, S>& b) {
  Jet<N, S> r;
  r.v = a.v * b.v;
  for (int i = 0; i < N; ++i) r.g[i] = a.g[i] * b.v + a.v * b.g[i];
  if constexpr (S)
    for (int i = 0; i < N; ++i)
      for (int k = 0; k < N; ++k)
        r.h[i * N + k] = a.h[i * N + k] * b.v + a.v * b.h[i * N + k] + a.g[i] * b.g[k] +
                       b.g[i] * a.g[k];
  return r;
}

/// f(a) for a scalar function with f(a.v) = f0, f'(a.v) = f1, f''(a.v) = f2.
template <int N, bool S>
Jet<N, S> chain(const Jet<N, S>& a, double f0, double f1, double f2) {
  Jet<N, S> r;
  r.v = f0;
  for (int i = 0; i < N; ++i) r.g[i] = f1 * a.g[i];
  if constexpr (S)
    for (int i = 0; i < N; ++i)
      for (int k = 0; k < N; ++k) r.h[i * N + k] = f1 * a.h[i * N + k] + f2 * a.g[i] * a.g[k];
  return r;
}

template <int N, bool S>
Jet<N, S> sqrt(const Jet<N, S>& a) {
  const double s = std::sqrt(a.v);
  return chain(a, s, 0.5 / s, -0.25 / (s * a.v));
}

template <int N, bool S>
Jet<N, S> inverse(const Jet<N, S>& a) {
  const double i = 1.0 / a.v;
  return chain(a, i, -i * i, 2.0 * i * i * i);
}

}  // namespace mlshell
