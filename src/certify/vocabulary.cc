#include "certify/vocabulary.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "check.h"
#include "elastica_closed_rolling.h"
#include "jacobi_elliptic.h"
#include "plateball/so3.h"
#include "rotation_trick.h"

namespace plateball::internal {

namespace {

// int_0^length min(alpha + beta s, cap) ds for alpha >= 0 and alpha + beta length >= 0.
double IntegralOfCappedLine(double alpha, double beta, double cap, double length) {
  if (alpha >= cap) return cap * length;
  const double s_cap = beta > 0.0 ? (cap - alpha) / beta : length;
  if (s_cap >= length) return alpha * length + 0.5 * beta * length * length;
  return alpha * s_cap + 0.5 * beta * s_cap * s_cap + cap * (length - s_cap);
}

}  // namespace

double PhasePeriod(PendulumRegime regime, double k) {
  const double kk = CompleteEllipticK(k);
  return regime == PendulumRegime::kOscillating ? 4.0 * kk : 2.0 * kk;
}

CertifyPoint CertifyBox::Centre() const {
  CertifyPoint c;
  for (int i = 0; i < 4; ++i) c[i] = 0.5 * (lo[i] + hi[i]);
  return c;
}

double ArgumentBound(const CertifyBox& box, double s) {
  double v = 0.0;
  for (double rate : {box.lo[kCertifyRate], box.hi[kCertifyRate]})
    for (double phase : {box.lo[kCertifyPhase], box.hi[kCertifyPhase]}) v = std::max(v, std::abs(rate * s + phase));
  return v;
}

double ArgumentBoundOver(const CertifyBox& box, double s_lo, double s_hi) {
  return std::max(ArgumentBound(box, s_lo), ArgumentBound(box, s_hi));
}

double EndArgumentBound(const CertifyBox& box) {
  return ArgumentBoundOver(box, box.lo[kCertifyLength], box.hi[kCertifyLength]);
}

double ArgumentChordSlope(const CertifyBox& box, double length) {
  return (ArgumentBound(box, length) - ArgumentBound(box, 0.0)) / length;
}

double HeadingRateBound(PendulumRegime regime, double k_max) {
  return regime == PendulumRegime::kOscillating ? 2.0 * k_max : 2.0;
}

double HeadingModulusFromAmplitude(PendulumRegime regime, double k_max, double am_k) {
  if (regime == PendulumRegime::kRotating) return 2.0 * am_k;  // theta = 2 am
  // theta = 2 asin(k sn): d theta/dk = 2 (sn + k cn d am/dk) / dn, dn >= k' and dn^2 = k'^2 + k^2 cn^2
  // >= k^2 cn^2. The two forms differ by 2 am_k (k/k' - 1): the choice depends on k_max only, so
  // the bound stays affine in am_k (the callers take slopes in v); ~1/k'^2 instead of ~1/k'^3 near 1.
  const double kp = std::sqrt((1.0 - k_max) * (1.0 + k_max));
  return k_max <= kp ? 2.0 * (1.0 + k_max * am_k) / kp : 2.0 * (1.0 / kp + am_k);
}

double JacobiZetaOverModulusBound(double k_min, double k_max) {
  const double by_slope = 0.5 * k_max * CompleteEllipticK(k_max);
  if (!(k_min > 0.0)) return by_slope;
  // E = K - k^2 D, decreasing in k; widened by 1e-12 relative for the rounding of K, D and the difference.
  const double e = CompleteEllipticK(k_min) - k_min * k_min * CompleteEllipticD(k_min);
  return std::min(by_slope, e * (1.0 + 1e-12) / k_min);
}

double HeadingModulusBound(PendulumRegime regime, double k_max, double v_max) {
  const double kp2 = (1.0 - k_max) * (1.0 + k_max);  // k'^2, decreasing in k: the sup is at k_max
  const double am_k = k_max * (0.5 + v_max) / kp2;   // sup |d am / dk|
  if (regime == PendulumRegime::kRotating) return 2.0 * am_k;
  // The oscillating form 2 (1 + k am_k) / k' of HeadingModulusFromAmplitude at every k: the zeta
  // form below takes the smaller one above k = 1/sqrt 2, and D the smaller of the two bounds; this
  // one stays as tests/certify/isoparallel_certify_tails_test.cc compares it with the separatrix bound.
  return 2.0 * (1.0 + k_max * am_k) / std::sqrt(kp2);
}

double HeadingModulusBoundByZeta(PendulumRegime regime, double k_min, double k_max, double v_max) {
  // d am/dk = [k sn cn - dn Z(v) / k] / k'^2 - dn v K'/K with K'/K = k (1 - D/K) / k'^2: k / k'^2
  // and K grow with k, 1 - D/K = <cos^2> under the weight (1 - k^2 sin^2)^(-1/2) decreases.
  if (!(k_max < 1.0)) return std::numeric_limits<double>::infinity();  // K(1) is infinite
  const double kp2 = (1.0 - k_max) * (1.0 + k_max);
  const double secular = 1.0 - CompleteEllipticD(k_min) / CompleteEllipticK(k_min);
  const double am_k = (0.5 * k_max + JacobiZetaOverModulusBound(k_min, k_max) + k_max * secular * v_max) / kp2;
  return HeadingModulusFromAmplitude(regime, k_max, am_k);
}

namespace {

// The deviation bound of a box for a bound mk0 + mk_slope (|v| - |u0|_max) on |d theta/dk| (the
// bounds are affine in v_max), and each axis' uncapped share (optional).
double DeviationForModulusBound(
    PendulumRegime regime, const CertifyBox& box, double mk0, double mk_slope, CertifyPoint* contributions) {
  const double k_max = box.hi[kCertifyModulus];
  const double length_max = box.hi[kCertifyLength];
  const double mv = HeadingRateBound(regime, k_max);
  const double hr = box.HalfWidth(kCertifyRate), hk = box.HalfWidth(kCertifyModulus);
  const double hu = box.HalfWidth(kCertifyPhase), hl = box.HalfWidth(kCertifyLength);
  // Mean value theorem on the segment from the centre: |g(s; p) - g(s; centre)| <= alpha + beta s.
  // |v| <= |u0|_max + slope s on [0, L_max] (the chord of the convex sup |v|; slope <= rate_max).
  const double slope = ArgumentChordSlope(box, length_max);
  const double alpha = hk * mk0, beta = hr * mv + hk * mk_slope * slope;
  // The phase either enters the heading bound (hu |d theta/dv|, over the whole length) or, at a
  // fixed rate, shifts the path along itself by du / rate: one rolling at each end, at most
  // 2 |du| / |rate| in rotation and in chord (rate_min = 0 when the box meets rate 0).
  const double rate_min = box.lo[kCertifyRate] > 0.0   ? box.lo[kCertifyRate]
                          : box.hi[kCertifyRate] < 0.0 ? -box.hi[kCertifyRate]
                                                       : 0.0;
  const double by_heading = IntegralOfCappedLine(alpha + hu * mv, beta, 2.0, length_max);
  const double by_shift =
      rate_min > 0.0 ? 2.0 * hu / rate_min + IntegralOfCappedLine(alpha, beta, 2.0, length_max) : by_heading;
  if (contributions != nullptr) {
    (*contributions)[kCertifyRate] = 0.5 * hr * mv * length_max * length_max;
    (*contributions)[kCertifyModulus] = hk * (mk0 * length_max + 0.5 * mk_slope * slope * length_max * length_max);
    (*contributions)[kCertifyPhase] =
        hu * (rate_min > 0.0 ? std::min(mv * length_max, 2.0 / rate_min) : mv * length_max);
    (*contributions)[kCertifyLength] = hl;
  }
  // |w1 - w2| = 2 |sin(dg / 2)| <= min(|dg|, 2); the extra length rolls at unit speed.
  return std::min(by_heading, by_shift) + hl;
}

}  // namespace

double RollingDeviationBound(PendulumRegime regime, const CertifyBox& box, CertifyPoint* contributions) {
  const double k_min = std::max(0.0, box.lo[kCertifyModulus]), k_max = box.hi[kCertifyModulus];
  const double phase_max = MaxAbs(box.lo[kCertifyPhase], box.hi[kCertifyPhase]);
  // d theta/dk is bounded by c1 + c2 |v| with |v| <= phase_max + slope s (two such bounds: at
  // fixed v, and through a fixed number of periods; both rigorous, the smaller D is kept).
  const double mk0 = HeadingModulusBound(regime, k_max, phase_max);
  const double mk_slope = HeadingModulusBound(regime, k_max, phase_max + 1.0) - mk0;
  const double zk0 = HeadingModulusBoundByZeta(regime, k_min, k_max, phase_max);
  const double zk_slope = HeadingModulusBoundByZeta(regime, k_min, k_max, phase_max + 1.0) - zk0;
  CertifyPoint share_v, share_z;
  const double by_v = DeviationForModulusBound(regime, box, mk0, mk_slope, &share_v);
  const double by_z = DeviationForModulusBound(regime, box, zk0, zk_slope, &share_z);
  if (contributions != nullptr) *contributions = by_v <= by_z ? share_v : share_z;
  return std::min(by_v, by_z);
}

double RollingDeviationBoundFor(PendulumRegime regime,
                                const CertifyBox& box,
                                double modulus_bound,
                                CertifyPoint* contributions) {
  return DeviationForModulusBound(regime, box, modulus_bound, 0.0, contributions);
}

CertifyTarget CertifyTargetOf(const IsoparallelProblem& problem) {
  CertifyTarget t;
  t.target = problem.goal_orientation * problem.start_orientation.transpose();
  const Eigen::Vector2d d = problem.goal - problem.start;
  t.radius = d.norm();
  t.goal_angle = std::atan2(d.y(), d.x());
  return t;
}

Elastica CertifyElastica(PendulumRegime regime, const CertifyPoint& x) {
  ElasticaParameters p;
  p.regime = regime;
  p.rate = x[kCertifyRate];
  p.modulus = x[kCertifyModulus];
  p.phase = x[kCertifyPhase];
  p.heading_w = M_PI / 2;
  return Elastica(p);
}

bool EvaluateCertifyResidual(const CertifyTarget& target,
                             PendulumRegime regime,
                             const CertifyPoint& x,
                             double /*max_step: the rolling is in closed form*/,
                             CertifyResidual* out) {
  const double length = x[kCertifyLength];
  if (!(std::abs(x[kCertifyModulus]) < 1.0) || !(length > 0.0) || !std::isfinite(x[kCertifyRate]) ||
      !std::isfinite(x[kCertifyPhase]) || !std::isfinite(length) ||
      !(std::abs(x[kCertifyRate]) <= ElasticaClosedRolling::kMaxRate) ||
      !std::isfinite(x[kCertifyRate] * length + x[kCertifyPhase]))
    return false;
  const Elastica e = CertifyElastica(regime, x);
  // The rolling in closed form (elastica_closed_rolling.h: ~1e-13, O(1) work at any length)
  // instead of a Magnus table with steps <= max_step (~1e-10, O(length / max_step)).
  const Eigen::Matrix3d rolling = ElasticaClosedRolling(e).Rolling(length);
  const Eigen::Vector2d chord = e.Position(length);
  out->chord_norm = chord.norm();
  out->chord_miss = out->chord_norm - target.radius;
  out->rotation = RotationTrickResidual(target.target, ChordTurn(target.goal_angle, chord), rolling).norm();
  return std::isfinite(out->rotation) && std::isfinite(out->chord_norm);
}

std::string ToString(BoxVerdict verdict) {
  switch (verdict) {
    case BoxVerdict::kNotRun:
      return "not run";
    case BoxVerdict::kExcludedByChord:
      return "excluded by chord";
    case BoxVerdict::kExcludedByRotation:
      return "excluded by rotation";
    case BoxVerdict::kExcludedByCostate:
      return "excluded by costate";
    case BoxVerdict::kUndecided:
      return "undecided";
  }
  return "unknown";
}

BoxVerdict TestBox(const CertifyResidual& centre, double deviation, double margin) {
  return TestBox(centre, deviation, deviation, margin);
}

double RotationSlack(const CertifyResidual& centre, double chord_deviation, double margin) {
  // The chord lies within Dc of the centre's: its direction turns by at most asin(Dc / |chord_c|),
  // B by as much, the conjugation B Q B^T by twice that; what is left bounds Q's own move.
  if (!(chord_deviation + margin < centre.chord_norm)) return -std::numeric_limits<double>::infinity();
  const double turn = std::asin((chord_deviation + margin) / centre.chord_norm);
  return centre.rotation - 2.0 * turn - 3.0 * margin;
}

BoxVerdict TestBox(const CertifyResidual& centre, double deviation, double chord_deviation, double margin) {
  // Every point of the box has | |chord| - |chord_c| | <= Dc, so | chord miss | >= |miss_c| - Dc.
  if (std::abs(centre.chord_miss) > chord_deviation + margin) return BoxVerdict::kExcludedByChord;
  // Q itself moves by at most D.
  if (deviation < RotationSlack(centre, chord_deviation, margin)) return BoxVerdict::kExcludedByRotation;
  return BoxVerdict::kUndecided;
}

std::string CertifyWindowOptions::Validate() const {
  static const char* kNames[4] = {"window.rate", "window.modulus", "window.phase", "window.length"};
  for (int i = 0; i < 4; ++i) {
    if (!(match[i] >= 0.0 && match[i] <= 1e3)) return InvalidValueMessage("match", match[i], "must be in [0, 1e3]");
    if (!std::isfinite(window.lo[i]) || !std::isfinite(window.hi[i]) || !(window.lo[i] <= window.hi[i]))
      return InvalidValueMessage(kNames[i], window.lo[i], "needs finite lo <= hi");
    if (std::abs(window.lo[i]) > 1e6 || std::abs(window.hi[i]) > 1e6)
      return InvalidValueMessage(kNames[i], MaxAbs(window.lo[i], window.hi[i]), "must be within [-1e6, 1e6]");
  }
  if (window.lo[kCertifyModulus] < 0.0 || window.hi[kCertifyModulus] > kMaxWindowModulus)
    return InvalidValueMessage("window.modulus", window.hi[kCertifyModulus], "must lie in [0, 1 - 1e-9]");
  if (window.lo[kCertifyLength] <= 0.0)
    return InvalidValueMessage("window.length", window.lo[kCertifyLength], "must be > 0");
  if (window.hi[kCertifyLength] > 1000.0)
    return InvalidValueMessage("window.length", window.hi[kCertifyLength], "must be <= 1000");
  if (!(max_boxes >= 1 && max_boxes <= 2000000000L))
    return InvalidValueMessage("max_boxes", max_boxes, "must be in [1, 2e9]");
  if (!(accept_deviation > 0.0 && accept_deviation <= 1.0))
    return InvalidValueMessage("accept_deviation", accept_deviation, "must be in (0, 1]");
  if (!(margin >= 0.0 && margin <= 1e-2)) return InvalidValueMessage("margin", margin, "must be in [0, 1e-2]");
  if (!(max_step >= 1e-4 && max_step <= 0.5))
    return InvalidValueMessage("max_step", max_step, "must be in [1e-4, 0.5]");
  if (!(first_order_deviation >= 0.0 && first_order_deviation <= 10.0))
    return InvalidValueMessage("first_order_deviation", first_order_deviation, "must be in [0, 10]");
  if (!(first_order_min_deviation >= 1e-14 && first_order_min_deviation <= 1.0))
    return InvalidValueMessage("first_order_min_deviation", first_order_min_deviation, "must be in [1e-14, 1]");
  if (!(log_modulus_split >= 0.0 && log_modulus_split <= 1.0))
    return InvalidValueMessage("log_modulus_split", log_modulus_split, "must be in [0, 1]");
  if (!(first_order_margin >= 0.0 && first_order_margin <= 1e-2))
    return InvalidValueMessage("first_order_margin", first_order_margin, "must be in [0, 1e-2]");
  return "";
}

double ModulusSplitPoint(double k_lo, double k_hi, double log_split) {
  const double arithmetic = 0.5 * (k_lo + k_hi);
  if (!(k_lo >= log_split && k_hi < 1.0)) return arithmetic;
  // k'^2 = (1 - k)(1 + k): 1 - k is exact (Sterbenz), so k' keeps its relative accuracy near k = 1.
  const double product = std::sqrt((1.0 - k_lo) * (1.0 + k_lo) * (1.0 - k_hi) * (1.0 + k_hi));  // k'_lo k'_hi
  const double geometric = std::sqrt(1.0 - product);
  return geometric > k_lo && geometric < k_hi ? geometric : arithmetic;
}

bool SamePath(PendulumRegime regime, const CertifyPoint& a, const CertifyPoint& b, double tolerance) {
  for (int axis : {kCertifyRate, kCertifyModulus, kCertifyLength})
    if (std::abs(a[axis] - b[axis]) > tolerance) return false;
  const double period = PhasePeriod(regime, a[kCertifyModulus]);
  const double d = std::abs(a[kCertifyPhase] - b[kCertifyPhase]);
  return std::min(d, std::abs(period - d)) <= tolerance;
}

CertifyPoint CanonicalSolution(const ElasticaParameters& parameters, double length) {
  const PendulumRegime regime = parameters.regime;
  const double k = std::abs(parameters.modulus);
  const double half = 0.5 * PhasePeriod(PendulumRegime::kOscillating, k);  // 2K
  double rate = parameters.rate, phase = parameters.phase;
  if (regime == PendulumRegime::kOscillating) {
    if (parameters.modulus < 0.0) phase += half;  // -k sn(v) = k sn(v + 2K)
    if (rate < 0.0) {                             // k sn(-b s + u) = k sn(b s - u + 2K)
      rate = -rate;
      phase = half - phase;
    }
  }
  const double period = PhasePeriod(regime, k);
  phase = std::fmod(phase, period);
  if (phase < 0.0) phase += period;
  return {rate, k, phase, length};
}

}  // namespace plateball::internal
