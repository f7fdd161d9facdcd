// Internal: a centred (second-order) bound on the rolling's move over a parameter box
// (docs/paper_notes.md, "General targets: a centred form of the rolling bound").
//
// For p in the box collapsed to L = Lc, E(s) = Q_p(s) Q_c(s)^T solves E' = E hat(z), z(s) =
// Q_c(s) (w_p(s) - w_c(s)), w = (-sin g, cos g, 0) the angular velocity of heading g. With
// Z(p) = int_0^Lc z ds and Lambda >= int_0^Lc |z| ds (the zeroth-order line of D):
//   dist(E(Lc), exp hat(Z)) <= Rm = Lambda^2 / 4      (|dexp_X - I| = |e^{it} - 1 - it| / t <= t/2, t = |X|);
//   Z(p) = M (p - c) + r,  |r| <= R2 = int [eps^2 / 2 + (1/2) sup |d^T H_g d|] ds,
// M the rolling's exact first derivative at the centre (never formed), eps(s) the first-order bound
// on |g_p - g_c| and H_g the Hessian of the heading in (rate, k, u0) (HeadingSecondDerivativeBounds).
// |M d| is convex in d, so its sup over the box is at a vertex d_j, where |M d_j| <= min(|Z(c + d_j)|,
// |Z(c - d_j)|) + R2 and |Z| <= angle(E) + Rm (Lambda < pi): with the closed-form rolling at the
// vertices,
//   dist(Q(p), Q(c)) <= max_j min_+- dist(Q(c +- d_j), Q(c)) + 2 Rm + 2 R2 + h_L,
// i.e. the largest rotation distance at the vertices plus a second-order term: the first-order
// cancellations between the frames at both ends and the twist are seen exactly.
#pragma once

#include <limits>

#include "certify/vocabulary.h"

namespace plateball::internal {

/// Bound 2 Rm + 2 R2 (above) on the box collapsed to L = Lc; with collapse_phase also to u0 =
/// u0_c (then d has no phase part). +infinity when Lambda >= pi or k_max >= 1.
double CentredRemainderBound(PendulumRegime regime, const CertifyBox& box, bool collapse_phase);

/// Bound on the rotation distance between Q(0, L) of any point of the box and Q(0, Lc) of its
/// centre: the smaller of the centred form over (rate, k, u0) and, when the rate keeps one sign,
/// over (rate, k) plus the phase shift 2 h_u / |rate|_min; + h_L, + 2 margin for the closed-form
/// rollings' error. +infinity when no form is finite or below stop_above (it stops as soon as a
/// form's remainder reaches it).
double CentredRollingDeviationBound(PendulumRegime regime,
                                    const CertifyBox& box,
                                    double margin,
                                    double stop_above = std::numeric_limits<double>::infinity());

}  // namespace plateball::internal
