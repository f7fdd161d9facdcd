#include "certify/centred.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "certify/jacobian.h"
#include "elastica_closed_rolling.h"
#include "plateball/so3.h"

namespace plateball::internal {

namespace {

// Pieces of [0, Lc] for the Hessian term's upper Riemann sum (each piece at the sup of its integrand).
constexpr int kHessianPieces = 16;

// The smallest |rate| over the box (0 when it meets rate 0).
double RateMin(const CertifyBox& box) {
  return box.lo[kCertifyRate] > 0.0 ? box.lo[kCertifyRate] : box.hi[kCertifyRate] < 0.0 ? -box.hi[kCertifyRate] : 0.0;
}

// The closed-form rolling Q(0, L) of a point, or false for an inadmissible or non-finite one.
bool ClosedRollingAt(PendulumRegime regime, const CertifyPoint& x, Eigen::Matrix3d* q) {
  if (!(x[kCertifyModulus] >= 0.0 && x[kCertifyModulus] < 1.0) || !(x[kCertifyLength] > 0.0) ||
      !(std::abs(x[kCertifyRate]) <= ElasticaClosedRolling::kMaxRate))
    return false;
  *q = ElasticaClosedRolling(CertifyElastica(regime, x)).Rolling(x[kCertifyLength]);
  return q->allFinite();
}

// max_j min(dist(Q(c + d_j), Q(c)), dist(Q(c - d_j), Q(c))) over the vertex offsets d_j of the
// box on `axes` (first sign fixed: one per pair), the other coordinates at the centre; stops at
// `stop` (returns it). +infinity when a rolling is not available.
double LargestVertexDistance(PendulumRegime regime, const CertifyBox& box, const std::vector<int>& axes, double stop) {
  const CertifyPoint c = box.Centre();
  Eigen::Matrix3d qc, q;
  if (!ClosedRollingAt(regime, c, &qc)) return kInfinity;
  const auto distance = [&](unsigned signs, double orientation) {
    CertifyPoint x = c;
    for (size_t i = 0; i < axes.size(); ++i)
      x[axes[i]] += orientation * ((signs >> i) & 1u ? -1.0 : 1.0) * box.HalfWidth(axes[i]);
    return ClosedRollingAt(regime, x, &q) ? RotationAngle(q, qc) : kInfinity;
  };
  double largest = 0.0;
  const unsigned pairs = 1u << (axes.size() - 1);  // the first axis' sign is +
  for (unsigned j = 0; j < pairs; ++j) {
    const unsigned signs = j << 1;
    const double plus = distance(signs, 1.0);
    if (plus <= largest) continue;  // this pair's minimum cannot raise the maximum
    largest = std::max(largest, std::min(plus, distance(signs, -1.0)));
    if (largest >= stop) return stop;
  }
  return largest;
}

}  // namespace

double CentredRemainderBound(PendulumRegime regime, const CertifyBox& box, bool collapse_phase) {
  const double k_min = std::max(0.0, box.lo[kCertifyModulus]), k_max = box.hi[kCertifyModulus];
  if (!(k_max < 1.0)) return kInfinity;
  const double phase_max = MaxAbs(box.lo[kCertifyPhase], box.hi[kCertifyPhase]);
  const double length = box.Centre()[kCertifyLength];
  const double ha = box.HalfWidth(kCertifyRate), hk = box.HalfWidth(kCertifyModulus);
  const double hu = collapse_phase ? 0.0 : box.HalfWidth(kCertifyPhase);
  const double mv = HeadingRateBound(regime, k_max);
  // |g_p(s) - g_c(s)| <= eps(s) = e0 + e1 s: |theta_v| <= mv, |theta_k| <= m0 + m1 (|v| - phase_max)
  // for |v| <= phase_max + slope s (the chord of ArgumentBound; two such bounds, the smaller
  // integral kept).
  const double mk0 = HeadingModulusBound(regime, k_max, phase_max);
  const double mk1 = HeadingModulusBound(regime, k_max, phase_max + 1.0) - mk0;
  const double zk0 = HeadingModulusBoundByZeta(regime, k_min, k_max, phase_max);
  const double zk1 = HeadingModulusBoundByZeta(regime, k_min, k_max, phase_max + 1.0) - zk0;
  const double slope = ArgumentChordSlope(box, length);
  const auto integral = [&](double m0, double m1) {
    return (hu * mv + hk * m0) * length + 0.5 * (ha * mv + hk * m1 * slope) * length * length;
  };
  const bool by_zeta = integral(zk0, zk1) < integral(mk0, mk1);
  const double e0 = hu * mv + hk * (by_zeta ? zk0 : mk0);
  const double e1 = ha * mv + hk * (by_zeta ? zk1 : mk1) * slope;
  const double lambda = e0 * length + 0.5 * e1 * length * length;  // >= int |z| ds, |z| <= |g_p - g_c|
  if (!(lambda < M_PI)) return kInfinity;
  const double magnus = 0.25 * lambda * lambda;  // |dexp_X - I| <= |X| / 2
  // int eps^2 / 2 (|w(g + delta) - w(g) - w'(g) delta| <= delta^2 / 2, |w''| = 1; e1 < 0 where the
  // phase opposes the rate, eps >= 0 throughout).
  const double square = 0.5 * length * (e0 * e0 + e0 * e1 * length + e1 * e1 * length * length / 3.0);
  // int (1/2) sup |d^T H d| with d^T H d = theta_vv (s da + du)^2 + 2 theta_vk (s da + du) dk +
  // theta_kk dk^2 (g = theta(rate s + u0; k) + const), the bounds at the sup of |v| over each
  // piece, t = |s da + du| at the piece's end.
  double hessian = 0.0;
  const double piece = length / kHessianPieces;
  for (int i = 1; i <= kHessianPieces; ++i) {
    const double s = i * piece, t = s * ha + hu;
    const HeadingSecondBounds b = HeadingSecondDerivativeBounds(regime, k_max, ArgumentBoundOver(box, s - piece, s));
    hessian += 0.5 * (b.vv * t * t + 2.0 * b.vk * t * hk + b.kk * hk * hk) * piece;
  }
  const double bound = 2.0 * magnus + 2.0 * (square + hessian);
  return std::isfinite(bound) ? bound : kInfinity;
}

double CentredRollingDeviationBound(PendulumRegime regime, const CertifyBox& box, double margin, double stop_above) {
  const double fixed = box.HalfWidth(kCertifyLength) + 2.0 * margin;
  double best = kInfinity;
  // Collapsed in the phase (the rate keeping one sign): a shift of the path by du / rate costs one
  // rolling at each end, 2 h_u / |rate|_min.
  const double rate_min = RateMin(box);
  if (rate_min > 0.0) {
    const double base =
        fixed + 2.0 * box.HalfWidth(kCertifyPhase) / rate_min + CentredRemainderBound(regime, box, true);
    if (base < stop_above)
      best = base + LargestVertexDistance(regime, box, {kCertifyRate, kCertifyModulus}, stop_above - base);
  }
  const double stop = std::min(best, stop_above);
  const double base = fixed + CentredRemainderBound(regime, box, false);
  if (base < stop)
    best = std::min(
        best, base + LargestVertexDistance(regime, box, {kCertifyRate, kCertifyModulus, kCertifyPhase}, stop - base));
  return best < stop_above ? best : kInfinity;
}

}  // namespace plateball::internal
