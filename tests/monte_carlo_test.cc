// Monte Carlo of plan execution (monte_carlo.h): results independent of threads and of how the
// task list is split (as the MPI ranks split it), order statistics, the error-against-n fit,
// limits with messages naming the field and the value.
#include "plateball/monte_carlo.h"

#include <gtest/gtest.h>

#include <cmath>

#include "plateball/problem_io.h"
#include "plateball/task_adapters.h"
#include "support/test_support.h"

namespace plateball {
namespace {

MonteCarloProblem CircleStudy(int n = 32, int trials = 6) {
  const Problem problem = ReadProblemFile(plateball::testing::SourcePath("problems/circle.json"));
  MonteCarloProblem p;
  p.plan = PlanSetupFor(problem, n).problem;
  ErrorModel a, b;
  a.impulse_magnitude = 1e-3;
  b.timing = 1e-3;
  b.observation = 1e-5;
  p.scenarios = {{"a", a}, {"b", b}};
  p.trials = trials;
  p.seed = 11;
  return p;
}

void ExpectSameRecords(const std::vector<TrialRecord>& a, const std::vector<TrialRecord>& b) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].n, b[i].n);
    EXPECT_EQ(a[i].scenario, b[i].scenario);
    EXPECT_EQ(a[i].strategy, b[i].strategy);
    EXPECT_EQ(a[i].trial, b[i].trial);
    EXPECT_EQ(a[i].position_error, b[i].position_error) << i;  // bit for bit
    EXPECT_EQ(a[i].orientation_error, b[i].orientation_error) << i;
    EXPECT_EQ(a[i].total_time, b[i].total_time) << i;
    EXPECT_EQ(a[i].missed_pass_points, b[i].missed_pass_points) << i;
  }
}

TEST(MonteCarlo, ThreadCountDoesNotChangeAnyResult) {
  const MonteCarloProblem p = CircleStudy();
  MonteCarloOptions one, three;
  three.threads = 3;
  const MonteCarloSummary a = RunMonteCarlo(p, one), b = RunMonteCarlo(p, three);
  ASSERT_TRUE(a.IsSolutionUsable()) << a.BriefReport();
  ExpectSameRecords(a.records, b.records);
  EXPECT_EQ(a.BriefReport(), b.BriefReport());
  ASSERT_EQ(a.cells.size(), 4u);  // 2 scenarios x 2 strategies
  ASSERT_TRUE(a.cells[1].orientation_error && b.cells[1].orientation_error);
  EXPECT_EQ(a.cells[1].orientation_error->p95, b.cells[1].orientation_error->p95);
}

// The split of the ranks: any partition of [0, TaskCount()) gathered in order is the whole run.
TEST(MonteCarlo, AnySplitOfTheTasksGivesTheSameSummary) {
  const MonteCarloProblem p = CircleStudy();
  const MonteCarloWork work(p, {});
  const long long total = work.TaskCount();
  ASSERT_EQ(total, 2 * 2 * 6);
  const std::vector<TrialRecord> whole = work.Run(0, total);
  for (int ranks : {2, 3, 5}) {
    std::vector<TrialRecord> gathered;
    for (int r = 0; r < ranks; ++r) {
      const std::vector<TrialRecord> part = work.Run(total * r / ranks, total * (r + 1) / ranks);
      gathered.insert(gathered.end(), part.begin(), part.end());
    }
    ExpectSameRecords(whole, gathered);
    EXPECT_EQ(work.Summarize(gathered).BriefReport(), work.Summarize(whole).BriefReport());
  }
  // Trial i meets the same draws in every cell: the strategies are compared on one realisation.
  EXPECT_EQ(whole[0].trial, whole[6].trial);
  EXPECT_EQ(whole[0].strategy, ExecutionStrategy::kOpenLoop);
  EXPECT_EQ(whole[6].strategy, ExecutionStrategy::kFeedback);
}

TEST(MonteCarlo, DistributionIsTypeSevenQuantiles) {
  const Distribution d = Distribute({5, 1, 4, 2, 3});
  EXPECT_EQ(d.median, 3);
  EXPECT_DOUBLE_EQ(d.p95, 4.8);  // h = 0.95 * 4 = 3.8: 4 + 0.8 (5 - 4)
  EXPECT_EQ(d.max, 5);
  EXPECT_EQ(d.mean, 3);
  const Distribution e = Distribute({});
  EXPECT_EQ(e.median, 0);
  EXPECT_EQ(Distribute({2, 4}).median, 3);
}

// Without errors every trial is the plan: the median error against n has Theorem 2.6's slope -2
// (Corollary 3) for both strategies and equals the plan's own error.
TEST(MonteCarlo, ZeroNoiseSweepHasThePlansSlopeMinusTwo) {
  MonteCarloProblem p = CircleStudy(16, 2);
  p.scenarios = {{"none", {}}};
  p.sweep_n = {32, 64};
  const MonteCarloSummary s = RunMonteCarlo(p, {});
  ASSERT_TRUE(s.IsSolutionUsable()) << s.BriefReport();
  ASSERT_EQ(s.sweeps.size(), 2u);
  for (const SweepSeries& w : s.sweeps) {
    ASSERT_EQ(w.n, (std::vector<int>{16, 32, 64}));
    ASSERT_TRUE(w.slope && w.plan_slope);
    EXPECT_NEAR(*w.slope, -2.0, 0.02) << ToString(w.strategy);
    EXPECT_NEAR(*w.slope, *w.plan_slope, 1e-6);
    for (std::size_t i = 0; i < w.n.size(); ++i)
      EXPECT_NEAR(w.median_orientation_error[i].value(), w.plan_orientation_error[i], 1e-10);
  }
  EXPECT_EQ(s.nominal.size(), 3u);
  EXPECT_EQ(s.nominal.front().n, 16);
}

// A cell where no trial completed has no distribution (not zeros), the report says "no trial
// completed", and a sweep row without data is missing and left out of the fit: the slope is then
// the fit over the remaining n, here two n, whose slope is log(e2 / e1) / log(n2 / n1) exactly.
TEST(MonteCarlo, CellWithoutACompletedTrialHasNoDistributionAndLeavesTheFit) {
  MonteCarloProblem p = CircleStudy(16, 3);
  p.scenarios = {{"none", {}}};
  p.strategies = {ExecutionStrategy::kFeedback};
  p.sweep_n = {32, 64};
  const MonteCarloWork work(p, {});
  std::vector<TrialRecord> records = work.Run(0, work.TaskCount());
  ASSERT_EQ(records.size(), 9u);  // n = 16, 32, 64 in that order (main n first), 3 trials each
  for (std::size_t i = 3; i < 6; ++i) {
    ASSERT_EQ(records[i].n, 32);
    records[i].status = ExecutionStatus::kLost;  // every trial at n = 32 lost the ball
  }
  const MonteCarloSummary s = work.Summarize(records);
  ASSERT_TRUE(s.IsSolutionUsable()) << s.BriefReport();  // every trial ran
  ASSERT_EQ(s.cells.size(), 3u);
  const MonteCarloCell& empty = s.cells[1];
  EXPECT_EQ(empty.n, 32);
  EXPECT_EQ(empty.completed, 0);
  EXPECT_FALSE(empty.orientation_error || empty.position_error || empty.max_pass_miss || empty.missed_pass_points ||
               empty.total_time);
  EXPECT_EQ(s.empty_cells, 1);
  EXPECT_NE(s.message.find("no trial completed in 1 cell"), std::string::npos) << s.message;
  EXPECT_NE(s.BriefReport().find("no trial completed"), std::string::npos) << s.BriefReport();
  ASSERT_EQ(s.sweeps.size(), 1u);
  const SweepSeries& w = s.sweeps.front();
  ASSERT_EQ(w.n, (std::vector<int>{16, 32, 64}));
  EXPECT_TRUE(w.Missing(1));
  EXPECT_FALSE(w.median_position_error[1]);
  ASSERT_FALSE(w.Missing(0) || w.Missing(2));
  ASSERT_TRUE(w.slope);
  const double two_point = std::log(*w.median_orientation_error[2] / *w.median_orientation_error[0]) / std::log(4.0);
  constexpr double kRounding = 1e-12;  // the same two logarithms, summed in another order
  EXPECT_NEAR(*w.slope, two_point, kRounding);
  ASSERT_EQ(w.local_slopes.size(), 2u);
  EXPECT_FALSE(w.local_slopes[0] || w.local_slopes[1]);  // each touches the missing n
}

// The noise of a hostile run: every feedback trial loses the ball, and its cell says so.
TEST(MonteCarlo, EveryTrialLostGivesNoDistribution) {
  MonteCarloProblem p = CircleStudy(64, 20);
  p.strategies = {ExecutionStrategy::kFeedback};
  p.scenarios = {{"hard",
                  ParseErrorModel("impulse_magnitude=0.5,impulse_angle=0.5,energy_loss=0.5,timing=0.1,"
                                  "lambda=0.1,observation=0.1")}};
  const MonteCarloSummary s = RunMonteCarlo(p, {});
  ASSERT_EQ(s.cells.size(), 1u);
  ASSERT_EQ(s.failed_trials, 20);
  EXPECT_EQ(s.cells[0].completed, 0);
  EXPECT_FALSE(s.cells[0].orientation_error);
  EXPECT_NE(s.BriefReport().find("feedback: no trial completed"), std::string::npos) << s.BriefReport();
}

TEST(MonteCarlo, LimitsNameTheFieldAndTheValue) {
  using plateball::testing::InvalidArgumentMessage;
  MonteCarloProblem p = CircleStudy();
  p.trials = 0;
  EXPECT_EQ(InvalidArgumentMessage([&] { MonteCarloWork(p, {}); }), "trials: value 0: must be in [1, 1000000]");
  p = CircleStudy();
  p.trials = 1'000'000;
  EXPECT_NE(
      InvalidArgumentMessage([&] { MonteCarloWork(p, {}); }).find("trials: value 1000000: the study would run 4000000"),
      std::string::npos);
  // The work bound, counted before any sweep plan: 2 scenarios x 2 strategies x 200000 trials x
  // n = 200 impulses = 1.6e8 executions > 1e8, though the 800000 trials are within kMaxTasks.
  p = CircleStudy(200, 200'000);
  EXPECT_NE(InvalidArgumentMessage([&] {
              MonteCarloWork(p, {});
            }).find("trials: value 200000: the study would execute about 160000000 impulses"),
            std::string::npos);
  // feedback_exact adds W^3 per trial: 2 x 1 x 100000 x (200 + 12^3) = 3.856e8.
  p = CircleStudy(200, 100'000);
  p.strategies = {ExecutionStrategy::kFeedbackExact};
  EXPECT_NE(InvalidArgumentMessage([&] { MonteCarloWork(p, {}); }).find("about 385600000 impulses"), std::string::npos);
  p = CircleStudy();
  p.scenarios[1].errors.timing = 1;
  EXPECT_EQ(InvalidArgumentMessage([&] { MonteCarloWork(p, {}); }),
            "scenarios[1].timing: value 1: must be a number in [0, 0.1]");
  p = CircleStudy();
  p.strategies = {ExecutionStrategy::kFeedback, ExecutionStrategy::kFeedback};
  EXPECT_EQ(InvalidArgumentMessage([&] { MonteCarloWork(p, {}); }),
            "strategies: value (repeated): give each strategy once");
  p = CircleStudy();
  p.sweep_n = {16, 0};
  EXPECT_EQ(InvalidArgumentMessage([&] { MonteCarloWork(p, {}); }), "sweep_n[1]: value 0: must be in [1, 10000]");
  p = CircleStudy();
  p.plan.partition = {ExplicitTaus{{0, 1, 2, 6.283185307179586}}};
  p.sweep_n = {16};
  EXPECT_NE(InvalidArgumentMessage([&] { MonteCarloWork(p, {}); }).find("sweep_n: value 16: needs a single uniform"),
            std::string::npos);
  MonteCarloOptions o;
  o.threads = 0;
  EXPECT_EQ(InvalidArgumentMessage([&] { MonteCarloWork(CircleStudy(), o); }), "threads: value 0: must be in [1, 256]");
  o = {};
  o.execution.exact_window = 100;
  EXPECT_EQ(InvalidArgumentMessage([&] { MonteCarloWork(CircleStudy(), o); }),
            "execution: exact_window: value 100: must be in [3, 64]");
}

}  // namespace
}  // namespace plateball
