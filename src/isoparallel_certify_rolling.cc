#include "isoparallel_certify_rolling.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "isoparallel_certify_costate.h"
#include "plateball/isoparallel_families.h"

namespace plateball::internal {

namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// The suprema over the box that the twist's derivatives use (notes), besides its extremes.
struct TwistScales {
  double gap;           // min |1 - G|
  double g_min, g_max;  // min G, max G
  double v_max;         // max V
};

TwistScales ScalesOf(PendulumRegime regime, const BoxExtremes& e) {
  const bool oscillating = regime == PendulumRegime::kOscillating;
  TwistScales t;
  // G = rate^2 (oscillating) or (rate k)^2 (rotating) ranges over [g_min, g_max].
  t.g_min = oscillating ? e.rate_min * e.rate_min : std::pow(e.rate_min * e.k_min, 2);
  t.g_max = oscillating ? e.rate_max * e.rate_max : std::pow(e.rate_max * e.k_max, 2);
  t.gap = t.g_max < 1.0 ? 1.0 - t.g_max : t.g_min > 1.0 ? t.g_min - 1.0 : 0.0;
  // V^2 = (1 - G)^2 + (2 rate k)^2 (oscillating), (1 - G)^2 + (2 rate)^2 (rotating).
  const double far = std::max(std::abs(1.0 - t.g_min), std::abs(1.0 - t.g_max));
  t.v_max = std::hypot(far, 2.0 * e.rate_max * (oscillating ? e.k_max : 1.0));
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

double TwistDeviationBound(PendulumRegime regime, const CertifyBox& box) {
  const CertifyPoint d = TwistDerivativeBounds(regime, box);
  double sum = 0.0;
  for (int i = 0; i < 4; ++i) sum += box.HalfWidth(i) > 0.0 ? box.HalfWidth(i) * d[i] : 0.0;
  return sum;
}

double FrameDeviationAngle(double delta, double norm, double norm_h) {
  const double du = UnitChord(delta, norm), df1 = UnitChord(delta, norm_h);
  const double df2 = std::min(2.0, du + df1);  // u' x f1' - u x f1 = (u' - u) x f1' + u x (f1' - f1)
  const double frobenius = std::sqrt(du * du + df1 * df1 + df2 * df2);
  return 2.0 * std::asin(std::min(1.0, frobenius / (2.0 * std::sqrt(2.0))));
}

namespace {

// `start` plus the closed-form terms (twist, then each frame) on a box whose length is collapsed
// to the centre's (and maybe its phase), +infinity as soon as the partial sum reaches stop_above.
double CollapsedBound(PendulumRegime regime, const CertifyBox& fixed, double start, double margin,
                      double stop_above) {
  const CertifyPoint x = fixed.Centre();
  double bound = start + TwistDeviationBound(regime, fixed);
  const Elastica path = CertifyElastica(regime, x);
  for (bool at_end : {false, true}) {
    if (!(bound < stop_above)) return kInfinity;
    const Eigen::Vector3d v = ElasticaCostate(path, at_end ? x[kCertifyLength] : 0.0);
    bound += FrameDeviationAngle(margin + CostateDeviationBound(regime, fixed, at_end), v.norm(), v.head<2>().norm());
  }
  return bound < stop_above ? bound : kInfinity;
}

}  // namespace

double ClosedRollingDeviationBound(PendulumRegime regime, const CertifyBox& box, double margin, double stop_above) {
  const CertifyPoint x = box.Centre();
  if (!(x[kCertifyModulus] < 1.0) || !(x[kCertifyLength] > 0.0)) return kInfinity;
  // Q(0, L) moves at unit speed in L (|e3 x x'| = 1): Q(p) is within h_L of Q at (p, L_centre),
  // which the closed form compares with the centre over the box collapsed to L = L_centre.
  CertifyBox fixed = box;
  fixed.lo[kCertifyLength] = fixed.hi[kCertifyLength] = x[kCertifyLength];
  const double by_length = CollapsedBound(regime, fixed, box.HalfWidth(kCertifyLength), margin, stop_above);
  // At a fixed rate a phase change du shifts the path by du/rate along itself, which moves Q(0, L)
  // by at most 2 |du| / |rate| (a rolling at unit speed at each end): collapse the phase too.
  const BoxExtremes e = ExtremesOf(box);
  if (!(e.rate_min > 0.0)) return by_length;
  fixed.lo[kCertifyPhase] = fixed.hi[kCertifyPhase] = x[kCertifyPhase];
  const double start = box.HalfWidth(kCertifyLength) + 2.0 * box.HalfWidth(kCertifyPhase) / e.rate_min;
  return std::min(by_length, CollapsedBound(regime, fixed, start, margin, std::min(by_length, stop_above)));
}

}  // namespace plateball::internal
