// Internal: the certificate's vocabulary, below every test and driver in src/certify/: parameter
// boxes over ALL shape parameters (rate, modulus k, phase u0, length L), the target and residual
// of an isoparallel problem, the rigorous zeroth-order exclusion bounds over a box, and the
// window's options ("General targets: certified, not statistical"; docs/paper_notes.md, "General
// targets: certified exclusion over parameter boxes"). The branch and bound that uses them is
// certify/window.h.
//
// The residual is the rotation trick of section 2.2 with a free length: roll the ball along the
// elastica (heading_w = pi/2, path from s = 0 to L), B = RotationZ(goal_angle - arg chord),
//   chord residual    |chord| - |x1 - x0|,
//   rotation residual angle of target^T B Q(0, L) B^T   (target = A1 A0^-1).
// Both are invariant under a common rotation of the plane, so the heading_w of the parameters
// does not matter. The bounds (derived in the notes):
//   - rolling comparison: two paths with headings g1, g2 roll to rotations at most
//     int_0^L 2 |sin((g1 - g2) / 2)| ds apart, and their chords differ by at most the same;
//   - heading derivatives: |d theta/dv| <= 2k (oscillating), 2 (rotating), v = rate s + u0, and
//     |d am/dk| <= k (1/2 + |v|) / k'^2 (from d am/dk = [k sn cn - dn (E(am v) - k'^2 v) / k] / k'^2
//     and E(am v) - k'^2 v = k^2 int_0^v cn^2), or through a fixed number of periods (Jacobi's
//     zeta, |Z| <= min(k^2 K/2, E)) (k/2 + |Z|/k + k (1 - D/K) |v|) / k'^2, D = (K - E)/k^2: D of a box
//     takes the smaller;
//   - the chord's direction moves by at most asin(D / |chord|), and the conjugation by B moves
//     the rotation by at most twice that.
// The box test is rigorous up to the floating-point error of the centre's residual (the rolling
// in closed form, ~1e-13), covered by a stated margin.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "plateball/elastica.h"
#include "plateball/isoparallel.h"

namespace plateball::internal {

/// +infinity: the bound of a box or a piece that no test decided.
inline constexpr double kInfinity = std::numeric_limits<double>::infinity();

/// Coordinates of a parameter box: rate, modulus k (>= 0), phase u0, length L.
enum CertifyAxis { kCertifyRate = 0, kCertifyModulus = 1, kCertifyPhase = 2, kCertifyLength = 3 };
using CertifyPoint = std::array<double, 4>;

struct CertifyBox {
  CertifyPoint lo{}, hi{};
  CertifyPoint Centre() const;
  double HalfWidth(int axis) const { return 0.5 * (hi[axis] - lo[axis]); }
};

/// The period of v = rate s + u0 after which the path repeats up to a rotation of the plane:
/// 4 K(k) oscillating, 2 K(k) rotating.
double PhasePeriod(PendulumRegime regime, double k);

/// sup |v| = |rate s + phase| over the box's rates and phases at arc length s >= 0: the largest
/// modulus of the affine form, at a corner (a phase of the opposite sign to the rate offsets it,
/// where |rate|_max s + |phase|_max does not).
double ArgumentBound(const CertifyBox& box, double s);
/// sup |v| over the box and arc lengths s in [s_lo, s_hi] (0 <= s_lo <= s_hi): ArgumentBound is a
/// maximum of |affine| in s, so convex, and its sup over an interval is at one of the two ends.
double ArgumentBoundOver(const CertifyBox& box, double s_lo, double s_hi);
/// sup |u0 + rate L| over the box: the argument at the path's end, ArgumentBoundOver the box's
/// lengths (at most |phase|_max + |rate|_max L_max).
double EndArgumentBound(const CertifyBox& box);
/// The slope c of the chord |phase|_max + c s of ArgumentBound over [0, length] (length > 0): by
/// convexity sup |v| <= |phase|_max + c s there. c <= |rate|_max, and c < 0 where the phase
/// opposes the rate (the bound that was |phase|_max + |rate|_max s).
double ArgumentChordSlope(const CertifyBox& box, double length);

/// sup |d theta / dv| over moduli in [0, k_max] (theta the pendulum angle, v = rate s + u0).
double HeadingRateBound(PendulumRegime regime, double k_max);
/// sup |d theta / dk| at fixed v over moduli in [0, k_max] and |v| <= v_max (k_max < 1): from
/// |d am/dk| <= k (1/2 + |v|) / k'^2, oscillating with dn >= k' alone (2 (1 + k am_k) / k').
double HeadingModulusBound(PendulumRegime regime, double k_max, double v_max);
/// A second bound on the same sup over moduli in [k_min, k_max], from d am/dk at a fixed number of
/// periods (Jacobi's zeta, |Z| / k <= JacobiZetaOverModulusBound) plus the period's change: a
/// larger constant, a secular slope smaller by the factor 1 - D/K <= 1/2 (D = (K - E) / k^2, taken
/// at k_min).
double HeadingModulusBoundByZeta(PendulumRegime regime, double k_min, double k_max, double v_max);
/// sup |Z(v, k)| / k over every v and k in [k_min, k_max] (Jacobi's zeta Z = E(am v) - (E/K) v):
/// the smaller of k_max K(k_max) / 2 (|Z'| <= k^2, Z(0) = Z(K) = 0) and E(k_min) / k_min (on
/// [0, K] both terms of Z lie in [0, E]; Z is odd and 2K-periodic), which stays bounded as k -> 1.
double JacobiZetaOverModulusBound(double k_min, double k_max);
/// sup |d theta/dk| over moduli in [k_min, k_max] from a bound am_k on |d am/dk| there (along any
/// path in (v, k)): 2 am_k rotating (theta = 2 am); oscillating (theta = 2 asin(k sn)) the smaller of
/// 2 (1 + k_max am_k) / k' and 2 (1/k' + am_k) (|sn| / dn <= 1/k', k |cn| / dn <= 1), k' at k_max.
double HeadingModulusFromAmplitude(PendulumRegime regime, double k_max, double am_k);

/// Bound D on both the rotation distance between Q(0, L) of any point of the box and Q(0, Lc) of
/// its centre, and on the distance between their chords. `contributions` (optional) receives the
/// uncapped share of each axis (for choosing the axis to split).
double RollingDeviationBound(PendulumRegime regime, const CertifyBox& box, CertifyPoint* contributions = nullptr);
/// The same bound D for a given constant bound `modulus_bound` on |d theta/dk| over the box (the
/// separatrix tail uses HeadingModulusBoundNearSeparatrix, valid for moduli up to k = 1).
double RollingDeviationBoundFor(PendulumRegime regime,
                                const CertifyBox& box,
                                double modulus_bound,
                                CertifyPoint* contributions = nullptr);

/// The target of a general isoparallel problem, in the form the residual uses.
struct CertifyTarget {
  Eigen::Matrix3d target = Eigen::Matrix3d::Identity();  // A1 A0^-1
  double radius = 1.0;                                   // |x1 - x0|
  double goal_angle = 0.0;                               // direction of x1 - x0
};

/// The certificate's form of an isoparallel problem (target A1 A0^-1, |x1 - x0|, arg(x1 - x0)).
CertifyTarget CertifyTargetOf(const IsoparallelProblem& problem);

struct CertifyResidual {
  double chord_norm = 0.0;  // |chord|
  double chord_miss = 0.0;  // |chord| - radius
  double rotation = 0.0;    // rotation residual angle (rad)
};

/// The elastica of a parameter point (heading_w = pi/2; the residual does not depend on it).
/// Throws std::invalid_argument like Elastica for |k| >= 1 or non-finite values.
Elastica CertifyElastica(PendulumRegime regime, const CertifyPoint& x);

/// The free-length residual at one parameter point (closed-form chord, closed-form rolling:
/// ElasticaClosedRolling; max_step is no longer used here and kept for the callers). False for an
/// inadmissible point (k >= 1, L <= 0, rate * L overflowing).
bool EvaluateCertifyResidual(
    const CertifyTarget& target, PendulumRegime regime, const CertifyPoint& x, double max_step, CertifyResidual* out);

enum class BoxVerdict { kNotRun, kExcludedByChord, kExcludedByRotation, kExcludedByCostate, kUndecided };
std::string ToString(BoxVerdict verdict);

/// The exclusion test: the centre's residual against the deviation bound D (plus `margin` for the
/// centre's floating-point error). kExcluded* means no solution lies in the box.
BoxVerdict TestBox(const CertifyResidual& centre, double deviation, double margin);
/// The same test with separate bounds: `deviation` on the rotation distance of Q(0, L) to the
/// centre's, `chord_deviation` on the distance of the chord to the centre's (the smaller of D and
/// ChordDeviationBound, certify/costate.h), used for the chord miss and its turn.
BoxVerdict TestBox(const CertifyResidual& centre, double deviation, double chord_deviation, double margin);
/// The rotation test's slack: the box is excluded by rotation when the bound on Q's move is below
/// it (the centre's rotation residual minus twice the chord's turn and 3 margin; -infinity when
/// chord_deviation + margin reaches |chord_c|).
double RotationSlack(const CertifyResidual& centre, double chord_deviation, double margin);

/// One box the branch and bound splits (left undecided by every test), for diagnostics: its
/// deviation bound D and the per-axis shares of D, and when the first-order tests ran, the
/// per-axis columns of the Krawczyk contraction times the half-widths (zero otherwise).
struct CertifyBoxTrace {
  CertifyBox box;
  double deviation = 0.0;
  CertifyPoint share{};
  CertifyPoint contraction{};
  int split_axis = -1;
};

/// The largest modulus a window may reach (k' ~ 4.5e-5; the separatrix's loop family takes over
/// below that k').
inline constexpr double kMaxWindowModulus = 1.0 - 1e-9;

/// The modulus at which a box [k_lo, k_hi] is split: sqrt(1 - k'_lo k'_hi) (the midpoint in
/// lambda = -ln k') when k_lo >= log_split, the arithmetic midpoint otherwise (or when rounding
/// leaves the geometric one outside (k_lo, k_hi)).
double ModulusSplitPoint(double k_lo, double k_hi, double log_split);

/// A request to stop (Ctrl-C), asked by the box loops (CertifyWindow, Bisect) from the thread
/// that runs them, before their first box and then every kInterruptPollBoxes boxes: true stops
/// the loop at once with the status "interrupted" (nothing claimed). Empty: never asked.
using CertifyInterrupt = std::function<bool()>;
/// About 10 ms of boxes at the certificate's 2-10 us per box: the stop is prompt, the hook cheap.
inline constexpr long kInterruptPollBoxes = 1024;
/// Whether a loop that has examined `boxes` boxes must stop now (asks `interrupt` every
/// kInterruptPollBoxes boxes, from 0 on).
inline bool InterruptRequested(const CertifyInterrupt& interrupt, long boxes) {
  return interrupt && boxes % kInterruptPollBoxes == 0 && interrupt();
}

struct CertifyWindowOptions {
  PendulumRegime regime = PendulumRegime::kOscillating;
  CertifyBox window;               // rate, k in [0, kMaxWindowModulus], phase, L > 0
  long max_boxes = 1000000;        // budget of examined boxes
  double accept_deviation = 1e-3;  // an undecided box with D below this must meet a neighbourhood
  /// Half-widths (rate, k, phase, length) of the neighbourhood of each known solution that is not
  /// searched: the certificate states that every solution of the window lies in one of them.
  CertifyPoint match = {0.01, 0.005, 0.02, 0.02};
  bool stop_at_unaccounted = true;  // a failed certificate needs no further boxes
  double margin = 1e-7;             // floating-point margin on the centre's residual (rad, length)
  double max_step = 0.05;           // Magnus step of the centre's rolling
  /// First-order tests (certify/jacobian.h) on boxes the zeroth-order test leaves
  /// undecided once D <= first_order_deviation: mean-value exclusion and Krawczyk. A box with
  /// exactly one solution is a found solution (refined by Newton, reported in `found`); boxes
  /// are then split down to D <= first_order_min_deviation before they count as undecided.
  bool first_order = false;
  double first_order_deviation = 0.5;
  double first_order_min_deviation = 1e-9;
  /// Added to CertifyResidualError(box) (certify/jacobian.h), the bound on the error
  /// of the centre's residual components that the first-order tests allow for.
  double first_order_margin = 0.0;
  /// The costate test (certify/costate.h) on boxes the chord and rotation tests leave
  /// undecided: rigorous, no rolling (~ a closed-form chord and two costates per box).
  bool costate = true;
  /// The rotation test's bound on the rolling is min(D, ClosedRollingDeviationBound)
  /// (certify/rolling.h: from the closed-form rolling, linear in L) on boxes D leaves
  /// undecided: rigorous, ~ two costates per box.
  bool closed_rolling = true;
  /// Then min(D, ChartRollingDeviationBound) (the theta/2 chart, certify/rolling.h:
  /// smooth and finite through G = 1, linear in L) on boxes still undecided: rigorous.
  bool chart_rolling = true;
  /// Then min(D, CentredRollingDeviationBound) (a centred form: the closed-form rolling at the
  /// box's vertices plus a second-order remainder, certify/centred.h) on boxes still
  /// undecided: rigorous.
  bool centred_rolling = true;
  /// Then the chord and rotation tests with the bounds compared at a fixed number of periods
  /// (certify/periods.h: a k change split into a bounded one at fixed rate / K and
  /// u0 / K, a rate change and a phase shift) on boxes still undecided: rigorous. A box is then
  /// also split along the largest share of FixedPeriodsDeviationBound where it is below D (the
  /// trace's shares are those).
  bool fixed_periods = true;
  /// A box with k_lo >= log_modulus_split is split in k at the geometric mean of k' = sqrt(1 - k^2)
  /// (the midpoint in lambda = -ln k', where the fixed-periods k share is uniform up to k = 1)
  /// instead of the arithmetic midpoint; in [0, 1], 1 = never.
  double log_modulus_split = 1.0;
  std::function<void(const CertifyBoxTrace&)> trace;  // if set: called for every box split
  CertifyInterrupt interrupted;                       // if set: asked every kInterruptPollBoxes boxes (kInterrupted)
  std::string Validate() const;
};

/// Two proved solutions closer than this in every canonical coordinate (the phase modulo its
/// period) are one path (Newton refines them to |F| < 1e-11).
inline constexpr double kSamePathTolerance = 1e-6;

/// A solution (rate, modulus, phase, length) in the window's canonical form: k >= 0, the phase
/// in [0, period) of v (4K oscillating, 2K rotating), an oscillating path with a negative rate
/// written with a positive one (same heading up to sign conventions: the same path).
CertifyPoint CanonicalSolution(const ElasticaParameters& parameters, double length);

/// Whether two canonical solutions are the same path: every coordinate within `tolerance`, the
/// phase compared modulo its period (a path near the end of the period is also near its start).
bool SamePath(PendulumRegime regime, const CertifyPoint& a, const CertifyPoint& b, double tolerance);

/// The largest magnitude over the interval with ends a and b.
inline double MaxAbs(double a, double b) { return std::max(std::abs(a), std::abs(b)); }

}  // namespace plateball::internal
