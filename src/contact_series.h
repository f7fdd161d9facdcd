// Internal: the Taylor series in t of the contact point of a free motion, x(t) - x(0) =
// sum_{m=1..M} x_m t^m, from the axis z0 and the conserved vector K (kinematics.h: omega_h =
// K - (lambda - 1) v0 z_h, v0 = <K, z_h> / (z3^2 + lambda |z_h|^2), z' = omega x z,
// x' = (omega_2, -omega_1)), by the recurrences of series arithmetic (Cauchy products and one
// series division). Templated on the scalar of K so that SeriesDual gives d x_m / ds.
// The join uses it as a cheap model of x(s, t) on short arcs to refine its first guess; every
// answer is still checked by a rollout (join.cc), so the model only saves rollouts.
#pragma once

#include <array>

namespace plateball::internal {

/// A number with its derivative d/ds (forward mode, one direction): lighter than ceres::Jet in
/// the unrolled recurrences below.
struct SeriesDual {
  double a = 0.0, d = 0.0;
  SeriesDual() = default;
  SeriesDual(double value, double derivative = 0.0) : a(value), d(derivative) {}
};
inline SeriesDual operator+(SeriesDual x, SeriesDual y) { return {x.a + y.a, x.d + y.d}; }
inline SeriesDual operator-(SeriesDual x, SeriesDual y) { return {x.a - y.a, x.d - y.d}; }
inline SeriesDual operator*(SeriesDual x, SeriesDual y) { return {x.a * y.a, x.a * y.d + x.d * y.a}; }
inline SeriesDual operator*(double c, SeriesDual x) { return {c * x.a, c * x.d}; }
inline SeriesDual operator-(SeriesDual x) { return {-x.a, -x.d}; }
inline SeriesDual& operator+=(SeriesDual& x, SeriesDual y) { return x = x + y; }
inline SeriesDual& operator-=(SeriesDual& x, SeriesDual y) { return x = x - y; }
inline double Value(double x) { return x; }
inline double Value(const SeriesDual& x) { return x.a; }

/// x * y, with its derivative when `exact` (else the value alone: the recurrences below then
/// carry no derivative beyond the order asked for, and the compiler drops that work).
inline double SeriesProduct(double x, double y, bool) { return x * y; }
inline SeriesDual SeriesProduct(const SeriesDual& x, const SeriesDual& y, bool exact) {
  return exact ? x * y : SeriesDual(x.a * y.a);
}

/// x[m] (m = 1..M) are the Taylor coefficients of x(t) - x(0) at t = 0; x[0] = 0. z0 must be a
/// unit vector: |z| = 1 along the motion gives z3^2 + lambda |z_h|^2 = lambda - (lambda - 1) z3^2.
/// T is double or SeriesDual (K and its derivative d K / ds); with SeriesDual the derivatives
/// are those of x_1 ... x_D, those of the higher coefficients are left 0 (the join's Newton step
/// needs the values to a higher order than the Jacobian).
template <int M, int D = M, typename T>
void ContactSeries(const double z0[3], const T k[2], double lambda, std::array<std::array<T, 2>, M + 1>* x) {
  std::array<std::array<T, M>, 3> z;  // z[i][m]: component i, order m
  std::array<T, M> q, v;              // q = lambda - (lambda - 1) z3^2, v = v0 = <K, z_h> / q
  std::array<std::array<T, M>, 2> w;  // omega_h
  for (int i = 0; i < 3; ++i) z[i][0] = T(z0[i]);
  const double c = lambda - 1.0;
  (*x)[0] = {T(0.0), T(0.0)};
  const double inv_q0 = 1.0 / (lambda - c * z0[2] * z0[2]);
#pragma GCC unroll 16
  for (int m = 0; m < M; ++m) {
    const bool e = m < D;  // with derivatives at this order
    const auto mul = [e](const T& p, const T& r) { return SeriesProduct(p, r, e); };
    T z22 = T(0.0), num = mul(k[0], z[0][m]) + mul(k[1], z[1][m]), cz0 = T(0.0), cz1 = T(0.0);
    for (int j = 0; j <= m; ++j) z22 += mul(z[2][j], z[2][m - j]);
    q[m] = (m == 0 ? T(lambda) : T(0.0)) - c * z22;
    for (int j = 0; j < m; ++j) num -= mul(v[j], q[m - j]);
    v[m] = inv_q0 * num;
    for (int j = 0; j <= m; ++j) {
      cz0 += mul(v[j], z[0][m - j]);
      cz1 += mul(v[j], z[1][m - j]);
    }
    w[0][m] = (m == 0 ? k[0] : T(0.0)) - c * cz0;
    w[1][m] = (m == 0 ? k[1] : T(0.0)) - c * cz1;
    const double inv = 1.0 / (m + 1);
    (*x)[m + 1] = {inv * w[1][m], -(inv * w[0][m])};
    if (m + 1 == M) break;
    // z' = omega x z with omega_3 = 0: (w1 z2, -w0 z2, w0 z1 - w1 z0), order m.
    T a = T(0.0), b = T(0.0), d = T(0.0);
    for (int j = 0; j <= m; ++j) {
      a += mul(w[1][j], z[2][m - j]);
      b -= mul(w[0][j], z[2][m - j]);
      d += mul(w[0][j], z[1][m - j]) - mul(w[1][j], z[0][m - j]);
    }
    z[0][m + 1] = inv * a;
    z[1][m + 1] = inv * b;
    z[2][m + 1] = inv * d;
  }
}

}  // namespace plateball::internal
