// Internal: the depth-first bisection the tail certificates share (the slow separatrix tail,
// isoparallel_certify_separatrix.h, and the fast tail loop by loop, isoparallel_certify_loops.h).
// Each certificate decides a box (excluded by the chord or the rotation test, outside the
// family's domain, undecided but small enough to report, or to be split along an axis); this
// file keeps the stack, the budget, the counts, the resolved volume and the status.
#pragma once

#include <string>
#include <vector>

#include "isoparallel_certify.h"

namespace plateball::internal {

/// The outcome of an exclusion certificate over a bounded window.
enum class ExclusionStatus { kNotRun, kExcluded, kUndecided, kBudgetExhausted, kInvalidInput };
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
  double resolved_volume = 0.0;  // the excluded and outside boxes' volume over the normalising volume
  bool budget_left = true;       // false when the budget ended with boxes left
  ExclusionStatus Status() const;
};

/// The product of the box's widths.
double BoxWidthProduct(const CertifyBox& box);

/// Bisects `window` depth first (left half first) until every box is decided or `max_boxes`
/// boxes (counted over every call on `tally`) have been examined. `decide(box)` returns a
/// BoxDecision; `keep(box)` is called for every kUndecided box. Volumes are divided by
/// `normalising_volume`.
template <class Decide, class Keep>
void Bisect(const CertifyBox& window, double normalising_volume, long max_boxes, Decide&& decide, Keep&& keep,
            BisectionTally* tally) {
  std::vector<CertifyBox> stack = {window};
  while (!stack.empty() && tally->boxes < max_boxes) {
    const CertifyBox box = stack.back();
    stack.pop_back();
    ++tally->boxes;
    const BoxDecision decision = decide(box);
    switch (decision.fate) {
      case BoxFate::kExcludedByChord: ++tally->excluded_by_chord; break;
      case BoxFate::kExcludedByRotation: ++tally->excluded_by_rotation; break;
      case BoxFate::kOutsideDomain: ++tally->outside_domain; break;
      case BoxFate::kUndecided: ++tally->undecided, keep(box); continue;
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
    tally->resolved_volume += BoxWidthProduct(box) / normalising_volume;
  }
  if (!stack.empty()) tally->budget_left = false;
}

}  // namespace plateball::internal
