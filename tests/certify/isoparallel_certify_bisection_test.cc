// The bisection shared by the tail certificates (src/certify/bisection.h): counts,
// resolved volume, order, budget and status on a window whose decisions are known by hand.
#include <gtest/gtest.h>

#include <vector>

#include "certify/bisection.h"

namespace plateball::internal {
namespace {

// Along axis 0 of [0, 1]^4 (the other axes have widths 1, 2, 3, so the volume is 6): boxes ending
// by 0.25 are excluded by the chord, boxes starting from 0.75 by the rotation, boxes of width
// <= 1/8 are undecided, the rest is split along axis 0. By hand (left first): [0, 1], [0, .5],
// [0, .25] chord, [.25, .5], [.25, .375] and [.375, .5] undecided, [.5, 1], [.5, .75], [.5, .625]
// and [.625, .75] undecided, [.75, 1] rotation: 11 boxes, resolved volume 1/2.
BoxDecision DecideAlongAxisZero(const CertifyBox& box) {
  if (box.hi[0] <= 0.25) return {BoxFate::kExcludedByChord};
  if (box.lo[0] >= 0.75) return {BoxFate::kExcludedByRotation};
  if (box.hi[0] - box.lo[0] <= 0.125) return {BoxFate::kUndecided};
  return {BoxFate::kSplit, 0};
}

CertifyBox Window() {
  CertifyBox w;
  w.lo = {0.0, 0.0, 0.0, 0.0};
  w.hi = {1.0, 1.0, 2.0, 3.0};
  return w;
}

TEST(IsoparallelCertifyBisection, CountsVolumeAndOrderMatchTheHandCount) {
  BisectionTally tally;
  std::vector<double> kept;
  Bisect(
      Window(), 1.0, 1000, DecideAlongAxisZero, [&](const CertifyBox& box) { kept.push_back(box.lo[0]); }, {}, &tally);
  EXPECT_EQ(tally.boxes, 11);
  EXPECT_EQ(tally.excluded_by_chord, 1);
  EXPECT_EQ(tally.excluded_by_rotation, 1);
  EXPECT_EQ(tally.outside_domain, 0);
  EXPECT_EQ(tally.undecided, 4);
  EXPECT_DOUBLE_EQ(tally.resolved_volume, 0.5);
  EXPECT_EQ(kept, (std::vector<double>{0.25, 0.375, 0.5, 0.625}));
  EXPECT_EQ(tally.Status(), ExclusionStatus::kUndecided);
}

TEST(IsoparallelCertifyBisection, OutsideBoxesCountAsResolvedAndAWindowCanBeExcluded) {
  BisectionTally tally;
  const auto decide = [](const CertifyBox& box) {
    if (box.hi[0] <= 0.5) return BoxDecision{BoxFate::kOutsideDomain};
    if (box.lo[0] >= 0.5) return BoxDecision{BoxFate::kExcludedByRotation};
    return BoxDecision{BoxFate::kSplit, 0};
  };
  // Two calls on one tally (as the loop family's two senses), each of weight 1/2.
  for (int call = 0; call < 2; ++call)
    Bisect(
        Window(), 0.5, 1000, decide, [](const CertifyBox&) {}, {}, &tally);
  EXPECT_EQ(tally.boxes, 6);
  EXPECT_EQ(tally.outside_domain, 2);
  EXPECT_EQ(tally.excluded_by_rotation, 2);
  EXPECT_DOUBLE_EQ(tally.resolved_volume, 1.0);
  EXPECT_EQ(tally.Status(), ExclusionStatus::kExcluded);
  EXPECT_EQ(ToString(tally.Status()), "excluded");
}

// A window of zero width on an axis (the loop family's run range when its shortest run already
// reaches the cap) is measured on its other axes: excluded whole, it counts as resolved 1 (it was
// 0/0, a NaN that the tool's JSON writer refused). The share of a box is its width ratios there.
TEST(IsoparallelCertifyBisection, ADegenerateWindowIsMeasuredOnItsOtherAxes) {
  CertifyBox flat = Window();
  flat.hi[1] = flat.lo[1];
  BisectionTally tally;
  const auto decide = [](const CertifyBox& box) {
    return box.hi[0] - box.lo[0] <= 0.25 ? BoxDecision{BoxFate::kExcludedByRotation} : BoxDecision{BoxFate::kSplit, 0};
  };
  Bisect(
      flat, 1.0, 1000, decide, [](const CertifyBox&) {}, {}, &tally);
  EXPECT_EQ(tally.boxes, 7);
  EXPECT_EQ(tally.excluded_by_rotation, 4);
  EXPECT_DOUBLE_EQ(tally.resolved_volume, 1.0);
  CertifyBox quarter = flat;
  quarter.hi[0] = 0.25;
  quarter.hi[2] = 1.0;
  EXPECT_DOUBLE_EQ(BoxShare(quarter, flat), 0.125);    // 1/4 along axis 0, 1/2 along axis 2
  EXPECT_DOUBLE_EQ(BoxShare(quarter, Window()), 0.0);  // zero width inside a full window
}

TEST(IsoparallelCertifyBisection, TheBudgetCountsOverCallsAndEndsWithBudgetExhausted) {
  BisectionTally tally;
  Bisect(
      Window(), 1.0, 5, DecideAlongAxisZero, [](const CertifyBox&) {}, {}, &tally);
  EXPECT_EQ(tally.boxes, 5);
  EXPECT_EQ(tally.Status(), ExclusionStatus::kBudgetExhausted);
  BisectionTally second = tally;
  second.budget_left = true;
  Bisect(
      Window(), 1.0, 5, DecideAlongAxisZero, [](const CertifyBox&) {}, {}, &second);
  EXPECT_EQ(second.boxes, 5);  // no box left in the budget: the window stays on the stack
  EXPECT_EQ(second.Status(), ExclusionStatus::kBudgetExhausted);
}

// The interrupt is asked before the first box and then every kInterruptPollBoxes boxes: a
// bisection that would split for ever (10^6 boxes of budget) stops after exactly two rounds of
// boxes when the third question says stop, with the status "interrupted"; a later call on the same
// tally (the loop family's second sense) examines nothing and does not ask again.
TEST(IsoparallelCertifyBisection, AnInterruptStopsAtTheNextPollAndLaterCallsOnTheTally) {
  const auto split_for_ever = [](const CertifyBox&) { return BoxDecision{BoxFate::kSplit, 0}; };
  int asked = 0;
  const CertifyInterrupt third = [&] { return ++asked == 3; };
  BisectionTally tally;
  Bisect(
      Window(), 0.5, 1000000, split_for_ever, [](const CertifyBox&) {}, third, &tally);
  EXPECT_EQ(asked, 3);
  EXPECT_EQ(tally.boxes, 2 * kInterruptPollBoxes);
  EXPECT_TRUE(tally.interrupted);
  EXPECT_EQ(tally.Status(), ExclusionStatus::kInterrupted);
  EXPECT_EQ(ToString(tally.Status()), "interrupted");
  Bisect(
      Window(), 0.5, 1000000, split_for_ever, [](const CertifyBox&) {}, third, &tally);
  EXPECT_EQ(asked, 3);
  EXPECT_EQ(tally.boxes, 2 * kInterruptPollBoxes);
  // Set before the start: no box at all.
  BisectionTally first;
  Bisect(
      Window(), 1.0, 1000000, split_for_ever, [](const CertifyBox&) {}, [] { return true; }, &first);
  EXPECT_EQ(first.boxes, 0);
  EXPECT_EQ(first.Status(), ExclusionStatus::kInterrupted);
}

TEST(IsoparallelCertifyBisection, VerdictsMapToFatesAndSplitsFollowTheLargestShare) {
  const CertifyPoint shares = {0.1, 0.4, 0.3, 0.2};
  EXPECT_EQ(DecideByVerdict(BoxVerdict::kExcludedByChord, 1.0, 1e-3, shares).fate, BoxFate::kExcludedByChord);
  EXPECT_EQ(DecideByVerdict(BoxVerdict::kExcludedByRotation, 1.0, 1e-3, shares).fate, BoxFate::kExcludedByRotation);
  EXPECT_EQ(DecideByVerdict(BoxVerdict::kExcludedByCostate, 1.0, 1e-3, shares).fate, BoxFate::kExcludedByRotation);
  EXPECT_EQ(DecideByVerdict(BoxVerdict::kUndecided, 1e-3, 1e-3, shares).fate, BoxFate::kUndecided);
  const BoxDecision split = DecideByVerdict(BoxVerdict::kUndecided, 2e-3, 1e-3, shares);
  EXPECT_EQ(split.fate, BoxFate::kSplit);
  EXPECT_EQ(split.split_axis, 1);
}

TEST(IsoparallelCertifyBisection, BadBudgetsAreRejectedByName) {
  EXPECT_EQ(ValidateBisectionBudget(1000, 1e-3, 16, 1e-7), "");
  EXPECT_NE(ValidateBisectionBudget(0, 1e-3, 16, 1e-7).find("max_boxes"), std::string::npos);
  EXPECT_NE(ValidateBisectionBudget(1000, 0.0, 16, 1e-7).find("accept_deviation"), std::string::npos);
  EXPECT_NE(ValidateBisectionBudget(1000, 1e-3, -1, 1e-7).find("keep_undecided"), std::string::npos);
  EXPECT_NE(ValidateBisectionBudget(1000, 1e-3, 16, 0.1).find("margin"), std::string::npos);
}

}  // namespace
}  // namespace plateball::internal
