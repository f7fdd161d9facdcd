// Internal: a bound on the rolling's deviation over a parameter box from the closed-form rolling,
// linear in the path length ("General targets: certified"; docs/paper_notes.md,
// "General targets: the rolling's deviation from the closed form").
//
// Q(0, L) = F(L) Rz(Psi) F(0)^T (elastica_closed_rolling.h), F = [f1 f2 u] the costate frame,
// u = v/V, f1 = e3 x u / |e3 x u|, Psi = psi(L) - psi(0) = -(V/2) [L + (1 - G^2) J],
// J = int_0^L ds / D, D = |v_h|^2 = 1 + G^2 - 2 G cos theta >= (1 - G)^2. The geodesic distance
// is bi-invariant, so between a point p of the box and its centre c
//   dist(Q(p), Q(c)) <= dist(F(L; p), F(L; c)) + |Psi(p) - Psi(c)| + dist(F(0; p), F(0; c)).
// - Each frame moves with v and v_h: |v(p) - v(c)| <= delta (CostateDeviationBound), so u turns
//   by at most asin(delta / |v(c)|) and f1 (v_h turned by -pi/2) by asin(delta / |v_h(c)|); f2 =
//   u x f1 moves by at most |du| + |df1|; a rotation whose columns move by d (Frobenius norm of the
//   difference) turns by 2 asin(d / (2 sqrt 2)), since |R - I|_F^2 = 8 sin^2(angle / 2).
// - |Psi(p) - Psi(c)| <= sum_i h_i sup |dPsi/dx_i| (TwistDerivativeBounds), each linear in L: the
//   phase and the periodic part of d/dk by differences of 1/D at the two ends, the rate's
//   s-weighted part by parts, the k's secular part through K_k/K, G and V by their derivatives.
// Near G = 1 the factor (1 + G)/|1 - G| blows up while Q stays smooth: the bound is +infinity when
// min |1 - G| over the box is below kMinUnitGap, and the certificate takes min(D, this bound).
#pragma once

#include <Eigen/Core>
#include <limits>

#include "certify/vocabulary.h"

namespace plateball::internal {

/// min over the box of |1 - G| below which the closed-form bounds are +infinity (G = rate^2
/// oscillating, (rate k)^2 rotating; 1/D <= 1/(1 - G)^2 enters them squared and cubed).
inline constexpr double kMinUnitGap = 1e-6;

/// Sup over the box of |dPsi/dx_i| for Psi = psi(L) - psi(0) (k_max < 1); every entry +infinity
/// when min |1 - G| over the box < kMinUnitGap.
CertifyPoint TwistDerivativeBounds(PendulumRegime regime, const CertifyBox& box);
/// Bound on |Psi(x) - Psi(centre)| over the box: sum of half-width x TwistDerivativeBounds.
double TwistDeviationBound(PendulumRegime regime, const CertifyBox& box);

/// Bound on the angle between the costate frames F(x) and F(centre) at one end when
/// |v(x) - v(centre)| <= delta, |v(centre)| = norm and |v_h(centre)| = norm_h (pi when it fails).
double FrameDeviationAngle(double delta, double norm, double norm_h);

/// Bound on the rotation distance between Q(0, L) of any point of the box and Q(0, Lc) of its
/// centre, from the closed form (above); margin added to each end's costate deviation. +infinity
/// when min |1 - G| over the box < kMinUnitGap, the centre is inadmissible, or the bound is not
/// below stop_above (then it stops as soon as a partial sum reaches it: the caller's D).
double ClosedRollingDeviationBound(PendulumRegime regime,
                                   const CertifyBox& box,
                                   double margin,
                                   double stop_above = std::numeric_limits<double>::infinity());

// ---------------------------------------------------------------------------------------------
// The theta/2 chart: a frame and twist that stay smooth through G = 1 (docs/paper_notes.md,
// "General targets: a rolling bound smooth through G = 1").
// With e = (-sin(theta/2), cos(theta/2), 0) (oscillating (-k sn, dn, 0), rotating (-sn, cn, 0)),
// c = <e, u> = (G - 1) cos(theta/2) / V, the frame Ft = [f1 u x f1 u], f1 = (e - c u)/|e - c u|,
// is defined wherever |e - c u|^2 = 1 - c^2 > 0 (always for rate != 0, and k > 0 oscillating), and
// Q(0, L) = Ft(L) Rz(Psit) Ft(0)^T with Psit = int_0^L phi(rate s + u0) ds,
//   phi(w) = -(V/2) [1 + (1 - G^2) S / ((1 - G)^2 S + 4 rate^2)],  S = sn^2(w, k)   (both regimes),
// bounded and smooth in (rate, k, w) for rate != 0, G = 1 included (there phi = -V/2).

/// The chart's frame Ft(s) on a path (CertifyElastica) and |e - <e, u> u| = sqrt(1 - c^2) (its
/// conditioning; `frame` is Ft when projection > 0).
struct ChartFrameAt {
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();
  double projection = 0.0;
  double costate_norm = 0.0;  // |v(s)| = V
};
ChartFrameAt ChartFrame(const Elastica& path, double s);

/// The chart's twist rate phi at arc length s of the path (formula above).
double ChartTwistRate(const Elastica& path, double s);

/// Sup over the box of |dPsit/dx_i| (derived in the notes: pointwise sups of the explicit
/// dependence, the rate's s-weighted and the k's secular parts by parts); +infinity when the box
/// meets rate 0 or k_max >= 1. Finite through G = 1.
CertifyPoint ChartTwistDerivativeBounds(PendulumRegime regime, const CertifyBox& box);
/// Bound on |Psit(x) - Psit(centre)| over the box: sum of half-width x ChartTwistDerivativeBounds.
double ChartTwistDeviationBound(PendulumRegime regime, const CertifyBox& box);

/// Bound on the angle between the chart frames Ft(x) and Ft(centre) at one end when
/// |v(x) - v(centre)| <= delta, |v(centre)| = norm, theta/2 moves by at most half_turn and the
/// centre's projection |e - c u| is `projection` (pi when it fails).
double ChartFrameDeviationAngle(double delta, double norm, double half_turn, double projection);

/// Bound on |theta(x)/2 - theta(centre)/2| at one end of the path over the box (heading bounds).
double HalfHeadingDeviationBound(PendulumRegime regime, const CertifyBox& box, bool at_end);

/// As ClosedRollingDeviationBound, in the theta/2 chart: +infinity when the box meets rate 0, the
/// centre is inadmissible, or the bound is not below stop_above; finite through G = 1.
double ChartRollingDeviationBound(PendulumRegime regime,
                                  const CertifyBox& box,
                                  double margin,
                                  double stop_above = std::numeric_limits<double>::infinity());

}  // namespace plateball::internal
