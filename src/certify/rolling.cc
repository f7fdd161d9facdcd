#include "certify/rolling.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>

#include "certify/costate.h"
#include "jacobi_elliptic.h"
#include "plateball/isoparallel_families.h"

namespace plateball::internal {

namespace {

// The suprema over the box that the twist's derivatives use (notes), besides its extremes.
struct TwistScales {
  double gap;           // min |1 - G|
  double g_min, g_max;  // min G, max G
  double far;           // max |1 - G|
  double v_min, v_max;  // min V, max V
};

TwistScales ScalesOf(PendulumRegime regime, const BoxExtremes& e) {
  const bool oscillating = regime == PendulumRegime::kOscillating;
  TwistScales t;
  // G = rate^2 (oscillating) or (rate k)^2 (rotating) ranges over [g_min, g_max].
  t.g_min = oscillating ? e.rate_min * e.rate_min : std::pow(e.rate_min * e.k_min, 2);
  t.g_max = oscillating ? e.rate_max * e.rate_max : std::pow(e.rate_max * e.k_max, 2);
  t.gap = t.g_max < 1.0 ? 1.0 - t.g_max : t.g_min > 1.0 ? t.g_min - 1.0 : 0.0;
  // V^2 = (1 - G)^2 + (2 rate k)^2 (oscillating), (1 - G)^2 + (2 rate)^2 (rotating).
  t.far = std::max(std::abs(1.0 - t.g_min), std::abs(1.0 - t.g_max));
  t.v_min = std::hypot(t.gap, 2.0 * e.rate_min * (oscillating ? e.k_min : 1.0));
  t.v_max = std::hypot(t.far, 2.0 * e.rate_max * (oscillating ? e.k_max : 1.0));
  return t;
}

// Angle bound asin(delta / norm) turned into a bound on the chord |w/|w| - w'/|w'||.
double UnitChord(double delta, double norm) {
  return delta < norm ? 2.0 * std::sin(0.5 * std::asin(delta / norm)) : 2.0;
}

}  // namespace

CertifyPoint TwistDerivativeBounds(PendulumRegime regime, const CertifyBox& box) {
  const BoxExtremes e = ExtremesOf(box);
  const TwistScales t = ScalesOf(regime, e);
  if (!(t.gap >= kMinUnitGap) || !(e.k_max < 1.0)) return {kInfinity, kInfinity, kInfinity, kInfinity};
  const bool oscillating = regime == PendulumRegime::kOscillating;
  const double r = e.rate_max, k = e.k_max, len = e.length_max, g = t.g_max, g_lo = t.g_min, gap2 = t.gap * t.gap;
  // Suprema over the box (pointwise in G, D >= (1 - G)^2, |sin theta| <= min(1, |v_h|)):
  // (1 - G^2)/D lies between (1 - G)/(1 + G) and (1 + G)/(1 - G), a spread of 4G / |1 - G^2|;
  const double spread = std::min((1.0 + g) / t.gap, 4.0 * g / (t.gap * (1.0 + g_lo)));
  // |(1 - G^2) d(1/D)/d theta| = 2 G |1 - G^2| |sin theta| / D^2 <= 2 G (1 + G) / |1 - G|^2 min(1, 1/|1 - G|);
  const double b_theta = 2.0 * g * (1.0 + g) / gap2 * std::min(1.0, 1.0 / t.gap);
  const double b = b_theta * HeadingRateBound(regime, k);  // |(1 - G^2) d(1/D)/dv|
  // d((1 - G^2)/D)/dG = 2 [(1 - G)^2 - x (1 + G^2)] / D^2, x = 1 - cos theta, D = (1 - G)^2 + 2 G x:
  // at most 2/(1 - G)^2 when positive, 2 (1 + G^2) min(2/D^2, x/D^2 <= 1/(8 G (1 - G)^2)) otherwise.
  const double c = 2.0 * std::max(1.0 / gap2, (1.0 + g * g) * std::min(2.0 / (gap2 * gap2), 1.0 / (8.0 * g_lo * gap2)));
  // |(1 - G^2)(1/D(u1) - 1/D(u0))| / |rate| (by parts) or L sup |(1 - G^2) d(1/D)/dv|.
  const double shift = e.rate_min > 0.0 ? std::min(spread / e.rate_min, len * b) : len * b;
  // |(1 - G^2) int_0^L s d(1/D)/dv ds| = |(1 - G^2)(L/D(u1) - J)| / |rate|, or L^2 b / 2.
  const double weighted =
      e.rate_min > 0.0 ? std::min(len * spread / e.rate_min, 0.5 * len * len * b) : 0.5 * len * len * b;
  // Psi = -(V/2) L [1 + <(1 - G^2)/D>], 1 + (1 - G^2)/D = 2 (1 - G cos theta)/D in
  // [2/(1 + G), 2/(1 - G)] (G < 1) or [-2/(G - 1), 2/(G + 1)] (G > 1): |dPsi/dV| <= L / |1 - G|,
  // |dPsi/dG| <= V L c / 2.
  const double per_v = len / t.gap, per_g = 0.5 * t.v_max * len * c;
  const double dv_dr = oscillating ? 2.0 * (k + r) : 2.0 * r * k * k + 2.0;
  const double dg_dr = oscillating ? 2.0 * r : 2.0 * r * k * k;
  const double dv_dk = oscillating ? 2.0 * r : 2.0 * r * r * k;
  const double dg_dk = oscillating ? 0.0 : 2.0 * r * r * k;
  // theta_k = Theta_k - (K_k/K) v theta_v: Theta_k bounded (zeta form at v = 0), the secular part
  // int (1 - G^2) v d(1/D)/dv ds = (1 - G^2)[u0 (1/D(u1) - 1/D(u0)) / rate + L/D(u1) - J].
  const double theta_k = HeadingModulusBoundByZeta(regime, e.k_min, k, 0.0);
  const double secular = PeriodLogSlope(e.k_min, k) * (e.phase_max * shift + len * spread);
  CertifyPoint d;
  d[kCertifyRate] = dv_dr * per_v + dg_dr * per_g + 0.5 * t.v_max * weighted;
  d[kCertifyModulus] = dv_dk * per_v + dg_dk * per_g + 0.5 * t.v_max * (len * b_theta * theta_k + secular);
  d[kCertifyPhase] = 0.5 * t.v_max * shift;
  // |dPsi/dL| = (V/2)|1 + (1 - G^2)/D(u1)| = V |1 - G cos theta| / D <= V / |1 - G|.
  d[kCertifyLength] = t.v_max / t.gap;
  return d;
}

namespace {

// sum_i h_i d_i over the box's half-widths (an axis of zero width adds nothing, even when d_i = inf).
double HalfWidthSum(const CertifyBox& box, const CertifyPoint& d) {
  double sum = 0.0;
  for (int i = 0; i < 4; ++i) sum += box.HalfWidth(i) > 0.0 ? box.HalfWidth(i) * d[i] : 0.0;
  return sum;
}

}  // namespace

double TwistDeviationBound(PendulumRegime regime, const CertifyBox& box) {
  return HalfWidthSum(box, TwistDerivativeBounds(regime, box));
}

namespace {

// The angle between frames [f1, u x f1, u] whose u and f1 move by the chords du and df1.
double FrameAngleFromChords(double du, double df1) {
  const double df2 = std::min(2.0, du + df1);  // u' x f1' - u x f1 = (u' - u) x f1' + u x (f1' - f1)
  const double frobenius = std::sqrt(du * du + df1 * df1 + df2 * df2);
  return 2.0 * std::asin(std::min(1.0, frobenius / (2.0 * std::sqrt(2.0))));
}

}  // namespace

double FrameDeviationAngle(double delta, double norm, double norm_h) {
  return FrameAngleFromChords(UnitChord(delta, norm), UnitChord(delta, norm_h));
}

double ChartFrameDeviationAngle(double delta, double norm, double half_turn, double projection) {
  // f1 = p/|p|, p = (I - u u^T) e: |p(x) - p(c)| <= |e(x) - e(c)| + ||u u^T - u' u'^T|| <= |de| + |du|
  // (the projectors differ by sin(angle(u, u')) <= |du| in norm), |de| <= min(2, half_turn).
  const double du = UnitChord(delta, norm);
  return FrameAngleFromChords(du, UnitChord(std::min(2.0, half_turn) + du, projection));
}

double HalfHeadingDeviationBound(PendulumRegime regime, const CertifyBox& box, bool at_end) {
  const BoxExtremes e = ExtremesOf(box);
  if (!(e.k_max < 1.0)) return kInfinity;
  // theta(w, k) at w = u0 (start) or u0 + rate L (end): |theta_w| <= Mv, |theta_k| at fixed w by
  // the smaller of the two heading bounds over |w| <= w_max.
  const double w_max = at_end ? EndArgumentBound(box) : e.phase_max;
  const double mv = HeadingRateBound(regime, e.k_max);
  const double theta_k =
      std::min(HeadingModulusBound(regime, e.k_max, w_max), HeadingModulusBoundByZeta(regime, e.k_min, e.k_max, w_max));
  double dw = box.HalfWidth(kCertifyPhase);
  if (at_end) dw += e.length_max * box.HalfWidth(kCertifyRate) + e.rate_max * box.HalfWidth(kCertifyLength);
  return 0.5 * (mv * dw + theta_k * box.HalfWidth(kCertifyModulus));
}

namespace {

// sin(theta/2), cos(theta/2) at arc length s (oscillating (k sn, dn), rotating (sn, cn)).
Eigen::Vector2d HalfHeading(const Elastica& path, double s) {
  const double half = 0.5 * path.PendulumAngle(s);
  return {std::sin(half), std::cos(half)};
}

}  // namespace

ChartFrameAt ChartFrame(const Elastica& path, double s) {
  const Eigen::Vector3d v = ElasticaCostate(path, s);
  const Eigen::Vector2d half = HalfHeading(path, s);
  ChartFrameAt out;
  out.costate_norm = v.norm();
  if (!(out.costate_norm > 0.0)) return out;
  const Eigen::Vector3d u = v / out.costate_norm, e(-half.x(), half.y(), 0.0);
  const Eigen::Vector3d p = e - e.dot(u) * u;
  out.projection = p.norm();
  if (!(out.projection > 0.0)) return out;
  const Eigen::Vector3d f1 = p / out.projection;
  out.frame.col(0) = f1;
  out.frame.col(1) = u.cross(f1);
  out.frame.col(2) = u;
  return out;
}

double ChartTwistRate(const Elastica& path, double s) {
  const ElasticaParameters& x = path.parameters();
  const PendulumRegime regime = x.regime;
  const double a = x.rate, k = x.modulus, g = path.G(), gap = 1.0 - g;
  const double big_v = ElasticaCostate(path, s).norm();
  double sq;  // S = sn^2(w, k)
  if (regime == PendulumRegime::kRotating || k > 0.0) {
    const double sin_half = HalfHeading(path, s).x();
    sq = regime == PendulumRegime::kRotating ? sin_half * sin_half : std::pow(sin_half / k, 2);
  } else {
    sq = std::pow(std::sin(a * s + x.phase), 2);  // sn(w, 0) = sin w
  }
  return -0.5 * big_v * (1.0 + gap * (1.0 + g) * sq / (gap * gap * sq + 4.0 * a * a));
}

CertifyPoint ChartTwistDerivativeBounds(PendulumRegime regime, const CertifyBox& box) {
  const BoxExtremes e = ExtremesOf(box);
  if (!(e.rate_min > 0.0) || !(e.k_max < 1.0)) return {kInfinity, kInfinity, kInfinity, kInfinity};
  const TwistScales t = ScalesOf(regime, e);
  const bool oscillating = regime == PendulumRegime::kOscillating;
  const double r = e.rate_max, r_lo = e.rate_min, k = e.k_max, len = e.length_max;
  // phi = -(V/2)(1 + P(S)), P = N S / den, N = 1 - G^2, den = (1 - G)^2 S + 4 rate^2, S in [0, 1].
  // S/den increases in S, S/den^2 peaks at S = 4 rate^2/(1 - G)^2 (if <= 1); both decrease in
  // (1 - G)^2 and rate^2: their sups are at (gap, rate_min).
  // N = (1 - G)(1 + G) decreases in G: its extremes are at g_min (largest) and g_max (smallest).
  const double n_hi = (1.0 - t.g_min) * (1.0 + t.g_min), n_lo = (1.0 - t.g_max) * (1.0 + t.g_max);
  const double n_max = std::max(std::abs(n_hi), std::abs(n_lo));
  const double gap2 = t.gap * t.gap, r2 = r_lo * r_lo, den_min = gap2 + 4.0 * r2;
  const double p1 = n_max / den_min;  // sup |P|, and P's spread over S (P(0) = 0, monotone in S)
  // P lies in [min(0, n_lo)/den_min, max(0, n_hi)/den_min] (sign of N), so 1 + P in
  // [1 + min(0, n_lo)/den_min, 1 + max(0, n_hi)/den_min].
  const double one_p = std::max(1.0 + std::max(0.0, n_hi) / den_min, std::abs(1.0 + std::min(0.0, n_lo) / den_min));
  const double p_s = n_max / (4.0 * r2);  // sup |dP/dS| = |N| 4 rate^2 / den^2 at S = 0
  const double q = gap2 <= 4.0 * r2 ? 1.0 / (den_min * den_min) : 1.0 / (16.0 * r2 * gap2);  // sup S/den^2
  // dP/dG = 2 S ((1 - G)^2 S - 4 G rate^2) / den^2, |.| <= 2 max(1, G) S/den; dP/drate|_G = -8 rate N S/den^2.
  const double p_g = 2.0 * std::max(1.0, t.g_max) / den_min, p_r = 8.0 * r * n_max * q;
  const double spread = 0.5 * t.v_max * p1;  // sup over w of |phi(w1) - phi(w2)|
  const double phi_w = 0.5 * t.v_max * p_s;  // sup |dphi/dw| (|dS/dw| = |2 sn cn dn| <= 1)
  // V^2 = (1 - G)^2 + 4 rate^2 k^2 (oscillating, G = rate^2): dV/drate = (4 rate k^2 - 2 (1 - G) rate)/V,
  // dV/dk = 4 rate^2 k / V; rotating (G = rate^2 k^2, + 4 rate^2): dV/drate = (4 rate - 2 (1 - G) rate k^2)/V,
  // dV/dk = -2 (1 - G) rate^2 k / V. Each also <= the V-free bounds of TwistDerivativeBounds.
  const double inv_v = t.v_min > 0.0 ? 1.0 / t.v_min : kInfinity;
  const double dv_dr = oscillating ? std::min(2.0 * (k + r), (4.0 * r * k * k + 2.0 * t.far * r) * inv_v)
                                   : std::min(2.0 * r * k * k + 2.0, (4.0 * r + 2.0 * t.far * r * k * k) * inv_v);
  const double dg_dr = oscillating ? 2.0 * r : 2.0 * r * k * k;
  const double dv_dk = oscillating ? std::min(2.0 * r, 4.0 * r * r * k * inv_v)
                                   : std::min(2.0 * r * r * k, 2.0 * t.far * r * r * k * inv_v);
  const double dg_dk = oscillating ? 0.0 : 2.0 * r * r * k;
  // By parts (w = rate s + u0): int_0^L s phi_w ds = int_0^L (phi(u1) - phi(s)) ds / rate, and
  // dPsit/du0 = (phi(u1) - phi(u0)) / rate.
  const double by_parts = std::min(len * spread / r_lo, 0.5 * len * len * phi_w);
  const double by_phase = std::min(spread / r_lo, len * phi_w);
  // k at fixed w: S_k = Sigma_k - (K_k/K) w S_w, |Sigma_k| = |2 sn cn am_k|_periods| <= A0, and
  // int w phi_w ds = u0 (phi(u1) - phi(u0))/rate + int_0^L (phi(u1) - phi(s)) ds.
  const double a0 = k * (1.0 + CompleteEllipticK(k)) / (2.0 * OneMinusSquare(k));  // Jacobi's zeta form
  const double secular =
      PeriodLogSlope(e.k_min, k) * (e.phase_max * by_phase + std::min(len * spread, 0.5 * r * len * len * phi_w));
  CertifyPoint d;
  d[kCertifyRate] = len * (0.5 * dv_dr * one_p + 0.5 * t.v_max * (p_g * dg_dr + p_r)) + by_parts;
  d[kCertifyModulus] = len * (0.5 * dv_dk * one_p + 0.5 * t.v_max * (p_g * dg_dk + p_s * a0)) + secular;
  d[kCertifyPhase] = by_phase;
  d[kCertifyLength] = 0.5 * t.v_max * one_p;
  return d;
}

double ChartTwistDeviationBound(PendulumRegime regime, const CertifyBox& box) {
  return HalfWidthSum(box, ChartTwistDerivativeBounds(regime, box));
}

namespace {

// The two charts of Q(0, L) = F(L) Rz(Psi) F(0)^T: the costate frame (f1 along e3 x u, singular
// where v_h = 0) and the theta/2 chart (smooth through G = 1).
enum class RollingChart { kCostate, kHalfHeading };

// `start` plus the chart's terms (twist, then each frame) on a box whose length is collapsed to
// the centre's (and maybe its phase), +infinity as soon as the partial sum reaches stop_above.
double CollapsedBound(RollingChart chart,
                      PendulumRegime regime,
                      const CertifyBox& fixed,
                      double start,
                      double margin,
                      double stop_above) {
  const CertifyPoint x = fixed.Centre();
  const bool costate_chart = chart == RollingChart::kCostate;
  double bound = start + (costate_chart ? TwistDeviationBound(regime, fixed) : ChartTwistDeviationBound(regime, fixed));
  const Elastica path = CertifyElastica(regime, x);
  for (bool at_end : {false, true}) {
    if (!(bound < stop_above)) return kInfinity;
    const double s = at_end ? x[kCertifyLength] : 0.0;
    const double delta = margin + CostateDeviationBound(regime, fixed, at_end);
    if (costate_chart) {
      const Eigen::Vector3d v = ElasticaCostate(path, s);
      bound += FrameDeviationAngle(delta, v.norm(), v.head<2>().norm());
    } else {
      const ChartFrameAt f = ChartFrame(path, s);
      const double half_turn = margin + HalfHeadingDeviationBound(regime, fixed, at_end);
      bound += ChartFrameDeviationAngle(delta, f.costate_norm, half_turn, f.projection);
    }
  }
  return bound < stop_above ? bound : kInfinity;
}

double RollingDeviationInChart(
    RollingChart chart, PendulumRegime regime, const CertifyBox& box, double margin, double stop_above) {
  const CertifyPoint x = box.Centre();
  if (!(x[kCertifyModulus] < 1.0) || !(x[kCertifyLength] > 0.0)) return kInfinity;
  // Q(0, L) moves at unit speed in L (|e3 x x'| = 1): Q(p) is within h_L of Q at (p, L_centre),
  // which the closed form compares with the centre over the box collapsed to L = L_centre.
  CertifyBox fixed = box;
  fixed.lo[kCertifyLength] = fixed.hi[kCertifyLength] = x[kCertifyLength];
  const double by_length = CollapsedBound(chart, regime, fixed, box.HalfWidth(kCertifyLength), margin, stop_above);
  // At a fixed rate a phase change du shifts the path by du/rate along itself, which moves Q(0, L)
  // by at most 2 |du| / |rate| (a rolling at unit speed at each end): collapse the phase too.
  const BoxExtremes e = ExtremesOf(box);
  if (!(e.rate_min > 0.0)) return by_length;
  fixed.lo[kCertifyPhase] = fixed.hi[kCertifyPhase] = x[kCertifyPhase];
  const double start = box.HalfWidth(kCertifyLength) + 2.0 * box.HalfWidth(kCertifyPhase) / e.rate_min;
  return std::min(by_length, CollapsedBound(chart, regime, fixed, start, margin, std::min(by_length, stop_above)));
}

}  // namespace

double ClosedRollingDeviationBound(PendulumRegime regime, const CertifyBox& box, double margin, double stop_above) {
  return RollingDeviationInChart(RollingChart::kCostate, regime, box, margin, stop_above);
}

double ChartRollingDeviationBound(PendulumRegime regime, const CertifyBox& box, double margin, double stop_above) {
  return RollingDeviationInChart(RollingChart::kHalfHeading, regime, box, margin, stop_above);
}

}  // namespace plateball::internal
