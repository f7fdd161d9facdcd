#include "certify/periods.h"

#include <algorithm>
#include <cmath>

#include "certify/costate.h"
#include "certify/rolling.h"
#include "jacobi_elliptic.h"

namespace plateball::internal {

namespace {

// Relative widening of rho = K(k_c) / K(k) for the rounding of the two K (a few ulp each).
constexpr double kRhoRounding = 1e-13;

// The half-width, about `centre`, of {x rho : x in [lo, hi], rho in [rho_lo, rho_hi]} (the
// product is bilinear: its extremes are at the corners), widened for the products' rounding.
double ScaledHalfWidth(double lo, double hi, double rho_lo, double rho_hi, double centre) {
  double h = 0.0;
  for (double x : {lo, hi})
    for (double rho : {rho_lo, rho_hi}) h = std::max(h, std::abs(x * rho - centre));
  return h * (1.0 + 1e-12);
}

}  // namespace

double HeadingModulusBoundAtFixedPeriods(PendulumRegime regime, double k_min, double k_max) {
  // At fixed z, d am/dk = [k sn cn - dn Z(v) / k] / k'^2 (the secular term dn v K'/K of the
  // derivative at fixed v is the period's change), |sn cn| <= 1/2, dn <= 1, |Z| / k <=
  // JacobiZetaOverModulusBound; k / k'^2 increases with k, so the sup is at k_max.
  if (!(k_max < 1.0)) return std::numeric_limits<double>::infinity();
  const double k = std::max(0.0, k_max);
  const double kp2 = (1.0 - k) * (1.0 + k);
  const double am_k = (0.5 * k + JacobiZetaOverModulusBound(std::max(0.0, k_min), k)) / kp2;
  return HeadingModulusFromAmplitude(regime, k, am_k);
}

CertifyBox FixedPeriodsBox(const CertifyBox& box) {
  const CertifyPoint c = box.Centre();
  const double k_c = c[kCertifyModulus];
  const double kk_c = CompleteEllipticK(k_c);
  // K increases with k: rho is largest at the smallest modulus.
  const double rho_lo = kk_c / CompleteEllipticK(box.hi[kCertifyModulus]) * (1.0 - kRhoRounding);
  const double rho_hi = kk_c / CompleteEllipticK(std::max(0.0, box.lo[kCertifyModulus])) * (1.0 + kRhoRounding);
  CertifyBox out = box;
  out.lo[kCertifyModulus] = out.hi[kCertifyModulus] = k_c;
  for (int axis : {kCertifyRate, kCertifyPhase}) {
    const double h = ScaledHalfWidth(box.lo[axis], box.hi[axis], rho_lo, rho_hi, c[axis]);
    out.lo[axis] = c[axis] - h;
    out.hi[axis] = c[axis] + h;
  }
  return out;
}

double FixedPeriodsModulusShare(PendulumRegime regime, const CertifyBox& box) {
  const double hk = box.HalfWidth(kCertifyModulus);
  if (hk == 0.0) return 0.0;
  // |w1 - w2| = 2 |sin(dg / 2)| <= min(|dg|, 2) at every s, dg <= h_k Mz (mean value in k at fixed z).
  const double mz = HeadingModulusBoundAtFixedPeriods(regime, box.lo[kCertifyModulus], box.hi[kCertifyModulus]);
  return box.hi[kCertifyLength] * std::min(hk * mz, 2.0);
}

double FixedPeriodsDeviationBound(PendulumRegime regime, const CertifyBox& box, CertifyPoint* contributions) {
  const double share = FixedPeriodsModulusShare(regime, box);
  CertifyPoint widened;
  const double rest = RollingDeviationBound(regime, FixedPeriodsBox(box), &widened);
  if (contributions != nullptr) {
    CertifyBox collapsed = box;  // the same box at the centre modulus, without the widening
    collapsed.lo[kCertifyModulus] = collapsed.hi[kCertifyModulus] = box.Centre()[kCertifyModulus];
    RollingDeviationBound(regime, collapsed, contributions);
    (*contributions)[kCertifyModulus] = share;
    for (int axis : {kCertifyRate, kCertifyPhase}) {
      (*contributions)[kCertifyModulus] += std::max(0.0, widened[axis] - (*contributions)[axis]);
    }
  }
  return share + rest;
}

double FixedPeriodsRollingDeviationBound(PendulumRegime regime,
                                         const CertifyBox& box,
                                         double margin,
                                         bool closed_rolling,
                                         bool chart_rolling,
                                         double stop_above) {
  const double share = FixedPeriodsModulusShare(regime, box);
  const CertifyBox periods = FixedPeriodsBox(box);
  double rest = RollingDeviationBound(regime, periods);
  const double stop = std::min(rest, stop_above - share);
  if (closed_rolling && stop > 0.0) rest = std::min(rest, ClosedRollingDeviationBound(regime, periods, margin, stop));
  if (chart_rolling && stop > 0.0) rest = std::min(rest, ChartRollingDeviationBound(regime, periods, margin, stop));
  return share + rest;
}

double FixedPeriodsChordDeviationBound(PendulumRegime regime, const CertifyBox& box) {
  const CertifyBox periods = FixedPeriodsBox(box);
  return FixedPeriodsModulusShare(regime, box) +
         std::min(RollingDeviationBound(regime, periods), ChordDeviationBound(regime, periods));
}

BoxVerdict FixedPeriodsTest(const CertifyWindowOptions& options,
                            const CertifyBox& box,
                            const CertifyResidual& centre,
                            double deviation,
                            double chord_deviation) {
  const double chord = std::min(chord_deviation, FixedPeriodsChordDeviationBound(options.regime, box));
  if (std::abs(centre.chord_miss) > chord + options.margin) return BoxVerdict::kExcludedByChord;
  const double slack = RotationSlack(centre, chord, options.margin);
  if (!(slack > box.HalfWidth(kCertifyLength))) return BoxVerdict::kUndecided;  // every bound holds h_L
  const double rolling = FixedPeriodsRollingDeviationBound(
      options.regime, box, options.margin, options.closed_rolling, options.chart_rolling, std::min(deviation, slack));
  return rolling < slack ? BoxVerdict::kExcludedByRotation : BoxVerdict::kUndecided;
}

}  // namespace plateball::internal
