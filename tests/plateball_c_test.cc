// The C API (plateball_c.h) against the C++ library: the plan's impulses are PlanImpulses', the
// steer's impulses arrive when replayed by an independent integration, the controller through C
// gives the C++ controller's commands, and every failure is a status with a message naming the field.
#include "plateball/plateball_c.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "plateball/controller.h"
#include "plateball/exact_arrival.h"
#include "plateball/problem_io.h"
#include "plateball/so3.h"
#include "plateball/task_adapters.h"
#include "simulated_rig.h"
#include "support/test_support.h"

namespace plateball {
namespace {

const std::string kCircle = plateball::testing::SourcePath("problems/circle.json");
// The replay integrates with its own tolerances (1e-14): the arrival holds to the solver's 1e-12.
constexpr double kReplayTolerance = 1e-9;

struct Handles {
  pb_problem* problem = nullptr;
  pb_plan* plan = nullptr;
  pb_controller* controller = nullptr;
  ~Handles() {
    pb_controller_destroy(controller);
    pb_plan_destroy(plan);
    pb_problem_destroy(problem);
  }
};

TEST(CApi, ThePlanIsPlanImpulses) {
  Handles h;
  ASSERT_EQ(pb_problem_load(kCircle.c_str(), &h.problem), PB_OK) << pb_last_error();
  ASSERT_EQ(pb_plan_create(h.problem, 16, &h.plan), PB_OK) << pb_last_error();
  const PlanSetup setup = PlanSetupFor(ReadProblemFile(kCircle), 16);
  const PlanSummary plan = PlanImpulses(setup.problem, setup.options);
  ASSERT_EQ(pb_plan_impulse_count(h.plan), 16);
  EXPECT_EQ(pb_plan_total_time(h.plan), plan.total_time);
  for (int k = 0; k < 16; ++k) {
    pb_impulse i;
    ASSERT_EQ(pb_plan_impulse(h.plan, k, &i), PB_OK);
    const PlanStep& s = plan.steps[static_cast<std::size_t>(k)];
    EXPECT_EQ(i.delta_psi, s.delta_psi);
    EXPECT_EQ(i.duration, s.duration);
    EXPECT_EQ(i.delta_omega[1], s.delta_omega.y());
    EXPECT_EQ(i.position[0], s.p_begin.x());
  }
  pb_impulse i;
  EXPECT_EQ(pb_plan_impulse(h.plan, 16, &i), PB_INVALID_INPUT);
  EXPECT_EQ(std::string(pb_last_error()), "k: value 16: must be in [0, 16)");
}

TEST(CApi, TheSteerArrivesWhenReplayed) {
  const double identity[9] = {1, 0, 0, 0, 1, 0, 0, 0, 1};
  pb_ball_state start{};
  start.theta = M_PI / 3;
  start.phi = 0.4;
  start.psi = 0.1;
  start.mu = 1.0;
  std::copy(identity, identity + 9, start.A);
  const double goal[2] = {1.0, 0.5};
  pb_impulse out[4];
  ASSERT_EQ(pb_steer(2.0, &start, goal, identity, 4, out, 4), PB_OK) << pb_last_error();
  ExactArrivalProblem p;
  p.model = BallModel::FromLambda(2.0);
  p.initial = {start.theta, start.phi, start.psi};
  p.x1 = {1.0, 0.5};
  p.reference = Path({SmoothCurve::Line(p.x0, p.x1)});
  p.impulses = 4;
  std::vector<ExactImpulse> impulses(4);
  for (int k = 0; k < 4; ++k) {
    impulses[static_cast<std::size_t>(k)].delta_psi = out[k].delta_psi;
    impulses[static_cast<std::size_t>(k)].duration = out[k].duration;
  }
  const ReplayResult r = ReplayExactArrival(p, impulses);
  EXPECT_LT(r.position_error, kReplayTolerance);
  EXPECT_LT(r.orientation_error, kReplayTolerance);
  // Failures are statuses: the same point twice, too few impulses, an unreachable goal.
  EXPECT_EQ(pb_steer(2.0, &start, start.x, identity, 4, out, 4), PB_INVALID_INPUT);
  EXPECT_NE(std::string(pb_last_error()).find("goal_x"), std::string::npos);
  EXPECT_EQ(pb_steer(2.0, &start, goal, identity, 2, out, 4), PB_INVALID_INPUT);
  EXPECT_NE(std::string(pb_last_error()).find("impulses"), std::string::npos) << pb_last_error();
  const double far[2] = {4.0, 0.5};
  EXPECT_EQ(pb_steer(2.0, &start, far, identity, 4, out, 4), PB_NO_SOLUTION);
  EXPECT_NE(std::string(pb_last_error()).find("not_reached"), std::string::npos) << pb_last_error();
}

TEST(CApi, TheControllerGivesTheCppControllersCommands) {
  Handles h;
  ASSERT_EQ(pb_problem_load(kCircle.c_str(), &h.problem), PB_OK);
  ASSERT_EQ(pb_plan_create(h.problem, 32, &h.plan), PB_OK);
  pb_controller_options o;
  pb_controller_options_default(&o);
  o.tick_period = 1e-3;
  ASSERT_EQ(pb_controller_create(h.plan, &o, &h.controller), PB_OK) << pb_last_error();
  const PlanSetup setup = PlanSetupFor(ReadProblemFile(kCircle), 32);
  const auto nominal = std::make_shared<NominalPlan>(MakeNominalPlan(setup.problem, setup.options));
  ControllerOptions co;
  co.tick_period = 1e-3;
  Controller cpp(nominal, co);
  ErrorModel errors;
  errors.impulse_magnitude = 0.02;
  internal::SimulatedRig rig(*nominal, errors, 1, 0, 1e-4);
  int impulses = 0;
  for (long tick = 0; tick < 20000; ++tick) {
    const ControllerMeasurement m = rig.Measure(tick);
    pb_measurement cm{};
    cm.x[0] = m.x.x();
    cm.x[1] = m.x.y();
    cm.has_orientation = 1;
    for (int i = 0; i < 9; ++i) cm.A[i] = m.A(i / 3, i % 3);
    for (int i = 0; i < 3; ++i) cm.omega[i] = m.omega[i];
    pb_command c;
    ASSERT_EQ(pb_controller_update(h.controller, static_cast<double>(tick) * 1e-3, &cm, &c), PB_OK);
    const ControllerOutput& out = cpp.Update(static_cast<double>(tick) * 1e-3, m);
    ASSERT_EQ(static_cast<int>(c.status), static_cast<int>(out.status)) << tick;
    ASSERT_EQ(c.impulse != 0, out.impulse) << tick;
    EXPECT_EQ(c.x_now[0], out.now.x.x());
    EXPECT_EQ(c.A_next[5], out.at_next_impulse.A(1, 2));
    if (out.impulse) {
      EXPECT_EQ(c.delta_omega[0], out.delta_omega.x());
      EXPECT_EQ(c.next_impulse_tick, out.next_impulse_tick);
      rig.Impulse(out.impulse_index, out.delta_omega);
      ++impulses;
    }
    if (out.status == ControllerStatus::kDone) break;
    rig.Roll(1e-3);
  }
  EXPECT_EQ(impulses, 32);
}

TEST(CApi, FailuresAreStatusesWithMessages) {
  Handles h;
  EXPECT_EQ(pb_problem_load("/nonexistent/problem.json", &h.problem), PB_IO_ERROR);
  EXPECT_NE(std::string(pb_last_error()).find("/nonexistent/problem.json"), std::string::npos);
  EXPECT_EQ(h.problem, nullptr);
  EXPECT_EQ(pb_problem_load(nullptr, &h.problem), PB_INVALID_INPUT);
  EXPECT_EQ(std::string(pb_last_error()), "path: value null: required");
  const std::string bad = plateball::testing::SourcePath("schemas/output/plan.schema.json");
  EXPECT_EQ(pb_problem_load(bad.c_str(), &h.problem), PB_INVALID_INPUT);
  ASSERT_EQ(pb_problem_load(kCircle.c_str(), &h.problem), PB_OK);
  EXPECT_EQ(pb_plan_create(h.problem, -3, &h.plan), PB_INVALID_INPUT);
  EXPECT_NE(std::string(pb_last_error()).find("n: value -3"), std::string::npos) << pb_last_error();
  ASSERT_EQ(pb_plan_create(h.problem, 16, &h.plan), PB_OK);
  pb_controller_options o;
  pb_controller_options_default(&o);
  o.tick_period = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(pb_controller_create(h.plan, &o, &h.controller), PB_INVALID_INPUT);
  EXPECT_NE(std::string(pb_last_error()).find("tick_period: value nan"), std::string::npos) << pb_last_error();
  pb_controller_options_default(&o);
  o.plate_impulse = 1;  // circle.json has no physical parameters
  EXPECT_EQ(pb_controller_create(h.plan, &o, &h.controller), PB_INVALID_INPUT);
  EXPECT_NE(std::string(pb_last_error()).find("plate_impulse"), std::string::npos);
  pb_controller_options_default(&o);
  ASSERT_EQ(pb_controller_create(h.plan, &o, &h.controller), PB_OK);
  pb_command c;
  EXPECT_EQ(pb_controller_update(h.controller, 0.0, nullptr, &c), PB_INVALID_INPUT);
  pb_measurement m{};
  m.x[0] = std::numeric_limits<double>::quiet_NaN();
  ASSERT_EQ(pb_controller_update(h.controller, 0.0, &m, &c), PB_OK);
  EXPECT_EQ(c.status, PB_CONTROLLER_MEASUREMENT_REJECTED);
  EXPECT_NE(std::string(c.reason), "");
}

}  // namespace
}  // namespace plateball
