// Internal: Carlson's symmetric elliptic integrals R_F, R_D, R_J, R_C in double precision, by the
// duplication theorem and Carlson's series termination (B. C. Carlson, "Numerical computation of
// real or complex elliptic integrals", Numer. Algorithms 10 (1995) 13-26; DLMF 19.36.1-19.36.2),
// and the complete integrals K, D by the arithmetic-geometric mean (DLMF 19.8.1, 19.8.6).
//
// Written for the closed-form elastica (elastica.cc, elastica_closed_rolling.cc): no policy
// machinery, no argument checks beyond the documented preconditions, no pow; R_F and R_J of the
// same (x, y, z) share one duplication loop (CarlsonRFRJ: Legendre's Pi needs both); R_C(1, 1 + e)
// of R_J's sum by its Maclaurin series once |e| is small (after the first one or two duplications
// e shrinks by ~64 per step). Relative error a few ulps (tests/carlson_test.cc against Boost in
// 50-digit arithmetic; docs/paper_notes.md, "Carlson's integrals in double").
#pragma once

#include <algorithm>
#include <cmath>

namespace plateball::internal {

namespace carlson {

// Duplication stops once 4^-n max|A0 - x_i| <= tau |A_n|: then |X|, |Y|, |Z| (|P|) <= tau and the
// terms of degree >= 8 that the seventh-order series omits are below ~eps. tau = (3 eps)^(1/8)
// for R_F, (eps/4)^(1/8) / 1.2 for R_D, (eps/5)^(1/8) for R_J (Carlson 1995's r^(1/6) with the
// series carried two degrees further, as DLMF 19.36.1-19.36.2 and Boost.Math do).
constexpr double kInvTauF = 79.5917;   // (3 eps)^(-1/8) = 79.5916...
constexpr double kInvTauD = 129.021;   // 1.2 (eps/4)^(-1/8) = 129.0205...
constexpr double kInvTauJ = 110.5243;  // (eps/5)^(-1/8) = 110.5242...
// A safeguard only: from any positive doubles the duplication converges in <= ~30 steps
// (log(x_max / x_min) halves per step, then the spread shrinks by 4 per step).
constexpr int kMaxSteps = 64;

inline double Max3Abs(double a, double b, double c) { return std::max({std::abs(a), std::abs(b), std::abs(c)}); }

// A^(-1/2) times the seventh-order series of R_F in X, Y (Z = -X - Y) (DLMF 19.36.1).
inline double SeriesF(double x_dev, double y_dev, double a) {
  const double z_dev = -x_dev - y_dev;
  const double e2 = x_dev * y_dev - z_dev * z_dev, e3 = x_dev * y_dev * z_dev;
  return (1.0 + e3 * (1.0 / 14.0 + 3.0 * e3 / 104.0) +
          e2 * (-1.0 / 10.0 + e2 / 24.0 - 3.0 * e3 / 44.0 - 5.0 * e2 * e2 / 208.0 + e2 * e3 / 16.0)) /
         std::sqrt(a);
}

// The seventh-order series of R_J / R_D in the elementary symmetric functions E2..E5 of
// (X, Y, Z, P, P) (Carlson 1995, eq. (2.12); DLMF 19.36.2), without the factor A^(-3/2).
inline double SeriesJ(double e2, double e3, double e4, double e5) {
  return 1.0 - 3.0 * e2 / 14.0 + e3 / 6.0 + 9.0 * e2 * e2 / 88.0 - 3.0 * e4 / 22.0 - 9.0 * e2 * e3 / 52.0 +
         3.0 * e5 / 26.0 - e2 * e2 * e2 / 16.0 + 3.0 * e3 * e3 / 40.0 + 3.0 * e2 * e4 / 20.0 +
         45.0 * e2 * e2 * e3 / 272.0 - 9.0 * (e3 * e4 + e2 * e5) / 68.0;
}

}  // namespace carlson

/// R_C(1, 1 + e) = int_0^inf dt / (2 sqrt(t + 1) (t + 1 + e)) for e > -1 (DLMF 19.2.17-19.2.19:
/// atan(sqrt e) / sqrt e for e > 0, atanh(sqrt(-e)) / sqrt(-e) for e < 0), by its Maclaurin series
/// sum (-e)^j / (2j + 1) through j = 5 when |e| < 2e-3 (truncation < e^6 / 13 < 5e-18 relative).
inline double CarlsonRC1p(double e) {
  if (std::abs(e) < 2e-3)
    return 1.0 + e * (-1.0 / 3.0 + e * (1.0 / 5.0 + e * (-1.0 / 7.0 + e * (1.0 / 9.0 - e / 11.0))));
  if (e > 0.0) {
    const double r = std::sqrt(e);
    return std::atan(r) / r;
  }
  const double r = std::sqrt(-e);
  return std::atanh(r) / r;
}

/// R_F(x, y, z) = (1/2) int_0^inf dt / sqrt((t + x)(t + y)(t + z)) (DLMF 19.16.1) for finite
/// x, y, z >= 0 with at most one of them zero (the callers' ranges; not checked).
inline double CarlsonRF(double x, double y, double z) {
  double a = (x + y + z) / 3.0;
  const double a0 = a, dx = a0 - x, dy = a0 - y;
  const double q = carlson::kInvTauF * carlson::Max3Abs(dx, dy, a0 - z);
  double f = 1.0;  // 4^-n
  for (int n = 0; n < carlson::kMaxSteps && !(f * q < a); ++n) {
    const double rx = std::sqrt(x), ry = std::sqrt(y), rz = std::sqrt(z);
    const double lambda = rx * (ry + rz) + ry * rz;
    a = 0.25 * (a + lambda);
    x = 0.25 * (x + lambda);
    y = 0.25 * (y + lambda);
    z = 0.25 * (z + lambda);
    f *= 0.25;
  }
  return carlson::SeriesF(f * dx / a, f * dy / a, a);
}

/// R_D(x, y, z) = R_J(x, y, z, z) = (3/2) int_0^inf dt / (sqrt((t + x)(t + y)) (t + z)^(3/2))
/// (DLMF 19.16.5) for finite x, y >= 0 (not both zero) and z > 0 (not checked).
inline double CarlsonRD(double x, double y, double z) {
  double a = (x + y + 3.0 * z) / 5.0;
  const double a0 = a, dx = a0 - x, dy = a0 - y;
  const double q = carlson::kInvTauD * carlson::Max3Abs(dx, dy, a0 - z);
  double f = 1.0, sum = 0.0;
  for (int n = 0; n < carlson::kMaxSteps && !(f * q < a); ++n) {
    const double rx = std::sqrt(x), ry = std::sqrt(y), rz = std::sqrt(z);
    const double lambda = rx * (ry + rz) + ry * rz;
    sum += f / (rz * (z + lambda));
    a = 0.25 * (a + lambda);
    x = 0.25 * (x + lambda);
    y = 0.25 * (y + lambda);
    z = 0.25 * (z + lambda);
    f *= 0.25;
  }
  const double xd = f * dx / a, yd = f * dy / a, zd = -(xd + yd) / 3.0;
  const double xy = xd * yd, z2 = zd * zd;
  const double e2 = xy - 6.0 * z2, e3 = (3.0 * xy - 8.0 * z2) * zd, e4 = 3.0 * (xy - z2) * z2, e5 = xy * z2 * zd;
  return f * carlson::SeriesJ(e2, e3, e4, e5) / (a * std::sqrt(a)) + 3.0 * sum;
}

/// R_F(x, y, z) and R_J(x, y, z, p) (DLMF 19.16.2) of the same x, y, z from one duplication loop
/// (the two share x_n, y_n, z_n and lambda_n; R_J adds p_n). Preconditions (not checked): finite
/// x, y, z >= 0, at most one zero, p > 0. Relative accuracy a few ulps when
/// e_0 = prod (p - x_i) / (sqrt p + sqrt x_i)^2 = prod (sqrt p - sqrt x_i) / (sqrt p + sqrt x_i)
/// is >= -1/2. e_0 >= 0 whenever p exceeds all of x, y, z or exactly one of them (the closed
/// rolling's x = cn^2 <= p <= y = dn^2 <= z = 1, so there every e_n >= 0); e_0 -> -1 needs p far
/// below one or three of them and far above the others, and loses digits to 1 + e_0.
struct CarlsonFJ {
  double rf, rj;
};
inline CarlsonFJ CarlsonRFRJ(double x, double y, double z, double p) {
  double af = (x + y + z) / 3.0, aj = (x + y + z + 2.0 * p) / 5.0;
  const double af0 = af, aj0 = aj, fdx = af0 - x, fdy = af0 - y, jdx = aj0 - x, jdy = aj0 - y, jdz = aj0 - z;
  const double qf = carlson::kInvTauF * carlson::Max3Abs(fdx, fdy, af0 - z);
  const double qj = carlson::kInvTauJ * std::max(carlson::Max3Abs(jdx, jdy, jdz), std::abs(aj0 - p));
  // p_n - x_n = (p - x) / 4^n exactly (Carlson's delta_n = delta_0 / 64^n, one factor at a time:
  // the product (p - x)(p - y)(p - z) underflows for p ~ 1e-308, and its quotient by d^2 would not).
  const double px = p - x, py = p - y, pz = p - z;
  double f = 1.0, sum = 0.0;
  for (int n = 0; n < carlson::kMaxSteps && !(f * qf < af && f * qj < aj); ++n) {
    const double rx = std::sqrt(x), ry = std::sqrt(y), rz = std::sqrt(z), rp = std::sqrt(p);
    const double tx = rp + rx, ty = rp + ry, tz = rp + rz, inv_d = 1.0 / (tx * ty * tz);
    // e_n = prod (p_n - x_n) / (sqrt p_n + sqrt x_n)^2, each quotient sqrt p_n - sqrt x_n.
    const double e = f * px / tx * inv_d * (f * py / ty) * (f * pz / tz);
    sum += f * inv_d * CarlsonRC1p(e);
    const double lambda = rx * (ry + rz) + ry * rz;
    af = 0.25 * (af + lambda);
    aj = 0.25 * (aj + lambda);
    x = 0.25 * (x + lambda);
    y = 0.25 * (y + lambda);
    z = 0.25 * (z + lambda);
    p = 0.25 * (p + lambda);
    f *= 0.25;
  }
  CarlsonFJ out;
  out.rf = carlson::SeriesF(f * fdx / af, f * fdy / af, af);
  const double xd = f * jdx / aj, yd = f * jdy / aj, zd = f * jdz / aj, pd = -0.5 * (xd + yd + zd);
  const double xyz = xd * yd * zd, pd2 = pd * pd;
  const double e2 = xd * yd + xd * zd + yd * zd - 3.0 * pd2;
  const double e3 = xyz + 2.0 * e2 * pd + 4.0 * pd2 * pd;
  const double e4 = (2.0 * xyz + e2 * pd + 3.0 * pd2 * pd) * pd;
  const double e5 = xyz * pd2;
  out.rj = f * carlson::SeriesJ(e2, e3, e4, e5) / (aj * std::sqrt(aj)) + 6.0 * sum;
  return out;
}

/// R_J(x, y, z, p) alone (the preconditions and accuracy of CarlsonRFRJ).
inline double CarlsonRJ(double x, double y, double z, double p) { return CarlsonRFRJ(x, y, z, p).rj; }

/// The complete integrals from the modulus k in [0, 1) and its complement kc = k' = sqrt(1 - k^2)
/// (both passed: near k = 0 and k = 1 neither is formed from the other by a subtraction):
/// K = R_F(0, kc^2, 1) = pi / (2 AGM(1, kc)) (DLMF 19.8.5) and
/// D = (K - E) / k^2 = R_D(0, kc^2, 1) / 3 = K (1/2 + sum_{n >= 1} 2^(n-1) (c_n / k)^2) (DLMF 19.8.6,
/// c_n = (a_(n-1) - b_(n-1)) / 2 = c_(n-1)^2 / (4 a_n): every term positive, no cancellation).
/// kc = 0 (the separatrix) gives K = D = +infinity.
struct CompleteKD {
  double k, d;
};
inline CompleteKD CompleteEllipticKD(double k, double kc) {
  if (kc == 0.0) return {HUGE_VAL, HUGE_VAL};  // the separatrix: K and D infinite
  // a, b = a_(n-1), b_(n-1) at the top of step n >= 1; t = t_n = c_n / k with t_1 = k / (2 (1 + kc)),
  // t_(n+1) = k t_n^2 / (4 a_(n+1)); weight = 2^(n-1).
  double a = 1.0, b = kc, t = k / (2.0 * (1.0 + kc)), weight = 1.0, sum = 0.5;
  for (int n = 0; n < carlson::kMaxSteps; ++n) {
    sum += weight * t * t;
    const double a_next = 0.5 * (a + b);
    b = std::sqrt(a * b);
    a = a_next;
    t = k * t * t / (2.0 * (a + b));
    weight *= 2.0;
    // 2.7 sqrt(eps): the next mean (a + b) / 2 is the AGM to (a - b)^2 / (8 a) < eps a.
    if (std::abs(a - b) < 2.7 * 1.4901161193847656e-08 * a && weight * t * t < 1e-17 * sum) break;
  }
  const double kk = M_PI / (a + b);
  return {kk, kk * sum};
}

}  // namespace plateball::internal
