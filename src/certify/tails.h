// Internal: the tails of the certified exclusion for general isoparallel targets
// (docs/paper_notes.md, "General targets: the tails of the certificate window").
//
// The branch and bound of certify/window.h covers a BOUNDED window of elastica parameters.
// This file bounds the large-rate tail rigorously (an averaging lemma):
//
//   for an elastica with heading period P in arc length (x(s + P) = x(s) + c_P), rolled over
//   [0, L] with chord c = x(L) - x(0),
//     angle(Q(0, L), exp(hat(e3 x c))) <= 2 asin(min(1, B / 2)),
//     B = diam(p) (sqrt(L^2 - |c|^2) + |c|),   p(s) = x(s) - s c_P / P (P-periodic).
//
// diam(p) <= PeriodicPartDiameter(regime, k) / |a|: the smaller of half the length of the closed
// curve p (PeriodicPartLength: the Cauchy-Schwarz form P sqrt(1 - rho^2), rho = |c_P| / P, which
// grows like sqrt K, and triangle forms int |x' - t| + P |t - c_P / P| for t = +-(drift
// direction)) and the diagonal of the box holding p (Jacobi's zeta); all but Cauchy-Schwarz stay
// bounded up to k = 1.
// A solution of the rotation trick has |c| = |x1 - x0|, so its residual differs from the straight
// segment's residual delta0 = angle(target^T exp(hat(e3 x (x1 - x0)))) by at most that bound:
// no solution of length <= cap has a rate above
//   a_max(k) = PeriodicPartDiameter(regime, k) h / (2 sin(delta / 2)),
// h = sqrt(cap^2 - |x1 - x0|^2) + |x1 - x0|, delta = delta0 - margin; finite for every k <= 1
// (the separatrix as a limit). When delta0 <= margin (the target is the straight rolling, or
// nearly) nothing is excluded. The pieces below these rates: certify/coverage.h.
#pragma once

#include <string>
#include <vector>

#include "certify/vocabulary.h"
#include "plateball/elastica.h"

namespace plateball::internal {

/// The straight segment's residual delta0 = angle(target^T exp(hat(e3 x (x1 - x0)))): the
/// rotation trick applied to rolling straight along x1 - x0.
double StraightResidual(const CertifyTarget& target);

/// sqrt(1 - rho^2) for the drift ratio rho = |chord over one heading period| / period length of
/// an elastica of modulus k in [0, 1): oscillating 2 k sqrt(D E) / K, rotating 2 sqrt(D (K - D)) / K
/// (D = (K - E) / k^2). 0 for the straight line (oscillating, k = 0).
double DriftDeficit(PendulumRegime regime, double k);

/// A bound on the length of the closed curve p(s) = x(s) - s c_P / P over one heading period,
/// int_0^P |x' - c_P / P| ds, in units of v = a s + u0 (divide by |a| for arc length), for a
/// modulus k in [0, 1] (k = 1 the limit at the separatrix). The smallest of
///   Cauchy-Schwarz   n K sqrt(1 - rho^2) (n K = PhasePeriod, sqrt(1 - rho^2) = DriftDeficit);
///   rotating, t at theta = pi:     4 asin(k) / k + 4 (K - D)   (2 |cn| integrated; 2K (1 + rho));
///   oscillating, t at theta = pi:  4 pi + 8 E                  (2 dn integrated; 4K (1 + rho));
///   oscillating, t at theta = 0:   8 atanh(k) + 8 (K - E)      (2k |sn| integrated; 4K (1 - rho));
/// (|x' - t| = 2 |sin((theta - theta_t) / 2)|, rho signed = mean of cos theta). At k = 1: rotating
/// 2 pi + 4, oscillating 4 pi + 8 (two loops per period).
double PeriodicPartLength(PendulumRegime regime, double k);
/// A rigorous sup of PeriodicPartLength over moduli in [k_lo, k_hi], 0 <= k_lo <= k_hi <= 1: the
/// largest over 16 pieces (uniform in log(1 - k)) of the smallest form's sup on the piece: the
/// Cauchy-Schwarz form with K at the piece's top and its smallest |rho| (infinite up to k = 1);
/// the forms increasing in k (rotating; oscillating at theta = 0) at the top, the decreasing one
/// (oscillating at theta = pi, E decreasing) at the bottom.
double PeriodicPartLengthOver(PendulumRegime regime, double k_lo, double k_hi);

/// A bound on the diameter of p(s) = x(s) - s c_P / P (v units; divide by |a|), k in [0, 1]: the
/// smaller of PeriodicPartLength / 2 (a closed curve's diameter is at most half its length) and
/// the diagonal of the box holding p in the frame of the drift direction e:
///   rotating     p_e = 2 Z(v) / k^2, p_perp = -2 dn / k^2:  hypot(4 Z_max / k^2, 2 / (1 + k'));
///   oscillating  p_e = 2 Z(v),       p_perp = -2k cn:       hypot(4 Z_max, 4k);
/// Z = E(am v) - (E/K) v Jacobi's zeta, Z_max its max (where dn^2 = E/K). At k = 1 (Z = tanh):
/// sqrt 20 = 4.47 rotating, sqrt 32 = 5.66 oscillating.
double PeriodicPartDiameter(PendulumRegime regime, double k);
/// A rigorous sup of PeriodicPartDiameter over [k_lo, k_hi], k_hi <= 1 allowed: by pieces as
/// PeriodicPartLengthOver, Z_max bounded on [a, b] by E(phi, a) - (E/K)(b) F(phi, a) maximised
/// over phi (E(phi, .), E/K decrease and F(phi, .) increases with k), the perpendicular range at b.
double PeriodicPartDiameterOver(PendulumRegime regime, double k_lo, double k_hi);

/// The averaging bound: the rotation angle between Q(0, L) and the straight rolling
/// exp(hat(e3 x c)) along the chord, for a periodic path whose periodic part has diameter at most
/// `diameter` (arc length: PeriodicPartDiameter / |rate|), of length L and chord |c| <= L:
/// 2 asin(min(1, B / 2)), B = diameter (sqrt(L^2 - |c|^2) + |c|). +inf for an infinite diameter.
double AveragingDeviationBound(double diameter, double length, double chord);

/// The straight-run bound: a path whose heading stays within eta (<= pi/2) of one direction over
/// [0, L] rolls to within 2 asin(min(1, B / 2)) of exp(hat(e3 x c)), B = (mu L^2 / 2)(2 mu + |c| / L),
/// mu = 2 sin(eta / 2). (Near the separatrix the runs between loops are such paths.)
double StraightRunDeviationBound(double eta, double length, double chord);

/// sup |d theta/dk| at fixed v over moduli in [0, k_max] (k_max <= 1: uniform up to the
/// separatrix) and |v| <= v_max, v measured from a loop centre (theta(0) = 0):
/// |d am/dk| <= k (cosh v - 1) (the bracket of d am/dk solves J' = sn M, M' = k^2 sn J - k'^2 cn),
/// rotating 2 k (cosh v - 1); oscillating 2 (1 + k^2 (cosh v - 1)) / dn with dn >= max(k', sech v).
double HeadingModulusBoundNearSeparatrix(PendulumRegime regime, double k_max, double v_max);

/// One loop near the separatrix: for 0 <= v <= K(k), |theta_k(v) - theta_1(v)| <= the gap,
/// theta_1 = 2 gd(v) the separatrix (odd in v).
///   rotating:    0 <= theta_k - theta_1 <= min(k'^2 (cosh v - 1), 2 asin(sech v)) (a rotation is
///                faster than the separatrix at equal angle, and theta_k <= pi on [0, K]);
///   oscillating: 0 <= theta_1 - theta_k <= min(2 (1 - k) cosh^2 v, 2 acos(k tanh v)) (slower;
///                sn >= tanh v).
/// The sup over all v >= 0 (rotating ~sqrt(2) k', oscillating ~k'^(2/3)) bounds the gap for every
/// modulus in [k, 1): one loop of an elastica is the separatrix loop within it in heading.
double SeparatrixHeadingGap(PendulumRegime regime, double k, double v);
double SeparatrixHeadingGapSup(PendulumRegime regime, double k);
/// The growing side of the gap alone (k'^2 (cosh v - 1) rotating, 2 (1 - k) cosh^2 v oscillating):
/// increasing in |v| and decreasing in k, so for |v| <= v_max <= K(k) and every modulus in [k, 1)
/// the gap is at most its value at (k, v_max).
double SeparatrixHeadingGapGrowing(PendulumRegime regime, double k, double v);

/// a_max(k): no solution of length <= cap (chord |x1 - x0|) has |rate| > a_max at modulus k in
/// [0, 1] (k = 1 the limit). +inf when StraightResidual(target) <= margin (the lemma excludes
/// nothing then) or k is not in [0, 1].
double MaxSolutionRate(const CertifyTarget& target, PendulumRegime regime, double k, double cap, double margin);
/// A rigorous sup of MaxSolutionRate over moduli in [k_lo, k_hi], k_hi <= 1 allowed
/// (PeriodicPartDiameterOver): finite up to the separatrix.
double MaxSolutionRateOver(
    const CertifyTarget& target, PendulumRegime regime, double k_lo, double k_hi, double cap, double margin);

}  // namespace plateball::internal
