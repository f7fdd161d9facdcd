#include "certify/tails.h"

#include <algorithm>
#include <boost/math/special_functions/ellint_2.hpp>
#include <cmath>
#include <limits>

#include "jacobi_elliptic.h"
#include "plateball/so3.h"
#include "rotation_trick.h"

namespace plateball::internal {

namespace {

// The drift ratio rho (signed): oscillating 2E/K - 1 (mean of cos theta), rotating 1 - 2D/K.
// Both are decreasing in k (E/K and D/K are means of decreasing resp. increasing functions of
// sin^2 under a weight (1 - k^2 sin^2)^(-1/2) whose likelihood ratio grows with k).
double DriftRatio(PendulumRegime regime, double k) {
  const double kk = CompleteEllipticK(k);
  if (regime == PendulumRegime::kOscillating) return 2.0 * boost::math::ellint_2(k) / kk - 1.0;
  return 1.0 - 2.0 * CompleteEllipticD(k) / kk;
}

// h(cap) = sqrt(cap^2 - l^2) + l, l = |x1 - x0| (the bound's factor at the largest length), over
// 4 sin(delta / 2); 0 when the straight residual does not exceed the margin.
double RateScale(const CertifyTarget& target, double cap, double margin) {
  const double delta = StraightResidual(target) - margin;
  if (!(delta > 0.0)) return 0.0;
  const double l = target.radius;
  const double h = std::sqrt(std::max(0.0, (cap - l) * (cap + l))) + l;
  return h / (4.0 * std::sin(0.5 * delta));
}

// ||E - I|| <= b for a rotation E means its angle is at most 2 asin(b / 2) (||E - I|| = 2 sin(angle / 2)).
double DeviationAngle(double b) { return b >= 2.0 ? M_PI : 2.0 * std::asin(0.5 * b); }

}  // namespace

double StraightResidual(const CertifyTarget& target) {
  // e3 x (x1 - x0) with x1 - x0 = radius (cos goal, sin goal).
  const Eigen::Vector3d w(
      -target.radius * std::sin(target.goal_angle), target.radius * std::cos(target.goal_angle), 0.0);
  return RotationTrickResidual(target.target, 0.0, ExpSO3(w)).norm();
}

double DriftDeficit(PendulumRegime regime, double k) {
  if (k <= 0.0) return regime == PendulumRegime::kOscillating ? 0.0 : 1.0;
  if (!(k < 1.0)) return 0.0;  // the limit k -> 1 (like 2 / sqrt(K)): |rho| -> 1 at the separatrix
  const double kk = CompleteEllipticK(k), d = CompleteEllipticD(k);
  // 1 - rho^2 = (1 - rho)(1 + rho) without cancellation: oscillating 1 - rho = 2 k^2 D / K,
  // 1 + rho = 2E / K; rotating 1 - rho = 2D / K, 1 + rho = 2 (K - D) / K.
  if (regime == PendulumRegime::kOscillating) return 2.0 * k * std::sqrt(d * boost::math::ellint_2(k)) / kk;
  return 2.0 * std::sqrt(d * (kk - d)) / kk;
}

namespace {

// The forms of PeriodicPartLength (v units), each with its monotonicity in k (notes, "a tail rate
// bound uniform up to the separatrix", 2).

// Cauchy-Schwarz: n K sqrt(1 - rho^2); infinite at k = 1.
double CauchySchwarzLength(PendulumRegime regime, double k) {
  return k < 1.0 ? PhasePeriod(regime, k) * DriftDeficit(regime, k) : kInfinity;
}

// Rotating, t at theta = pi: 2 |cos am| = 2 |cn| over [0, 2K] (int_0^K cn = asin(k) / k) plus
// 2K (1 + rho) = 4 (K - D). Both terms increase with k; at k = 1: 2 pi + 4.
double RotatingLengthAtPi(double k) {
  const double asin_over_k = k > 0.0 ? std::asin(k) / k : 1.0;
  const double k_minus_d = k < 1.0 ? CompleteEllipticK(k) - CompleteEllipticD(k) : 1.0;
  return 4.0 * asin_over_k + 4.0 * k_minus_d;
}

// Oscillating, t at theta = pi: 2 cos(theta / 2) = 2 dn over [0, 4K] (int_0^K dn = pi / 2) plus
// 4K (1 + rho) = 8E. Decreasing with k (E is); at k = 1: 4 pi + 8.
double OscillatingLengthAtPi(double k) {
  const double e = k < 1.0 ? CompleteEllipticK(k) - k * k * CompleteEllipticD(k) : 1.0;
  return 4.0 * M_PI + 8.0 * e;
}

// Oscillating, t at theta = 0: 2 |sin(theta / 2)| = 2k |sn| over [0, 4K] (int_0^K sn = atanh(k) / k)
// plus 4K (1 - rho) = 8 (K - E) = 8 k^2 D. Increasing with k; infinite at k = 1 (best at small k).
double OscillatingLengthAtZero(double k) {
  return k < 1.0 ? 8.0 * std::atanh(k) + 8.0 * k * k * CompleteEllipticD(k) : kInfinity;
}

// The sup of the Cauchy-Schwarz form over [k_lo, k_hi]: K(k_hi) and the smallest |rho| (rho is
// decreasing in k: 0 if it changes sign on the interval, else the smaller end value).
double CauchySchwarzLengthOver(PendulumRegime regime, double k_lo, double k_hi) {
  if (!(k_hi < 1.0)) return kInfinity;
  const double r_lo = DriftRatio(regime, k_lo), r_hi = DriftRatio(regime, k_hi);
  const double m = (r_lo >= 0.0 && r_hi <= 0.0) ? 0.0 : std::min(std::abs(r_lo), std::abs(r_hi));
  return PhasePeriod(regime, k_hi) * std::sqrt(std::max(0.0, (1.0 - m) * (1.0 + m)));
}

}  // namespace

double PeriodicPartLength(PendulumRegime regime, double k) {
  if (!(k >= 0.0 && k <= 1.0)) return kInfinity;
  const double cs = CauchySchwarzLength(regime, k);
  if (regime == PendulumRegime::kRotating) return std::min(cs, RotatingLengthAtPi(k));
  return std::min({cs, OscillatingLengthAtPi(k), OscillatingLengthAtZero(k)});
}

namespace {

// A sup of PeriodicPartLength on [k_lo, k_hi] from each form's own sup (a min of sups).
double PeriodicPartLengthOnPiece(PendulumRegime regime, double k_lo, double k_hi) {
  const double cs = CauchySchwarzLengthOver(regime, k_lo, k_hi);
  if (regime == PendulumRegime::kRotating) return std::min(cs, RotatingLengthAtPi(k_hi));
  return std::min({cs, OscillatingLengthAtPi(k_lo), OscillatingLengthAtZero(k_hi)});
}

// The largest of piece_sup(a, b) over contiguous pieces covering [k_lo, k_hi] (k_lo < k_hi): the
// sup of a min is at most the min of the sups, piece by piece. 16 pieces uniform in log(1 - k)
// (the scale on which K grows; down to 1 - k = 1e-12 when k_hi = 1), so that the forms' crossings
// are resolved; the last piece ends at k_hi exactly.
template <typename PieceSup>
double OverPieces(double k_lo, double k_hi, PieceSup piece_sup) {
  constexpr int kPieces = 16;
  const double gap_lo = 1.0 - k_lo, gap_hi = std::max(1.0 - k_hi, std::min(1e-12, 0.5 * gap_lo));
  double sup = 0.0, a = k_lo;
  for (int i = 1; i <= kPieces; ++i) {
    const double gap = gap_lo * std::pow(gap_hi / gap_lo, double(i) / kPieces);
    const double b = i == kPieces ? k_hi : std::min(k_hi, 1.0 - gap);
    sup = std::max(sup, piece_sup(a, std::max(a, b)));
    a = std::max(a, b);
  }
  return sup;
}

}  // namespace

double PeriodicPartLengthOver(PendulumRegime regime, double k_lo, double k_hi) {
  if (!(k_lo >= 0.0 && k_lo <= k_hi && k_hi <= 1.0)) return kInfinity;
  if (k_lo == k_hi) return PeriodicPartLength(regime, k_lo);
  return OverPieces(k_lo, k_hi, [regime](double a, double b) { return PeriodicPartLengthOnPiece(regime, a, b); });
}

namespace {

// A bound on max_v Z(v, k) (Jacobi's zeta, odd and 2K-periodic) for every k in [a, b]: with
// G(phi, k) = E(phi, k) - (E/K)(k) F(phi, k) (= Z at phi = am v), E(phi, .) and E/K decrease and
// F(phi, .) increases in k, so G(phi, k) <= E(phi, a) - r F(phi, a), r = (E/K)(b), whose max over
// phi is where Delta_a^2 = r: sin^2 phi = min(1, (1 - r) / a^2). Exact for a = b (dn^2 = E/K).
// E(phi, a) = F - a^2 D(phi) and 1 - r = b^2 D(b) / K(b) without cancellation.
double ZetaMaxOver(double a, double b) {
  if (!(b > 0.0)) return 0.0;                                                                  // Z = 0 for k = 0
  if (!(b < 1.0)) return a < 1.0 ? CompleteEllipticK(a) - a * a * CompleteEllipticD(a) : 1.0;  // r = 0: E(a)
  const double one_minus_r = b * b * CompleteEllipticD(b) / CompleteEllipticK(b);
  const double s2 = a > 0.0 ? std::min(1.0, one_minus_r / (a * a)) : 1.0;
  const double sn = std::sqrt(s2), cn = std::sqrt(1.0 - s2), kc2 = OneMinusSquare(a);
  return one_minus_r * EllipticFSinCos(sn, cn, kc2) - a * a * EllipticDSinCos(sn, cn, kc2);
}

// The diagonal of the box holding p over one period, in the frame of the drift direction (v
// units), for every k in [a, b]: p_e = int (cos theta - rho) = 2 Z / k^2 (rotating), 2 Z
// (oscillating), range 2 Z_max times that; p_perp = int sin theta = -2 dn / k^2 (rotating,
// sin theta = 2 sn cn; range 2 (1 - k') / k^2 = 2 / (1 + k'), increasing) or -2k cn (oscillating,
// sin theta = 2k sn dn; range 4k).
double BoxDiagonalOver(PendulumRegime regime, double a, double b) {
  const double z = ZetaMaxOver(a, b);
  if (regime == PendulumRegime::kOscillating) return std::hypot(4.0 * z, 4.0 * b);
  if (!(a > 0.0)) return kInfinity;  // Z / k^2 at k = 0: left to the other forms
  return std::hypot(4.0 * z / (a * a), 2.0 / (1.0 + std::sqrt(OneMinusSquare(b))));
}

}  // namespace

double PeriodicPartDiameter(PendulumRegime regime, double k) {
  if (!(k >= 0.0 && k <= 1.0)) return kInfinity;
  return std::min(0.5 * PeriodicPartLength(regime, k), BoxDiagonalOver(regime, k, k));
}

double PeriodicPartDiameterOver(PendulumRegime regime, double k_lo, double k_hi) {
  if (!(k_lo >= 0.0 && k_lo <= k_hi && k_hi <= 1.0)) return kInfinity;
  if (k_lo == k_hi) return PeriodicPartDiameter(regime, k_lo);
  return OverPieces(k_lo, k_hi, [regime](double a, double b) {
    return std::min(0.5 * PeriodicPartLengthOnPiece(regime, a, b), BoxDiagonalOver(regime, a, b));
  });
}

double AveragingDeviationBound(double diameter, double length, double chord) {
  if (!std::isfinite(diameter)) return kInfinity;
  const double c = std::min(std::abs(chord), length);
  return DeviationAngle(diameter * (std::sqrt((length - c) * (length + c)) + c));
}

double StraightRunDeviationBound(double eta, double length, double chord) {
  // |x' - t*| <= mu, so |c / L - t*| <= mu, |x' - c / L| <= 2 mu and the deviation F from the
  // uniformly run chord has |F(s)| <= 2 mu min(s, L - s): int |F| <= mu L^2 / 2.
  const double mu = 2.0 * std::sin(0.5 * std::min(std::abs(eta), M_PI / 2));
  const double r = std::min(std::abs(chord), length) / length;
  return DeviationAngle(0.5 * mu * length * length * (2.0 * mu + r));
}

double HeadingModulusBoundNearSeparatrix(PendulumRegime regime, double k_max, double v_max) {
  const double ch = std::cosh(std::min(std::abs(v_max), 700.0));
  const double am_k = k_max * (ch - 1.0);  // increasing in k: the sup is at k_max
  if (regime == PendulumRegime::kRotating) return 2.0 * am_k;
  // 1 / dn <= min(cosh v, 1 / k'): the oscillation is slower than the separatrix at equal angle.
  const double kp = std::sqrt(std::max(0.0, (1.0 - k_max) * (1.0 + k_max)));
  const double inv_dn = kp > 0.0 ? std::min(ch, 1.0 / kp) : ch;
  return 2.0 * (1.0 + k_max * am_k) * inv_dn;
}

namespace {

// The decreasing side of the gap (the loop's distance to pi); the growing one is the modulus
// integral of the separatrix bound, SeparatrixHeadingGapGrowing.
double GapDecreasing(PendulumRegime regime, double k, double v) {
  const double a = std::min(std::abs(v), 350.0);
  return regime == PendulumRegime::kRotating ? 2.0 * std::asin(1.0 / std::cosh(a)) : 2.0 * std::acos(k * std::tanh(a));
}

}  // namespace

double SeparatrixHeadingGapGrowing(PendulumRegime regime, double k, double v) {
  const double ch = std::cosh(std::min(std::abs(v), 350.0));
  return regime == PendulumRegime::kRotating ? (1.0 - k) * (1.0 + k) * (ch - 1.0) : 2.0 * (1.0 - k) * ch * ch;
}

double SeparatrixHeadingGap(PendulumRegime regime, double k, double v) {
  return std::min(SeparatrixHeadingGapGrowing(regime, k, v), GapDecreasing(regime, k, v));
}

double SeparatrixHeadingGapSup(PendulumRegime regime, double k) {
  // min(A, B), A increasing and B decreasing in |v|: for a bracket [lo, hi] of their crossing
  // every v has min <= A(hi) (v <= hi) or <= B(lo) (v >= lo). Over every v >= 0 (not only
  // [0, K(k)]), so that it also bounds every modulus in [k, 1), whose A and B are smaller.
  if (!(k < 1.0)) return 0.0;
  const auto a = [&](double v) { return SeparatrixHeadingGapGrowing(regime, k, v); };
  const auto b = [&](double v) { return GapDecreasing(regime, k, v); };
  double lo = 0.0, hi = 1.0;
  while (a(hi) < b(hi)) hi *= 2.0;  // A grows without bound, B stays bounded
  for (int i = 0; i < 200 && hi - lo > 1e-13 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (a(mid) < b(mid) ? lo : hi) = mid;
  }
  return std::max(a(hi), b(lo));
}

double MaxSolutionRate(const CertifyTarget& target, PendulumRegime regime, double k, double cap, double margin) {
  const double scale = RateScale(target, cap, margin);
  // B = (diameter_v / |a|) h >= 2 sin(delta / 2) for a solution: |a| <= diameter_v h / (2 sin).
  return scale == 0.0 ? kInfinity : 2.0 * PeriodicPartDiameter(regime, k) * scale;
}

double MaxSolutionRateOver(
    const CertifyTarget& target, PendulumRegime regime, double k_lo, double k_hi, double cap, double margin) {
  const double scale = RateScale(target, cap, margin);
  return scale == 0.0 ? kInfinity : 2.0 * PeriodicPartDiameterOver(regime, k_lo, k_hi) * scale;
}

}  // namespace plateball::internal
