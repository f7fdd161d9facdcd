// Internal: fast Jacobi elliptic functions for the closed-form elastica (elastica.h).
#pragma once

#include <cmath>

namespace plateball::internal {

/// The arithmetic-geometric mean sequence of the modulus k (depends on k only): computed once
/// per elastica, it leaves the per-argument work of JacobiSnCnDn to one sincos and a short
/// descending recursion.
struct JacobiAgm {
  explicit JacobiAgm(double k = 0.0);
  double k = 0.0;
  double c = 1.0;  // final AGM value
  int levels = 0;  // index of the last level
  double em[16] = {}, en[16] = {};
};

/// sn(u, k), cn(u, k), dn(u, k) for 0 <= k < 1 (descending Landen / AGM; ~1e-15 accurate for
/// |u| up to a few periods; callers reduce u modulo 4K first). Finite for every finite u: below
/// |u| = kJacobiTinyArgument (where the recursion, which divides by sin(c u), would overflow for
/// |u| < ~1e-154) sn = u, cn = dn = 1, exact in double.
void JacobiSnCnDn(double u, double k, double* sn, double* cn, double* dn);
/// The same with the modulus' AGM sequence precomputed.
void JacobiSnCnDn(double u, const JacobiAgm& agm, double* sn, double* cn, double* dn);
constexpr double kJacobiTinyArgument = 1e-20;

/// Whether the integer-valued m (a count of half periods 2K) is odd: std::fmod(m, 2) != 0 without
/// the libm call (0.5 m is exact; every double beyond 2^53 is even).
inline bool IsOddInteger(double m) {
  const double half = 0.5 * m;
  return half != std::trunc(half);
}

/// 1 - x^2 as (1 - |x|)(1 + |x|): no cancellation near |x| = 1 (the complementary parameter
/// k'^2 = 1 - k^2 of a modulus near the separatrix; 1 - G near G = 1).
inline double OneMinusSquare(double x) {
  const double a = x < 0.0 ? -x : x;
  return (1.0 - a) * (1.0 + a);
}

// Legendre's integrals by Carlson's symmetric forms (DLMF 19.25.1, 19.25.5, 19.25.13; carlson.h),
// with the complementary parameter k'^2 = OneMinusSquare(k) and Delta(phi)^2 = cos^2 + k'^2 sin^2
// (never 1 - k^2 sin^2): relatively accurate to a few ulps up to the separatrix. Boost's
// ellint_1(k), ellint_d(k) and their incomplete forms subtract k^2 from 1 and lose ~1e-10 of K at
// k = 1 - 1e-8 (docs/paper_notes.md, "Elastica near the separatrix and at tiny arguments").
/// K(k) = R_F(0, k'^2, 1) = pi / (2 AGM(1, k')), |k| < 1.
double CompleteEllipticK(double k);
/// D(k) = (K - E) / k^2 = int_0^K sn^2 = R_D(0, k'^2, 1) / 3 (by the same AGM), |k| < 1.
double CompleteEllipticD(double k);
/// F(phi, k) for |phi| <= pi/2 from sin_phi, cos_phi (only cos_phi^2 enters) and kc2 = k'^2:
/// sin_phi R_F(cos^2, Delta^2, 1).
double EllipticFSinCos(double sin_phi, double cos_phi, double kc2);
/// D(phi, k) = int_0^phi sin^2 / Delta for |phi| <= pi/2, likewise: sin_phi^3 R_D(cos^2, Delta^2, 1) / 3.
double EllipticDSinCos(double sin_phi, double cos_phi, double kc2);

}  // namespace plateball::internal
