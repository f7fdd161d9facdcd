// The real-time controller (controller.h) in a closed loop with the library's simulated rig
// (src/simulated_rig.h): it reproduces the Monte Carlo feedback strategy's trials for the same seed
// and errors, reproduces the plan without errors (also from the contact point alone), and meets
// measurements that contradict the model with a status.
#include "plateball/controller.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>

#include "execution_noise.h"
#include "plateball/closed_loop.h"
#include "plateball/monte_carlo.h"
#include "plateball/problem_io.h"
#include "plateball/so3.h"
#include "plateball/task_adapters.h"
#include "simulated_rig.h"
#include "support/test_support.h"

namespace plateball {
namespace {

constexpr int kImpulses = 32;
constexpr double kTick = 1e-4;
// The loop fires each impulse on the tick nearest to the commanded time and ends on a tick, so it
// differs from Execute's exact times by at most half a tick per impulse. The join re-targets the
// next pass point from wherever the ball is, so the position differences do not add up: the final
// position differs by at most one tick's travel, v_max dt (v_max = max |x'| <= 1.5 on the circle's
// energy mu = 1, lambda = 2: sqrt(mu) bounds |x'| and 1.5 leaves room for the energy errors).
constexpr double kPositionMatch = 1.5 * kTick;
// The orientation is not fed back by the join, so the half-tick turns of the n impulses could add
// up (at worst n |omega| dt / 2 = 2.4e-3); they are of either sign and do not: the measured largest
// difference over these runs is 2.4e-5. One tick's turn at |omega| <= 1.5 bounds it with a margin
// of 6 (a found bound, not a proved one).
constexpr double kOrientationMatch = 1.5 * kTick;

PlanProblem CirclePlanProblem(PlanOptions* options) {
  const Problem problem = ReadProblemFile(plateball::testing::SourcePath("problems/circle.json"));
  const PlanSetup setup = PlanSetupFor(problem, kImpulses);
  *options = setup.options;
  return setup.problem;
}

std::shared_ptr<const NominalPlan> Circle() {
  static std::shared_ptr<const NominalPlan> plan;
  if (!plan) {
    PlanOptions options;
    const PlanProblem problem = CirclePlanProblem(&options);
    plan = std::make_shared<NominalPlan>(MakeNominalPlan(problem, options));
  }
  return plan;
}

ControllerOptions LoopOptions(ExecutionStrategy strategy = ExecutionStrategy::kFeedback) {
  ControllerOptions o;
  o.tick_period = kTick;
  o.strategy = strategy;
  o.time_budget = 10.0;  // a test is not a real-time loop: the budget never cuts a re-plan short
  return o;
}

internal::ClosedLoopResult Loop(const ErrorModel& errors,
                                std::uint64_t seed,
                                std::uint64_t trial,
                                const ControllerOptions& options,
                                bool contact_point_only = false) {
  Controller controller(Circle(), options);
  internal::SimulatedRig rig(*Circle(), errors, seed, trial);
  const long max_ticks = std::lround(2.0 * Circle()->plan.total_time / kTick);
  return internal::RunClosedLoop(controller, rig, max_ticks, contact_point_only);
}

TEST(Controller, ClosedLoopMatchesMonteCarloFeedbackTrials) {
  MonteCarloProblem mc;
  MonteCarloOptions options;
  mc.plan = CirclePlanProblem(&options.plan);
  mc.strategies = {ExecutionStrategy::kFeedback};
  mc.scenarios = {{"rig", testing::ControllerTestErrors()}};
  mc.trials = 3;
  mc.seed = 11;
  const MonteCarloSummary s = RunMonteCarlo(mc, options);
  ASSERT_TRUE(s.IsSolutionUsable()) << s.BriefReport();
  ASSERT_EQ(s.records.size(), 3u);
  for (const TrialRecord& r : s.records) {
    ASSERT_EQ(r.status, ExecutionStatus::kCompleted);
    const internal::ClosedLoopResult loop =
        Loop(testing::ControllerTestErrors(), mc.seed, static_cast<std::uint64_t>(r.trial), LoopOptions());
    EXPECT_EQ(loop.status, ControllerStatus::kDone) << "trial " << r.trial;
    EXPECT_EQ(loop.impulses, kImpulses);
    const double position_error = (loop.x - Circle()->goal).norm();
    const double orientation_error = RotationAngle(Circle()->goal_orientation, loop.A);
    EXPECT_NEAR(position_error, r.position_error, kPositionMatch) << "trial " << r.trial;
    EXPECT_NEAR(orientation_error, r.orientation_error, kOrientationMatch) << "trial " << r.trial;
    // The final errors are those of the error model, not of the tick (without errors: 1.8e-5).
    EXPECT_GT(r.position_error, 10 * kPositionMatch) << "trial " << r.trial;
  }
}

TEST(Controller, ClosedLoopMatchesExecuteFeedbackExact) {
  ExecutionProblem ep;
  ep.nominal = Circle();
  ep.strategy = ExecutionStrategy::kFeedbackExact;
  ep.errors = testing::ControllerTestErrors();
  ep.seed = 5;
  const ControllerOptions o = LoopOptions(ExecutionStrategy::kFeedbackExact);
  const ExecutionSummary s = Execute(ep);
  ASSERT_TRUE(s.IsSolutionUsable()) << s.BriefReport();
  ASSERT_EQ(s.exact_solves, 10);  // every step while 12 ... 3 impulses remain re-planned exactly
  Controller controller(Circle(), o);
  internal::SimulatedRig rig(*Circle(), ep.errors, ep.seed, ep.trial);
  const internal::ClosedLoopResult loop =
      internal::RunClosedLoop(controller, rig, std::lround(2.0 * Circle()->plan.total_time / kTick));
  EXPECT_EQ(loop.status, ControllerStatus::kDone);
  EXPECT_EQ(controller.exact_solves(), 10);
  EXPECT_NEAR((loop.x - Circle()->goal).norm(), s.position_error, kPositionMatch);
  EXPECT_NEAR(RotationAngle(Circle()->goal_orientation, loop.A), s.orientation_error, kOrientationMatch);
}

TEST(Controller, WithoutErrorsTheLoopFollowsThePlanAlsoFromTheContactPointAlone) {
  for (bool contact_point_only : {false, true}) {
    const internal::ClosedLoopResult loop = Loop(ErrorModel{}, 1, 0, LoopOptions(), contact_point_only);
    EXPECT_EQ(loop.status, ControllerStatus::kDone);
    EXPECT_EQ(loop.impulses, kImpulses);
    EXPECT_LT((loop.x - Circle()->goal).norm(), kPositionMatch) << contact_point_only;
    // The plan's own orientation error (Theorem 2.6) plus the tick's.
    EXPECT_NEAR(RotationAngle(Circle()->goal_orientation, loop.A), Circle()->plan_orientation_error, kOrientationMatch)
        << contact_point_only;
  }
}

TEST(Controller, MeasurementsThatContradictTheModelGetAStatus) {
  Controller c(Circle(), LoopOptions());
  internal::SimulatedRig rig(*Circle(), ErrorModel{}, 1, 0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const auto rejected = [&](ControllerMeasurement m, const char* what) {
    const ControllerOutput& out = c.Update(0.0, m);
    EXPECT_EQ(out.status, ControllerStatus::kMeasurementRejected) << what;
    EXPECT_FALSE(out.measurement_used) << what;
    EXPECT_NE(std::string(out.reason), "") << what;
    EXPECT_TRUE(out.now.x.allFinite() && out.now.A.allFinite()) << what;
  };
  ControllerMeasurement m = rig.Measure(0);
  m.x.x() = nan;
  rejected(m, "NaN contact point");
  m = rig.Measure(0);
  m.A(0, 1) += 1e-3;
  rejected(m, "not a rotation");
  m = rig.Measure(0);
  m.A = -m.A;
  rejected(m, "a reflection");
  m = rig.Measure(0);
  m.omega.z() = 0.1;
  rejected(m, "spin");
  m = rig.Measure(0);
  m.x.x() += 1.0;
  rejected(m, "a jump");
  m = rig.Measure(0);
  m.A = RotationZ(1.0) * m.A;
  rejected(m, "an orientation jump");
  m = rig.Measure(0);
  m.omega.setZero();
  rejected(m, "at rest");
  // The impulse due at tick 0 was fired from the prediction at the first Update; time goes on.
  EXPECT_EQ(c.Update(-kTick, rig.Measure(0)).status, ControllerStatus::kTimeOutOfOrder);
  EXPECT_EQ(c.Update(nan, rig.Measure(0)).status, ControllerStatus::kTimeOutOfOrder);
  EXPECT_EQ(c.Update(0.0, rig.Measure(0)).status, ControllerStatus::kOk);
}

TEST(Controller, TheFirstImpulseIsThePlansAndTheEstimatesRollWithTheModel) {
  Controller c(Circle(), LoopOptions());
  internal::SimulatedRig rig(*Circle(), ErrorModel{}, 1, 0);
  const ControllerOutput& out = c.Update(0.0, rig.Measure(0));
  ASSERT_EQ(out.status, ControllerStatus::kOk);
  ASSERT_TRUE(out.impulse);
  const PlanStep& s0 = Circle()->plan.steps.front();
  // The same join from the same state as the planner (its residual tolerance 1e-12).
  EXPECT_LT((out.delta_omega - s0.delta_omega).norm(), 1e-9);
  EXPECT_EQ(out.next_impulse_tick, std::lround(s0.duration / kTick));
  // The prediction at the next impulse is the first pass point to within the rounding to a tick.
  EXPECT_LT((out.at_next_impulse.x - Circle()->pass_points[1]).norm(), 1.5 * kTick);
  EXPECT_FALSE(out.has_plate_impulse);
}

TEST(Controller, PhysicalParametersGiveThePlateImpulse) {
  ControllerOptions o = LoopOptions();
  o.physical = plateball::testing::PhysicalUnitsBall();
  Controller c(Circle(), o);
  internal::SimulatedRig rig(*Circle(), ErrorModel{}, 1, 0);
  const ControllerOutput& out = c.Update(0.0, rig.Measure(0));
  ASSERT_TRUE(out.impulse && out.has_plate_impulse);
  const PlateImpulse j = PlateImpulseFor(*o.physical, rig.state().z, out.delta_omega);
  EXPECT_LT((out.plate_impulse.plate - j.plate).norm(), 1e-12 * j.plate.norm());
  EXPECT_GT(j.plate.norm(), 0.0);
}

TEST(Controller, AnExhaustedBudgetGivesTheJoinWithAFlag) {
  ControllerOptions o = LoopOptions(ExecutionStrategy::kFeedbackExact);
  o.time_budget = 1e-12;  // spent before any exact re-plan could start
  Controller c(Circle(), o);
  internal::SimulatedRig rig(*Circle(), testing::ControllerTestErrors(), 3, 0);
  const internal::ClosedLoopResult loop =
      internal::RunClosedLoop(c, rig, std::lround(2.0 * Circle()->plan.total_time / kTick));
  EXPECT_EQ(loop.status, ControllerStatus::kDone);
  EXPECT_EQ(c.exact_solves(), 0);
  EXPECT_GE(loop.budget_exhausted, 10);  // at least the ten impulses that wanted an exact re-plan
  // Every impulse was the re-join: the run is the feedback strategy's, to the last bit.
  const internal::ClosedLoopResult feedback = Loop(testing::ControllerTestErrors(), 3, 0, LoopOptions());
  EXPECT_EQ(loop.x, feedback.x);
  EXPECT_EQ(loop.A, feedback.A);
}

TEST(Controller, AMissedImpulseTickFiresLateAtTheNextUpdate) {
  Controller c(Circle(), LoopOptions());
  internal::SimulatedRig rig(*Circle(), ErrorModel{}, 1, 0);
  const ControllerOutput& first = c.Update(0.0, rig.Measure(0));
  ASSERT_TRUE(first.impulse);
  rig.Impulse(0, first.delta_omega);
  const long due = first.next_impulse_tick, now = due + 5;  // the rig skipped the due tick
  rig.Roll(static_cast<double>(now) * kTick);
  const ControllerOutput& late = c.Update(static_cast<double>(now) * kTick, rig.Measure(now));
  EXPECT_EQ(late.status, ControllerStatus::kOk) << late.reason;
  EXPECT_TRUE(late.impulse);
  EXPECT_TRUE(late.late);
  EXPECT_EQ(late.impulse_index, 1);
  EXPECT_GT(late.next_impulse_tick, now);
}

// closed_loop.h gives a plant outside the library the same trial and the same loop.
TEST(Controller, ThePublicTrialErrorsAndSimulatedLoopAreExecutesDrawsAndTheRigsLoop) {
  ControllerOptions o = LoopOptions();
  o.tick_period = 1e-3;  // the same loop on a coarser tick: a tenth of the work
  const SimulatedLoopResult pub = RunSimulatedClosedLoop(Circle(), o, testing::ControllerTestErrors(), 11, 1);
  Controller controller(Circle(), o);
  internal::SimulatedRig rig(*Circle(), testing::ControllerTestErrors(), 11, 1);
  const internal::ClosedLoopResult loop =
      internal::RunClosedLoop(controller, rig, std::lround(2.0 * Circle()->plan.total_time / o.tick_period) + 2);
  EXPECT_EQ(pub.status, loop.status);
  EXPECT_EQ(pub.impulses, loop.impulses);
  EXPECT_EQ(pub.ticks, loop.ticks);
  EXPECT_EQ(pub.x, loop.x);
  EXPECT_EQ(pub.A, loop.A);
  EXPECT_EQ(pub.position_error, (loop.x - Circle()->goal).norm());
  EXPECT_EQ(pub.orientation_error, RotationAngle(Circle()->goal_orientation, loop.A));
  const TrialErrors errors(testing::ControllerTestErrors(), 11, 1);
  const internal::ExecutionNoise noise(testing::ControllerTestErrors(), 11, 1);
  const Eigen::Vector3d d(0.3, -0.2, 0.0);
  for (int k : {0, 7, 31}) EXPECT_EQ(errors.PerturbImpulse(k, d), noise.PerturbImpulse(k, d));
  EXPECT_NE(errors.PerturbImpulse(7, d), d);
  EXPECT_EQ(errors.TrueLambda(2.0), noise.TrueLambda(2.0));
  EXPECT_EQ(pub.lambda, errors.TrueLambda(2.0));
  EXPECT_EQ(errors.Restitution(), std::sqrt(1 - testing::ControllerTestErrors().energy_loss));
  ErrorModel bad;
  bad.impulse_angle = -1.0;
  EXPECT_NE(
      plateball::testing::InvalidArgumentMessage([&] { TrialErrors e(bad, 1, 0); }).find("impulse_angle: value -1"),
      std::string::npos);
}

TEST(Controller, InvalidOptionsNameTheField) {
  const auto message = [](const ControllerOptions& o) {
    return plateball::testing::InvalidArgumentMessage([&] { Controller c(Circle(), o); });
  };
  ControllerOptions o;
  o.tick_period = 0.0;
  EXPECT_NE(message(o).find("tick_period: value 0"), std::string::npos) << message(o);
  o = {};
  o.strategy = ExecutionStrategy::kOpenLoop;
  EXPECT_NE(message(o).find("strategy: value 'open_loop'"), std::string::npos) << message(o);
  o = {};
  o.time_budget = -1.0;
  EXPECT_NE(message(o).find("time_budget: value -1"), std::string::npos) << message(o);
  o = {};
  o.execution.exact_window = 1;
  EXPECT_NE(message(o).find("execution: exact_window: value 1"), std::string::npos) << message(o);
  EXPECT_NE(plateball::testing::InvalidArgumentMessage([] { Controller c(nullptr); }).find("nominal"),
            std::string::npos);
}

}  // namespace
}  // namespace plateball
