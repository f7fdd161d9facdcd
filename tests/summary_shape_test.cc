// The shape every solver summary shares (README, "Library shape"): a default-constructed summary
// says "not run" (status kNotRun, ToString "not_run", message "not run", not usable), and the
// accessors of the best solution throw std::logic_error on an empty result. The list is every summary
// with IsSolutionUsable() in include/plateball/*.h (the OMPL steering's connection result, in the
// optional plateball_ompl library, is checked by tests/ompl/steering_test.cc).
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "plateball/convergence.h"
#include "plateball/exact_arrival.h"
#include "plateball/execution.h"
#include "plateball/fewest_impulses.h"
#include "plateball/identify.h"
#include "plateball/impulse_planner.h"
#include "plateball/isoparallel.h"
#include "plateball/isoparallel_certificate.h"
#include "plateball/join.h"
#include "plateball/monte_carlo.h"
#include "plateball/reach.h"
#include "plateball/rig_planner.h"

using namespace plateball;

namespace {

template <class Summary>
class SummaryShape : public ::testing::Test {};

using Summaries = ::testing::Types<JoinSummary,
                                   ReachSummary,
                                   PlanSummary,
                                   ConvergenceStudy,
                                   IsoparallelSummary,
                                   ExactArrivalSummary,
                                   FewestImpulsesSummary,
                                   ExecutionSummary,
                                   MonteCarloSummary,
                                   IdentifySummary,
                                   IsoparallelCertificate,
                                   RigPlanSummary>;
TYPED_TEST_SUITE(SummaryShape, Summaries);

TYPED_TEST(SummaryShape, DefaultSaysNotRun) {
  const TypeParam s;
  EXPECT_EQ(ToString(s.status), "not_run");
  EXPECT_EQ(s.message, "not run");
  EXPECT_FALSE(s.IsSolutionUsable());
  EXPECT_NE(s.BriefReport().find("not_run"), std::string::npos) << s.BriefReport();
}

}  // namespace

TEST(SummaryShape, ConvergenceStudyDefaultHasNoRowsAndNoSlope) {
  const ConvergenceStudy s;
  EXPECT_TRUE(s.rows.empty());
  EXPECT_FALSE(s.error_slope.has_value());
  EXPECT_EQ(ConvergenceRow{}.status, PlanStatus::kNotRun);
}

TEST(SummaryShape, ShortestAndEarliestOfAnEmptyResultThrowTheSame) {
  EXPECT_THROW(ReachSummary{}.Earliest(), std::logic_error);
  EXPECT_THROW(IsoparallelSummary{}.Shortest(), std::logic_error);
}
