// Internal: the depth-first bisection the tail certificates share (the slow separatrix tail,
// certify/separatrix.h, and the fast tail loop by loop, certify/loops.h).
// Each certificate decides a box (excluded by the chord or the rotation test, outside the
// family's domain, undecided but small enough to report, or to be split along an axis); this
// file keeps the stack, the budget, the counts, the resolved volume and the status.
#pragma once

#include <string>
#include <vector>

#include "certify/vocabulary.h"

namespace plateball::internal {

/// The outcome of an exclusion certificate over a bounded window.
enum class ExclusionStatus { kNotRun, kExcluded, kUndecided, kBudgetExhausted, kInvalidInput, kInterrupted };
std::string ToString(ExclusionStatus status);

/// The budget fields both certificates validate: "" when valid, else the message naming the field.
std::string ValidateBisectionBudget(long max_boxes, double accept_deviation, int keep_undecided, double margin);

/// What a certificate decided for one box.
enum class BoxFate { kExcludedByChord, kExcludedByRotation, kOutsideDomain, kUndecided, kSplit };
struct BoxDecision {
  BoxFate fate = BoxFate::kSplit;
  int split_axis = 0;  // for kSplit
};
/// kExcludedByChord / kExcludedByRotation from the box test's verdict; otherwise kUndecided when
/// the deviation is at most `accept_deviation`, else a split along the largest share.
BoxDecision DecideByVerdict(BoxVerdict verdict, double deviation, double accept_deviation, const CertifyPoint& shares);

struct BisectionTally {
  long boxes = 0;
  long excluded_by_chord = 0, excluded_by_rotation = 0, outside_domain = 0, undecided = 0;
  double resolved_volume = 0.0;  // the excluded and outside boxes' shares of their windows, weighted
  bool budget_left = true;       // false when the budget ended with boxes left
  bool interrupted = false;      // the CertifyInterrupt stopped the bisection
  ExclusionStatus Status() const;
};

/// The box's share of `window` (the box inside it): the product of width ratios over the axes on
/// which the window has a positive width. A window of zero width on an axis (a loop family whose
/// shortest run already reaches the cap) is measured on its other axes, so that a decided
/// degenerate window counts as wholly resolved instead of 0/0.
double BoxShare(const CertifyBox& box, const CertifyBox& window);

/// Bisects `window` depth first (left half first) until every box is decided or `max_boxes`
/// boxes (counted over every call on `tally`) have been examined. `decide(box)` returns a
/// BoxDecision; `keep(box)` is called for every kUndecided box. Each decided box adds `weight`
/// times its BoxShare of the window to the resolved volume (weight 1/2 for each of two calls
/// that make one whole, as the loop family's two senses). `interrupt` (InterruptRequested) stops
/// it, and every later call on the same tally, with tally->interrupted set.
template <class Decide, class Keep>
void Bisect(const CertifyBox& window,
            double weight,
            long max_boxes,
            Decide&& decide,
            Keep&& keep,
            const CertifyInterrupt& interrupt,
            BisectionTally* tally) {
  std::vector<CertifyBox> stack = {window};
  while (!stack.empty() && tally->boxes < max_boxes) {
    if (tally->interrupted || (tally->interrupted = InterruptRequested(interrupt, tally->boxes))) break;
    const CertifyBox box = stack.back();
    stack.pop_back();
    ++tally->boxes;
    const BoxDecision decision = decide(box);
    switch (decision.fate) {
      case BoxFate::kExcludedByChord:
        ++tally->excluded_by_chord;
        break;
      case BoxFate::kExcludedByRotation:
        ++tally->excluded_by_rotation;
        break;
      case BoxFate::kOutsideDomain:
        ++tally->outside_domain;
        break;
      case BoxFate::kUndecided:
        ++tally->undecided, keep(box);
        continue;
      case BoxFate::kSplit: {
        const int axis = decision.split_axis;
        const double mid = 0.5 * (box.lo[axis] + box.hi[axis]);
        CertifyBox left = box, right = box;
        left.hi[axis] = mid;
        right.lo[axis] = mid;
        stack.push_back(right);
        stack.push_back(left);
        continue;
      }
    }
    tally->resolved_volume += weight * BoxShare(box, window);
  }
  if (!stack.empty()) tally->budget_left = false;
}

}  // namespace plateball::internal
