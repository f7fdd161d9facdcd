#include "certify/bisection.h"

#include <algorithm>

#include "check.h"

namespace plateball::internal {

std::string ToString(ExclusionStatus status) {
  switch (status) {
    case ExclusionStatus::kNotRun:
      return "not run";
    case ExclusionStatus::kExcluded:
      return "excluded";
    case ExclusionStatus::kUndecided:
      return "undecided boxes remain";
    case ExclusionStatus::kBudgetExhausted:
      return "budget exhausted";
    case ExclusionStatus::kInvalidInput:
      return "invalid input";
    case ExclusionStatus::kInterrupted:
      return "interrupted";
  }
  return "unknown";
}

std::string ValidateBisectionBudget(long max_boxes, double accept_deviation, int keep_undecided, double margin) {
  if (!(max_boxes >= 1 && max_boxes <= 1000000000L))
    return InvalidValueMessage("max_boxes", static_cast<double>(max_boxes), "expected [1, 1e9]");
  if (!(accept_deviation > 0.0 && accept_deviation <= 1.0))
    return InvalidValueMessage("accept_deviation", accept_deviation, "expected (0, 1]");
  if (!(keep_undecided >= 0 && keep_undecided <= 100000))
    return InvalidValueMessage("keep_undecided", keep_undecided, "expected [0, 100000]");
  if (!(margin >= 0.0 && margin <= 1e-2)) return InvalidValueMessage("margin", margin, "expected [0, 0.01]");
  return "";
}

BoxDecision DecideByVerdict(BoxVerdict verdict, double deviation, double accept_deviation, const CertifyPoint& shares) {
  BoxDecision out;
  if (verdict == BoxVerdict::kExcludedByChord) {
    out.fate = BoxFate::kExcludedByChord;
  } else if (verdict != BoxVerdict::kUndecided) {
    out.fate = BoxFate::kExcludedByRotation;
  } else if (deviation <= accept_deviation) {
    out.fate = BoxFate::kUndecided;
  } else {
    out.split_axis = static_cast<int>(std::max_element(shares.begin(), shares.end()) - shares.begin());
  }
  return out;
}

ExclusionStatus BisectionTally::Status() const {
  return interrupted     ? ExclusionStatus::kInterrupted
         : !budget_left  ? ExclusionStatus::kBudgetExhausted
         : undecided > 0 ? ExclusionStatus::kUndecided
                         : ExclusionStatus::kExcluded;
}

double BoxShare(const CertifyBox& box, const CertifyBox& window) {
  double share = 1.0;
  for (int i = 0; i < 4; ++i) {
    const double width = window.hi[i] - window.lo[i];
    if (width > 0.0) share *= (box.hi[i] - box.lo[i]) / width;
  }
  return share;
}

}  // namespace plateball::internal
