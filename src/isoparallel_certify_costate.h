// Internal: two exclusion tests for the certificate's branch and bound whose bounds grow only
// linearly in the path length (issue 15, "General targets: certified"; docs/paper_notes.md,
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
//    Over a box e_c moves by at most the angles through which vhat(0) and vhat(L) move (closed-form
//    derivatives of v in (rate, k, u) at each end, u1 = u0 + rate L) plus twice the chord's turn:
//    a box whose centre has a larger e_c holds no solution. No rolling is needed.
#pragma once

#include <Eigen/Core>

#include "isoparallel_certify.h"

namespace plateball::internal {

/// Sup over the box of |dc/dx_i| for x = (rate, k, u0, L) (derived above; k_max < 1).
CertifyPoint ChordDerivativeBounds(PendulumRegime regime, const CertifyBox& box);
/// Bound on |c(x) - c(centre)| over the box: sum of half-width x ChordDerivativeBounds.
double ChordDeviationBound(PendulumRegime regime, const CertifyBox& box);

/// Sup over the box of |dv/dx_i| for v at the start (at_end = false: v(u0)) or at the end
/// (v(u0 + rate L)) of the path (derived in the notes; k_max < 1).
CertifyPoint CostateDerivativeBounds(PendulumRegime regime, const CertifyBox& box, bool at_end);

/// The costate angle e_c at a parameter point: the angle between target B vhat(0) and B vhat(L),
/// B = RotationZ(goal_angle - arg c), v = ElasticaCostate (isoparallel_families.h; with heading_w
/// = pi/2 it is (sin theta, G - cos theta, theta')); zero at every solution. Also the chord and |v| (optional).
/// False for an inadmissible point (|k| >= 1, L <= 0, non-finite values).
struct CostateAngle {
  double angle = 0.0;
  double costate_norm = 0.0;  // |v(0)| (= |v(L)| along the path)
  double end_norm = 0.0;      // |v(L)| as evaluated
  Eigen::Vector2d chord = Eigen::Vector2d::Zero();
};
bool EvaluateCostateAngle(const CertifyTarget& target, PendulumRegime regime, const CertifyPoint& x, CostateAngle* out);

/// The bound on |e_c(x) - e_c(centre)| over the box given the centre's values and a bound
/// chord_deviation on |c(x) - c(centre)| (margin added to it); +infinity when the chord's turn
/// cannot be bounded (chord_deviation + margin >= |c(centre)|).
double CostateAngleDeviationBound(PendulumRegime regime, const CertifyBox& box, const CostateAngle& centre,
                                  double chord_deviation, double margin);

/// The costate test: true when no point of the box can be a solution (e_c(centre) exceeds its
/// deviation bound plus 3 margin). chord_deviation bounds |c(x) - c(centre)| over the box.
bool CostateExcludes(const CertifyTarget& target, PendulumRegime regime, const CertifyBox& box,
                     double chord_deviation, double margin);

}  // namespace plateball::internal
