// Internal: the rolling's deviation over a parameter box compared at a fixed number of periods
// (docs/paper_notes.md, "General targets: comparing at a fixed number of periods").
//
// A point x = (rate, k, u0, L) of a box and the point x' = (rate rho, k_c, u0 rho, L),
// rho = K(k_c) / K(k), k_c the box's centre modulus, run through the same normalised phase
// z(s) = (rate s + u0) / K(k) at every s: their headings differ by a k change at fixed z, bounded
// without a secular part (|d am/dk| at fixed z <= A0 = (k/2 + min(k K/2, E/k)) / k'^2, Jacobi's zeta), so
//   dist(Q(x), Q(x')) <= int_0^L min(h_k Mz, 2) ds,   Mz = sup |d theta/dk| at fixed z,
// and the same bounds the chord's move. x' lies in a box of the centre modulus only (zero k
// width) centred at the box's centre with the rate and phase ranges widened by the change of
// rho; any deviation bound of that box (D, the closed-form R, the chart's Rt, the chord's) then
// completes the triangle inequality. The k change of the box is thereby split into a bounded k
// change, a rate change and a phase shift (which, at a fixed rate, moves Q only at the ends).
#pragma once

#include <limits>

#include "certify/vocabulary.h"

namespace plateball::internal {

/// sup |d theta/dk| at a fixed normalised phase z = v / K(k) over moduli in [k_min, k_max], k_max < 1
/// (+infinity otherwise): from |d am/dk| <= (k/2 + |Z|/k) / k'^2 at k_max, |Z| / k <=
/// JacobiZetaOverModulusBound (min(k K/2, E/k): near k = 1 the bound grows like 1/k'^2 only, so
/// in lambda = -ln k' (dk = k'^2/k dlambda) it is uniform up to the separatrix).
double HeadingModulusBoundAtFixedPeriods(PendulumRegime regime, double k_min, double k_max);

/// The box of the points x' = (rate rho, k_c, u0 rho, L), rho = K(k_c) / K(k), of every point of
/// `box`: centred at the box's centre, of zero width in k (rounding of K covered).
CertifyBox FixedPeriodsBox(const CertifyBox& box);

/// The k share of the comparison: L_max min(h_k Mz, 2), a bound on dist(Q(x), Q(x')) and on
/// |chord(x) - chord(x')|.
double FixedPeriodsModulusShare(PendulumRegime regime, const CertifyBox& box);

/// The bound D compared at a fixed number of periods: the k share plus D of FixedPeriodsBox, and
/// its per-axis shares (optional; the k share takes the widening of the rate and phase ranges).
double FixedPeriodsDeviationBound(PendulumRegime regime, const CertifyBox& box, CertifyPoint* contributions = nullptr);

/// Bound on the rotation distance between Q(0, L) of any point of the box and Q(0, Lc) of its
/// centre: the k share plus the smallest of D, R (with `closed_rolling`) and Rt (with
/// `chart_rolling`) of FixedPeriodsBox; R and Rt are skipped when D's already attains stop_above.
double FixedPeriodsRollingDeviationBound(PendulumRegime regime,
                                         const CertifyBox& box,
                                         double margin,
                                         bool closed_rolling,
                                         bool chart_rolling,
                                         double stop_above = std::numeric_limits<double>::infinity());

/// Bound on the distance between the chord of any point of the box and the centre's: the k share
/// plus the smaller of D and ChordDeviationBound of FixedPeriodsBox.
double FixedPeriodsChordDeviationBound(PendulumRegime regime, const CertifyBox& box);

/// The chord and rotation tests (TestBox) of a box the tests with D, R and Rt leave undecided,
/// redone with the chord bound min(chord_deviation, FixedPeriodsChordDeviationBound) and the
/// rolling bound FixedPeriodsRollingDeviationBound (stopped at min(deviation, slack)).
BoxVerdict FixedPeriodsTest(const CertifyWindowOptions& options,
                            const CertifyBox& box,
                            const CertifyResidual& centre,
                            double deviation,
                            double chord_deviation);

}  // namespace plateball::internal
