// Internal: two exclusion tests for the certificate's branch and bound whose bounds grow only
// linearly in the path length ("General targets: certified"; docs/paper_notes.md,
// "General targets: closed-form chord bounds and the costate test").
//
// Parameters x = (rate, k, u0, L), v = rate s + u0, heading theta(v) (heading_w = pi/2), chord
// c = x(L) = int_0^L t, t = (cos theta, sin theta), n = (-sin theta, cos theta).
//
// 1. Chord bound. Since t' = rate theta_v n, the chord's parameter derivatives integrate by parts:
//      dc/du0 = (t(L) - t(0)) / rate,   dc/drate = (L t(L) - c) / rate,   dc/dL = t(L),
//      dc/dk  = int_0^L Theta_k n ds - (K_k/K) [u0 (t(L) - t(0)) / rate + L t(L) - c],
//    Theta_k = d theta/dk at a fixed number of periods (bounded in v; Jacobi's zeta),
//    K_k/K = k (1 - D/K) / k'^2. |L t(L) - c| <= int_0^L min(2, |rate| Mv sigma) d sigma, and
//    |t(L) - t(0)| <= min(2, |rate| Mv L): every bound is linear in L (the rate one ~ 2L/|rate|).
// 2. Costate test. The costate v(s) = (sin theta, G - cos theta, theta') (W = (0, G)) is carried
//    by the rolling, v(s) = Q(0, s) v(0). At a solution B Q(0, L) B^T = target, hence
//    target B v(0) = B v(L): the angle e_c between target B vhat(0) and B vhat(L) is zero.
//    Over a box vhat(0) and vhat(L) move by bounded angles (closed-form derivatives of v in
//    (rate, k, u) at each end, u1 = u0 + rate L), and beta = arg of B by at most the chord's turn:
//    a box where the centre's angle, minimised over that range of beta, exceeds the ends' angles
//    holds no solution. No rolling is needed.
#pragma once

#include <Eigen/Core>

#include "certify/vocabulary.h"

namespace plateball::internal {

/// The box's extremes of |rate| (rate_min = 0 when the box meets rate 0), k, |u0| and L.
struct BoxExtremes {
  double rate_min, rate_max, k_min, k_max, phase_max, length_max;
};
BoxExtremes ExtremesOf(const CertifyBox& box);

/// Sup over the box of |dc/dx_i| for x = (rate, k, u0, L) (derived above; k_max < 1).
CertifyPoint ChordDerivativeBounds(PendulumRegime regime, const CertifyBox& box);
/// Bound on |c(x) - c(centre)| over the box: sum of half-width x ChordDerivativeBounds.
double ChordDeviationBound(PendulumRegime regime, const CertifyBox& box);

/// Sup over the box of |dv/dx_i| for v at the start (at_end = false: v(u0)) or at the end
/// (v(u0 + rate L)) of the path (derived in the notes; k_max < 1).
CertifyPoint CostateDerivativeBounds(PendulumRegime regime, const CertifyBox& box, bool at_end);
/// Bound on |v(x) - v(centre)| over the box at one end: sum of half-width x CostateDerivativeBounds.
double CostateDeviationBound(PendulumRegime regime, const CertifyBox& box, bool at_end);

/// sup K_k / K over moduli in [k_min, k_max] (k_max < 1): the period's logarithmic change, the
/// factor of the secular part of d theta/dk = Theta_k - (K_k/K) v theta_v.
double PeriodLogSlope(double k_min, double k_max);

/// The costate angle e_c at a parameter point: the angle between target B vhat(0) and B vhat(L),
/// B = RotationZ(beta), beta = goal_angle - arg c, v = ElasticaCostate (isoparallel_families.h;
/// with heading_w = pi/2 it is (sin theta, G - cos theta, theta')); zero at every solution.
/// False for an inadmissible point (|k| >= 1, L <= 0, non-finite values).
struct CostateAngle {
  double angle = 0.0;
  double beta = 0.0;
  Eigen::Vector3d start = Eigen::Vector3d::Zero(), end = Eigen::Vector3d::Zero();  // v(0), v(L)
  Eigen::Vector2d chord = Eigen::Vector2d::Zero();
};
bool EvaluateCostateAngle(const CertifyTarget& target, PendulumRegime regime, const CertifyPoint& x, CostateAngle* out);

/// f(beta) = angle(target R(beta) v(0), R(beta) v(L)) at the centre's costates, R = RotationZ.
double CostateAngleAt(const CertifyTarget& target, const CostateAngle& centre, double beta);

/// A lower bound on min f(beta) over |beta - centre.beta| <= turn (turn >= pi: every beta):
/// samples of f on the interval minus Lambda times half their spacing, Lambda = |v_h(0)|/|v(0)| +
/// |v_h(L)|/|v(L)| >= f's Lipschitz constant (a rotation by d about e3 turns a vector w by at most
/// d |w_h|/|w|). At most 128 samples.
double MinCostateAngleOverTurn(const CertifyTarget& target, const CostateAngle& centre, double turn);

/// The bound on the angles through which vhat(0) and vhat(L) move over the box (their sum), from
/// CostateDerivativeBounds and the centre's |v| (a vector within delta of w, delta < |w|, makes an
/// angle of at most asin(delta/|w|) with it; pi otherwise); margin added to each delta.
double CostateEndsDeviationBound(PendulumRegime regime,
                                 const CertifyBox& box,
                                 const CostateAngle& centre,
                                 double margin);

/// The costate test: true when no point x of the box can be a solution. For every x,
/// e_c(x) >= f_centre(beta_x) - (the ends' deviation), and beta_x lies within
/// turn = asin((chord_deviation + margin)/|c(centre)|) of the centre's (every beta when
/// chord_deviation + margin >= |c(centre)|): excluded when MinCostateAngleOverTurn exceeds the
/// ends' deviation bound plus 3 margin. chord_deviation bounds |c(x) - c(centre)| over the box.
bool CostateExcludes(
    const CertifyTarget& target, PendulumRegime regime, const CertifyBox& box, double chord_deviation, double margin);

}  // namespace plateball::internal
