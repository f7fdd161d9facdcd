// Identity targets of the isoparallel problem (section 2.2, Figure 7): every solution is a
// one-parameter family, and the families are the roots of one scalar function of one variable.
//
// Costate transport. Along an optimal path the costate v = (W - e3 x x', curvature) obeys
// v' = (e3 x x') x v, the equation of the rolling itself, so v(s) = Q(0, s) v(0) (W is the
// constant horizontal vector of elastica.h). If the rolling returns the ball to its orientation,
// Q(0, L) = I, then v(L) = v(0): the heading and the curvature return, and L is a whole number m
// of curvature periods T (the pendulum only repeats its state after whole periods; straight lines
// and circles are checked separately). So, for A1 = A0, there are no isolated solutions: every
// solution covers m whole periods, and then P^m = I for the one-period rolling P at any starting
// phase (a family).
//
// The same transport gives P v(0) = v(0): the axis of P is v(0), so P = exp(phi hat(n)),
// n = v(0)/|v(0)|, with phi a smooth signed angle. P^m = I iff m phi = 2 pi j for an integer j:
// ONE equation. The chord fixes the scale: m |drift per period| = |x1 - x0|, so for each regime
// (oscillating, rotating) and m the unknown is the modulus k alone, and the path length
// L(k) = |x1 - x0| T / |drift| does not depend on m. The search samples m phi(k) adaptively in
// xi = atanh(k) over the k where L(k) <= max_length, brackets every crossing of a level 2 pi j,
// refines it (TOMS 748 on coarse Magnus rollings, then secant steps on accurate ones) and
// increases m until a certificate holds for several m in a row: |m phi - Phi_inf| stays below
// the distance from |x1 - x0| to 2 pi Z at every sample, where Phi_inf = +-|x1 - x0| is the
// limit of many small periods (rolling along the chord). See docs/paper_notes.md.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "plateball/elastica.h"
#include "plateball/export.h"

namespace plateball PLATEBALL_EXPORT {

/// Options of EnumerateIdentityFamilies.
struct FamilySearchOptions {
  /// Longest family searched; clamped to max(64 chord, 200) (then `complete` stays false
  /// unless the length cap shrank below the clamp).
  double max_length = 0.0;
  /// When > 0, the search also stops at this factor times the shortest family found so far
  /// (the length cap of the isoparallel solver; families beyond it are not reported).
  double length_cap_factor = 0.0;
  double tolerance = 1e-12;  ///< accepted |m phi - 2 pi j| of a family (radians)
  double cell = 0.5;         ///< initial sampling step in xi = atanh(k) (refined adaptively)
  int max_periods = 512;     ///< largest m examined if the certificate never holds
  int certified_run = 3;     ///< consecutive certified m (no roots possible) that end the search
  int threads = 1;           ///< worker threads (the two regimes, the polishing; results do not depend on it)
  /// Called after each period count m is finished, with m (for a tool's progress line).
  std::function<void(int)> progress;
  /// Empty when valid, else a message naming the field, the value and the bound.
  std::string Validate() const;
};

/// One family: m periods of the elastica with modulus k whose drift over m periods is the chord.
/// Phase 0 is the canonical member; every phase gives a solution of the same length.
/// Rotating families come in mirror pairs (rate and -rate); `rate` here is positive.
struct ElasticaFamily {
  PendulumRegime regime = PendulumRegime::kOscillating;
  double modulus = 0.0;   ///< k
  double rate = 0.0;      ///< b = sqrt(G) (oscillating) or a = sqrt(G)/k (rotating), > 0
  int periods = 0;        ///< m (0 for the straight segment, when |x1 - x0| is a multiple of 2 pi)
  int winding = 0;        ///< j: m phi = 2 pi j
  double length = 0.0;    ///< m T
  double residual = 0.0;  ///< |m phi - 2 pi j| with the accurate rolling (radians)

  /// The elastica in the pendulum frame (W along +y, heading 0 at s = 0; phase 0).
  ElasticaParameters Parameters() const;
};

struct FamilySearch {
  std::vector<ElasticaFamily> families;  ///< up to max_length, sorted by length
  int periods_searched = 0;              ///< largest m examined (either regime)
  double searched_length = 0.0;          ///< final length cap: every family up to it is reported
  bool complete = false;                 ///< the certificate ended the search in both regimes
  long evaluations = 0;                  ///< one-period rollings computed
};

/// All identity-target families with chord |x1 - x0| = chord and length <= options.max_length.
/// Throws std::invalid_argument naming the field for a non-positive or non-finite chord or
/// invalid options.
FamilySearch EnumerateIdentityFamilies(double chord, const FamilySearchOptions& options);

/// phi: the signed rotation angle of P about n (|n| = 1), in (-pi, pi]; exact when n is P's axis.
double SignedRotationAngle(const Eigen::Matrix3d& p, const Eigen::Vector3d& n);

/// The costate v(0) = (W - e3 x x'(0), curvature(0)) of an elastica: the axis of its
/// one-period rolling, and transported by the rolling, v(s) = Q(0, s) v(0).
Eigen::Vector3d ElasticaCostate(const Elastica& e, double s);

}  // namespace PLATEBALL_EXPORT
