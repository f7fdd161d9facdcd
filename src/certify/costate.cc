#include "certify/costate.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "jacobi_elliptic.h"
#include "plateball/isoparallel_families.h"
#include "plateball/so3.h"

namespace plateball::internal {

namespace {

// int_0^length min(2, slope sigma) d sigma: a bound on |length t(length) - c| when the heading
// moves by at most slope per unit length (|t(L) - t(s)| = 2 |sin(dtheta / 2)| <= min(2, |dtheta|)).
double CappedTurn(double slope, double length) {
  if (slope * length <= 2.0) return 0.5 * slope * length * length;
  return 2.0 * length - 2.0 / slope;
}

// 1 - D/K at k (D = (K - E)/k^2): the secular factor of K_k/K = k (1 - D/K)/k'^2, decreasing in k.
double SecularFactor(double k) { return 1.0 - CompleteEllipticD(k) / CompleteEllipticK(k); }

// sup |d am/dk| at fixed v over [k_min, k_max] and |v| <= v_max: the smaller of the fixed-v form
// k (1/2 + |v|)/k'^2 and the zeta form k ((1 + K)/2 + (1 - D/K) |v|)/k'^2 (certify/vocabulary.h).
double AmplitudeModulusBound(double k_min, double k_max, double v_max) {
  const double kp2 = (1.0 - k_max) * (1.0 + k_max);
  const double by_v = k_max * (0.5 + v_max) / kp2;
  const double by_zeta = k_max * (0.5 * (1.0 + CompleteEllipticK(k_max)) + SecularFactor(k_min) * v_max) / kp2;
  return std::min(by_v, by_zeta);
}

// |dc/du0| <= min(2 / |rate|, Mv L) (the chord of a shifted path moves by |t(L) - t(0)| / |rate|).
double PhaseShiftBound(const BoxExtremes& b, double mv) {
  const double by_heading = mv * b.length_max;
  return b.rate_min > 0.0 ? std::min(2.0 / b.rate_min, by_heading) : by_heading;
}

}  // namespace

BoxExtremes ExtremesOf(const CertifyBox& box) {
  const double rlo = box.lo[kCertifyRate], rhi = box.hi[kCertifyRate];
  BoxExtremes b;
  b.rate_min = rlo > 0.0 ? rlo : rhi < 0.0 ? -rhi : 0.0;
  b.rate_max = std::max(std::abs(rlo), std::abs(rhi));
  b.k_min = std::max(0.0, box.lo[kCertifyModulus]);
  b.k_max = box.hi[kCertifyModulus];
  b.phase_max = std::max(std::abs(box.lo[kCertifyPhase]), std::abs(box.hi[kCertifyPhase]));
  b.length_max = box.hi[kCertifyLength];
  return b;
}

// sup K_k / K over [k_min, k_max]: k/k'^2 increases, 1 - D/K decreases.
double PeriodLogSlope(double k_min, double k_max) {
  return k_max * SecularFactor(k_min) / ((1.0 - k_max) * (1.0 + k_max));
}

CertifyPoint ChordDerivativeBounds(PendulumRegime regime, const CertifyBox& box) {
  const BoxExtremes b = ExtremesOf(box);
  const double mv = HeadingRateBound(regime, b.k_max);
  CertifyPoint d;
  d[kCertifyPhase] = PhaseShiftBound(b, mv);
  // |L t(L) - c| / |rate| <= CappedTurn(|rate| Mv, L) / |rate|, non-increasing in |rate|.
  d[kCertifyRate] = b.rate_min > 0.0 ? CappedTurn(b.rate_min * mv, b.length_max) / b.rate_min
                                     : 0.5 * mv * b.length_max * b.length_max;
  // int |Theta_k| <= L sup |Theta_k| (zeta form at v = 0: no secular term), plus K_k/K times
  // |u0| |t(L) - t(0)| / |rate| + |L t(L) - c|.
  const double theta_k_w = HeadingModulusBoundByZeta(regime, b.k_min, b.k_max, 0.0);
  const double secular = b.phase_max * d[kCertifyPhase] + CappedTurn(b.rate_max * mv, b.length_max);
  d[kCertifyModulus] = b.length_max * theta_k_w + PeriodLogSlope(b.k_min, b.k_max) * secular;
  d[kCertifyLength] = 1.0;  // |t(L)|
  return d;
}

double ChordDeviationBound(PendulumRegime regime, const CertifyBox& box) {
  const CertifyPoint d = ChordDerivativeBounds(regime, box);
  double sum = 0.0;
  for (int i = 0; i < 4; ++i) sum += box.HalfWidth(i) * d[i];
  return sum;
}

CertifyPoint CostateDerivativeBounds(PendulumRegime regime, const CertifyBox& box, bool at_end) {
  const BoxExtremes b = ExtremesOf(box);
  const bool oscillating = regime == PendulumRegime::kOscillating;
  const double k = b.k_max, kp = std::sqrt((1.0 - k) * (1.0 + k)), r = b.rate_max;
  const double u_max = at_end ? EndArgumentBound(box) : b.phase_max;
  // In u at fixed (rate, k): (cos theta, sin theta) theta_v and rate theta_vv, |theta_vv| <= 2k
  // (oscillating, theta_v = 2k cn) or k^2 (rotating, theta_v = 2 dn).
  const double mv = HeadingRateBound(regime, k);
  const double du = std::hypot(mv, r * (oscillating ? 2.0 * k : k * k));
  // In the rate at fixed (k, u): G = b^2, theta' = 2 k b cn (oscillating); G = a^2 k^2,
  // theta' = 2 a dn (rotating).
  const double dr = oscillating ? std::hypot(2.0 * r, 2.0 * k) : std::hypot(2.0 * r * k * k, 2.0);
  // In k at fixed (rate, u): |am_k| <= A; oscillating theta_k = 2 (sn + k cn am_k)/dn (dn >= k'),
  // theta'_k = 2 b (cn - k sn am_k); rotating theta_k = 2 am_k, G_k = 2 a^2 k,
  // theta'_k = 2 a dn_k with |dn_k| = |k sn^2 + k^2 sn cn am_k| / dn <= (k + k^2 A)/k'.
  const double a = AmplitudeModulusBound(b.k_min, k, u_max);
  const double dk = oscillating ? std::hypot(2.0 * (1.0 + k * a) / kp, 2.0 * r * (1.0 + k * a))
                                : std::hypot(2.0 * a + 2.0 * r * r * k, 2.0 * r * (k + k * k * a) / kp);
  CertifyPoint d;
  d[kCertifyModulus] = dk;
  if (!at_end) {
    d[kCertifyRate] = dr;
    d[kCertifyPhase] = du;
    d[kCertifyLength] = 0.0;
  } else {  // u1 = u0 + rate L: du1/drate = L, du1/du0 = 1, du1/dL = rate
    d[kCertifyRate] = dr + b.length_max * du;
    d[kCertifyPhase] = du;
    d[kCertifyLength] = r * du;
  }
  return d;
}

double CostateDeviationBound(PendulumRegime regime, const CertifyBox& box, bool at_end) {
  const CertifyPoint d = CostateDerivativeBounds(regime, box, at_end);
  double sum = 0.0;
  for (int i = 0; i < 4; ++i) sum += box.HalfWidth(i) * d[i];
  return sum;
}

bool EvaluateCostateAngle(const CertifyTarget& target,
                          PendulumRegime regime,
                          const CertifyPoint& x,
                          CostateAngle* out) {
  const double length = x[kCertifyLength];
  for (double value : x)
    if (!std::isfinite(value)) return false;
  if (!(std::abs(x[kCertifyModulus]) < 1.0) || !(length > 0.0)) return false;
  const Elastica path = CertifyElastica(regime, x);
  out->chord = path.Position(length);
  out->start = ElasticaCostate(path, 0.0);
  out->end = ElasticaCostate(path, length);
  out->beta = target.goal_angle - std::atan2(out->chord.y(), out->chord.x());
  out->angle = CostateAngleAt(target, *out, out->beta);
  return std::isfinite(out->angle) && std::isfinite(out->chord.norm());
}

double CostateAngleAt(const CertifyTarget& target, const CostateAngle& centre, double beta) {
  const Eigen::Matrix3d b = RotationZ(beta);
  const Eigen::Vector3d p = target.target * b * centre.start, q = b * centre.end;
  return std::atan2(p.cross(q).norm(), p.dot(q));
}

double MinCostateAngleOverTurn(const CertifyTarget& target, const CostateAngle& centre, double turn) {
  const auto flat = [](const Eigen::Vector3d& w) { return w.head<2>().norm() / w.norm(); };
  const double lipschitz = flat(centre.start) + flat(centre.end);
  const double width = 2.0 * std::min(turn, M_PI);
  const int samples = static_cast<int>(std::clamp(std::ceil(lipschitz * width / 0.02), 1.0, 128.0));
  const double spacing = width / samples;  // sample midpoints: every beta within spacing/2 of one
  double least = M_PI;
  for (int i = 0; i < samples; ++i)
    least = std::min(least, CostateAngleAt(target, centre, centre.beta - 0.5 * width + (i + 0.5) * spacing));
  return least - 0.5 * lipschitz * spacing;
}

double CostateEndsDeviationBound(PendulumRegime regime,
                                 const CertifyBox& box,
                                 const CostateAngle& centre,
                                 double margin) {
  const auto end_angle = [&](bool at_end, double norm) {
    const double delta = margin + CostateDeviationBound(regime, box, at_end);
    return delta < norm ? std::asin(delta / norm) : M_PI;
  };
  return end_angle(false, centre.start.norm()) + end_angle(true, centre.end.norm());
}

bool CostateExcludes(
    const CertifyTarget& target, PendulumRegime regime, const CertifyBox& box, double chord_deviation, double margin) {
  CostateAngle centre;
  if (!EvaluateCostateAngle(target, regime, box.Centre(), &centre)) return false;
  const double ends = CostateEndsDeviationBound(regime, box, centre, margin);
  if (!(centre.angle > ends + 3.0 * margin)) return false;  // no beta does better than the centre's
  const double chord_norm = centre.chord.norm();
  const double turn = chord_deviation + margin < chord_norm ? std::asin((chord_deviation + margin) / chord_norm) : M_PI;
  return MinCostateAngleOverTurn(target, centre, turn) > ends + 3.0 * margin;
}

}  // namespace plateball::internal
