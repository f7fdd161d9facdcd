// Internal: the separatrix tail k in [k_lo, 1) of the certified exclusion for general isoparallel
// targets (docs/paper_notes.md, "General targets: the separatrix tail").
//
// Every path of the tail at modulus k, rate a (|a| <= A) and length L <= cap starts, modulo the
// period of v (2K rotating, 4K oscillating with the mirrored loop at v = 2K written as
// (rate, phase) -> (-rate, -phase)), either
//   - in a run: its whole v-range stays at least W from every loop centre; its heading is then
//     within eta(W) of one direction (rotating 2 asin(sech W), oscillating asin(sech W)) and the
//     straight-run lemma excludes it when StraightRunDeviationBound(eta, cap, |x1 - x0|) is below
//     the straight residual delta0 (minus a margin); W = SeparatrixRunDistance;
//   - or near a loop: phase u0 in [-W - A cap, W + A cap] from the loop centre v = 0. There the
//     modulus bound uniform up to the separatrix (|d theta/dk| <= HeadingModulusBoundNearSeparatrix
//     on the box's v-range) makes the window k in [k_lo, 1] (closed) a bounded box, searched by
//     the branch and bound below (CertifySeparatrixTail).
// Rates |a| > A are not covered here (the averaging bound a_max(k) grows like sqrt(K(k)) and is
// infinite at k = 1).
#pragma once

#include <string>
#include <vector>

#include "certify/bisection.h"
#include "certify/vocabulary.h"
#include "plateball/elastica.h"

namespace plateball::internal {

/// The half-width of the heading's range on a run at distance >= w (in v) from every loop centre,
/// for every modulus k < 1 with K(k) >= w: rotating 2 asin(sech w), oscillating asin(sech w).
double SeparatrixRunHeadingSpread(PendulumRegime regime, double w);

/// The smallest distance W (bisection, to 1e-9 relative, rounded up) such that every run of
/// length <= cap at distance >= W from every loop is excluded by the straight-run lemma;
/// +inf when even a straight path is not excluded (delta0 <= margin).
double SeparatrixRunDistance(const CertifyTarget& target, PendulumRegime regime, double cap, double margin);

/// The deviation bound D of a box with k in [k_lo, k_hi], k_hi <= 1 (phase from a loop centre):
/// RollingDeviationBoundFor with the modulus bound uniform up to the separatrix on the box's
/// v-range |v| <= max |u0| + max |rate| max L.
double SeparatrixDeviationBound(PendulumRegime regime, const CertifyBox& box, CertifyPoint* contributions = nullptr);

struct SeparatrixTailOptions {
  PendulumRegime regime = PendulumRegime::kRotating;
  double k_lo = 0.95;      // the tail is k in [k_lo, 1)
  double rate_max = 0.5;   // A: rates in [-A, A]
  double length_lo = 0.0;  // L in [length_lo, cap] (length_lo >= 0; L = 0 is no path)
  double cap = 1.0;
  long max_boxes = 1000000;
  double accept_deviation = 1e-3;  // an undecided box with D below this is reported, not split
  int keep_undecided = 16;         // how many undecided boxes to keep in the result
  double margin = 1e-7;            // on the centre residual (as CertifyWindowOptions)
  double max_step = 0.05;
  CertifyInterrupt interrupted;  // if set: asked every kInterruptPollBoxes boxes (kInterrupted)
  std::string Validate() const;
};

using SeparatrixTailStatus = ExclusionStatus;  // ToString in certify/bisection.h

struct SeparatrixTailResult {
  SeparatrixTailStatus status = SeparatrixTailStatus::kNotRun;
  double run_distance = 0.0;  // W (runs beyond it are excluded by the straight-run lemma)
  CertifyBox window;          // the near-loop window searched (k in [k_lo, 1])
  long boxes = 0;
  long excluded_by_chord = 0, excluded_by_rotation = 0;
  long undecided = 0;                       // boxes with D <= accept_deviation not excluded
  std::vector<CertifyBox> undecided_boxes;  // the first keep_undecided of them
  double resolved_volume = 0.0;             // fraction of the window excluded
  std::string message;
  bool Excluded() const { return status == SeparatrixTailStatus::kExcluded; }
};

/// The tail certificate: kExcluded means no solution with k in [k_lo, 1), |rate| <= rate_max and
/// length in [length_lo, cap] (rigorous up to `margin` on the centre residuals). kUndecided: the
/// listed small boxes may hold solutions (everything else of that set is excluded).
SeparatrixTailResult CertifySeparatrixTail(const CertifyTarget& target, const SeparatrixTailOptions& options);

}  // namespace plateball::internal
