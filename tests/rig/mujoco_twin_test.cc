// The MuJoCo twin against the library: MuJoCo is an independent rigid-body engine (contacts with
// friction, no rolling constraint), the library integrates the reduced rolling equations (FreeMotion).
// Tolerances are the agreement measured in docs/mujoco_twin.md with a margin of about 5.
#include "rig/mujoco_twin.h"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "common/json_output.h"
#include "common/plan_json.h"
#include "plateball/exact_arrival.h"
#include "plateball/free_motion.h"
#include "plateball/impulse_planner.h"
#include "plateball/problem_io.h"
#include "plateball/task_adapters.h"
#include "rig/rig_plan.h"

namespace plateball::tools::rig {
namespace {

const std::string kSource = PLATEBALL_SOURCE_DIR;

std::string TempFile(const std::string& name) {
  return (std::filesystem::path(PLATEBALL_BINARY_DIR) / ("mujoco_twin_test_" + name)).string();
}

// A free motion over two periods from problems/physical_units.json, compared with `model`.
RigPlan FreeRigPlan(const BallModel& model) {
  const Problem p = ReadProblemFile(kSource + "/problems/physical_units.json");
  RigPlan plan;
  plan.physical = *p.physical;
  plan.model = model;
  plan.integration = p.integration;
  const FreeMotion fm = FreeMotion::FromAngles(model, p.initial, p.mu, p.x0, p.A0, p.integration);
  plan.start = fm.start().state;
  plan.x0 = fm.start().x0;
  plan.A0 = fm.start().A0;
  plan.t_end = 2 * fm.Period();
  return plan;
}

ReplayReport Replay(const RigPlan& plan, double dt, double pulse_duration = 0.0) {
  ReplayOptions o;
  o.settings.timestep = dt;
  o.pulse_duration = pulse_duration;
  return ReplayInTwin(plan, PlannedTrajectory(plan), o);
}

// A `plateball plan` result of a problem file, written as the tool writes it.
std::string PlanResult(const std::string& problem_file, int n, const std::string& name) {
  const Problem p = ReadProblemFile(problem_file);
  const PlanSetup setup = PlanSetupFor(p, n);
  const PlanSummary plan = PlanImpulses(setup.problem, setup.options);
  EXPECT_TRUE(plan.IsSolutionUsable()) << plan.BriefReport();
  Json doc = HeaderJson("plateball", "plan", p, problem_file);
  Json initial = InitialJson(p);
  initial["orientation"] = ToJson(plan.A0);
  doc["initial"] = std::move(initial);
  Append(doc, PlanSummaryToJson(plan, true));
  const std::string file = TempFile(name);
  std::ofstream(file) << DumpJson(doc);
  return file;
}

// ---------------------------------------------------------------- free motion
// Measured at dt = 1e-3 over two periods: position 1.9e-7 r, orientation 1.7e-6 rad, energy 2.5e-11.
constexpr double kFreePositionTolerance = 1e-6;
constexpr double kFreeOrientationTolerance = 1e-5;
constexpr double kFreeEnergyTolerance = 1e-9;
// The paper's 2 M_plate gives lambda 0.958 instead of 0.971: measured 3.5e-2 r and 3.7e-2 rad apart.
constexpr double kPaperLambdaMiss = 1e-2;

TEST(MujocoTwin, FreeMotionMatchesTheCorrectedLambdaNotThePapers) {
  const Problem p = ReadProblemFile(kSource + "/problems/physical_units.json");
  const ReplayReport corrected = Replay(FreeRigPlan(p.model), 1e-3);
  EXPECT_LT(corrected.position_error, kFreePositionTolerance);
  EXPECT_LT(corrected.orientation_error, kFreeOrientationTolerance);
  EXPECT_LT(corrected.energy_error, kFreeEnergyTolerance);
  const PhysicalParameters& ph = *p.physical;
  const double paper_beta = (ph.ball_mass + 2 * ph.plate_mass) * ph.radius * ph.radius / ph.inertia_1;
  const ReplayReport paper =
      Replay(FreeRigPlan(BallModel::FromAlphaBeta(ph.inertia_3 / ph.inertia_1, paper_beta)), 1e-3);
  EXPECT_GT(paper.position_error, kPaperLambdaMiss);
  EXPECT_GT(paper.orientation_error, kPaperLambdaMiss);
}

// The error is the contact's steady penetration, proportional to the time constant squared (2 dt):
// ten times smaller a step, a hundred times smaller an error (measured 1.7e-8 rad at 1e-4).
TEST(MujocoTwin, FreeMotionErrorFallsWithTheTimestepSquared) {
  const Problem p = ReadProblemFile(kSource + "/problems/physical_units.json");
  const RigPlan plan = FreeRigPlan(p.model);
  const ReplayReport coarse = Replay(plan, 1e-3), fine = Replay(plan, 1e-4);
  EXPECT_LT(fine.orientation_error, kFreeOrientationTolerance / 100);
  EXPECT_GT(coarse.orientation_error / fine.orientation_error, 50.0);
  EXPECT_LT(coarse.orientation_error / fine.orientation_error, 200.0);
}

// ---------------------------------------------------------------- plans
// circle_physical.json with 64 impulses, ideal jumps at dt = 1e-3: measured position 1.9e-9 r,
// orientation 1.5e-6 rad, energy 6e-9, slip 3e-9 m/s, spin 5e-10 rad/s.
constexpr double kPlanPositionTolerance = 1e-7;
constexpr double kPlanOrientationTolerance = 1e-5;
constexpr double kPlanEnergyTolerance = 5e-8;
constexpr double kSlipTolerance = 2e-8;       // m/s
constexpr double kIdealSpinTolerance = 5e-9;  // rad/s
constexpr double kPulseSpinTolerance = 2e-5;  // rad/s: a pulse's torsion (measured 3.3e-6 at D = 0.01 s)

TEST(MujocoTwin, PlanWithIdealJumpsFollowsThePlan) {
  const RigPlan plan = ReadRigPlan(PlanResult(kSource + "/problems/circle_physical.json", 64, "circle64.json"));
  ASSERT_EQ(plan.impulses.size(), 64u);
  const ReplayReport r = Replay(plan, 1e-3);
  EXPECT_LT(r.position_error, kPlanPositionTolerance);
  EXPECT_LT(r.orientation_error, kPlanOrientationTolerance);
  EXPECT_LT(r.energy_error, kPlanEnergyTolerance);
  EXPECT_LT(r.max_slip_speed, kSlipTolerance);
  EXPECT_LT(r.max_spin_rate, kIdealSpinTolerance);
}

// Centred pulses leave O(D^2) (docs/mujoco_twin.md): measured orientation 1.07e-5 rad at D = 0.01 s
// and 4.7e-5 at 0.02 s (ratio 4.4), both well above the ideal jumps' 1.5e-6.
TEST(MujocoTwin, CentredPulsesLeaveAnErrorOfOrderDurationSquared) {
  const RigPlan plan = ReadRigPlan(PlanResult(kSource + "/problems/circle_physical.json", 64, "circle64p.json"));
  const ReplayReport d1 = Replay(plan, 1e-3, 0.01), d2 = Replay(plan, 1e-3, 0.02);
  EXPECT_LT(d2.orientation_error, 1e-4);
  EXPECT_LT(d2.position_error, 5e-6);
  const double ratio = d2.orientation_error / d1.orientation_error;
  EXPECT_GT(ratio, 3.0);  // 4 for D^2 (2 for a causal pulse's D)
  EXPECT_LT(ratio, 6.0);
  EXPECT_LT(d2.max_slip_speed, kSlipTolerance);
  EXPECT_LT(d1.max_spin_rate, kPulseSpinTolerance);
  EXPECT_LT(d2.energy_error, 1e-6);
  EXPECT_LT(d1.t_begin, 0.0);  // the first impulse is at t = 0: its pulse starts at -D/2
}

// steer --stop-at-goal --start-at-rest: the engine starts at rest, arrives and stops (measured 3.7e-8 r,
// 4.2e-7 rad with ideal jumps).
TEST(MujocoTwin, SteerResultArrivesAndStops) {
  const std::string problem = kSource + "/tests/data/rig_steer_physical.json";
  const Problem p = ReadProblemFile(problem);
  ExactArrivalSetup setup = ExactArrivalSetupFor(p);
  setup.problem.start_at_rest = true;
  const ExactArrivalSummary s = SolveExactArrival(setup.problem, setup.options);
  ASSERT_TRUE(s.IsSolutionUsable()) << s.BriefReport();
  Json doc = HeaderJson("plateball", "steer", p, problem);
  doc["initial"] = InitialJson(p);
  Append(doc, Json{{"total_time", s.total_time}});
  Json list = Json::array();
  auto add = [&](const ExactImpulse& e) {
    list.push_back(Json{{"t_impulse", e.t_impulse},
                        {"x", ToJson(e.position)},
                        {"delta_omega", ToJson(e.delta_omega)},
                        {"angles_before", ToJson(e.angles_before)},
                        {"mu_before", e.mu_before}});
  };
  for (const ExactImpulse& e : s.impulses) add(e);
  ASSERT_TRUE(s.stop.has_value());
  add(*s.stop);
  doc["impulses"] = list;
  const std::string file = TempFile("steer.json");
  std::ofstream(file) << DumpJson(doc);
  const RigPlan plan = ReadRigPlan(file);
  EXPECT_EQ(plan.start.omega.norm(), 0.0);
  const ReplayReport r = Replay(plan, 1e-3);
  EXPECT_LT(r.position_error, kPlanPositionTolerance * 5);
  EXPECT_LT(r.orientation_error, kPlanOrientationTolerance);
  EXPECT_LT(r.energy_engine, 1e-15);  // J: at rest at the goal (the plan's energy is 6.8e-5 J)
}

// ---------------------------------------------------------------- the model and bad input
TEST(MujocoTwin, ExportedMjcfLoadsWithTheBallsInertiaAndOrientation) {
  const Problem p = ReadProblemFile(kSource + "/problems/physical_units.json");
  const Eigen::Matrix3d A0 = FreeMotion::FromAngles(p.model, p.initial, p.mu).start().A0;
  const std::string file = TempFile("model.xml");
  const Eigen::Vector3d omega0(0.3, -0.7, 0.0);
  std::ofstream(file) << TwinMjcf(*p.physical, Eigen::Vector2d(1.5, -2.0), A0, TwinSettings{}, omega0);
  char error[1000] = "";
  mjModel* m = mj_loadXML(file.c_str(), nullptr, error, sizeof(error));
  ASSERT_NE(m, nullptr) << error;
  EXPECT_EQ(m->nbody, 3);  // world, ball, upper plate
  EXPECT_EQ(m->njnt, 4);   // free joint, three slides
  EXPECT_EQ(m->opt.integrator, mjINT_RK4);
  EXPECT_EQ(m->opt.cone, mjCONE_ELLIPTIC);
  const int ball = mj_name2id(m, mjOBJ_BODY, "ball");
  EXPECT_DOUBLE_EQ(m->body_mass[ball], p.physical->ball_mass);
  // MuJoCo orders the principal moments itself; the diagonal inertia is I1, I1, I3 in some frame.
  Eigen::Vector3d moments(m->body_inertia[3 * ball], m->body_inertia[3 * ball + 1], m->body_inertia[3 * ball + 2]);
  std::sort(moments.data(), moments.data() + 3);
  EXPECT_NEAR(moments(0), p.physical->inertia_3, 1e-15);
  EXPECT_NEAR(moments(2), p.physical->inertia_1, 1e-15);
  mjData* d = mj_makeData(m);
  mj_forward(m, d);
  Eigen::Matrix3d R;
  for (int i = 0; i < 9; ++i) R(i / 3, i % 3) = d->xmat[9 * ball + i];
  // The inertial frame may be permuted; the body's symmetry axis is the z of the initial angles.
  Eigen::Matrix3d Ri;
  for (int i = 0; i < 9; ++i) Ri(i / 3, i % 3) = d->ximat[9 * ball + i];
  int axis = 0;
  for (int i = 0; i < 3; ++i)
    if (std::abs(m->body_inertia[3 * ball + i] - p.physical->inertia_3) < 1e-15) axis = i;
  EXPECT_LT((Ri.col(axis).cwiseAbs() - A0.col(2).cwiseAbs()).norm(), 1e-12);
  EXPECT_NEAR(d->xpos[3 * ball], 1.5 * p.physical->radius, 1e-15);
  EXPECT_NEAR(d->xpos[3 * ball + 2], p.physical->radius, 1e-15);
  EXPECT_LT((R - A0).norm(), 1e-12);
  // The keyframe "start": the same pose, rolling velocities v = r omega x e3 and 2 v, the body-frame omega.
  ASSERT_EQ(m->nkey, 1);
  mj_resetDataKeyframe(m, d, 0);
  const double r = p.physical->radius;
  EXPECT_NEAR(d->qvel[0], r * omega0.y(), 1e-15);
  EXPECT_NEAR(d->qvel[1], -r * omega0.x(), 1e-15);
  EXPECT_LT((A0 * Eigen::Vector3d(d->qvel[3], d->qvel[4], d->qvel[5]) - omega0).norm(), 1e-14);
  EXPECT_NEAR(d->qvel[6], 2 * r * omega0.y(), 1e-15);
  EXPECT_NEAR(d->qpos[0], 1.5 * r, 1e-15);
  mj_deleteData(d);
  mj_deleteModel(m);
}

// The reason for the twin's own check: MuJoCo's compiler itself rejects I3 > 2 I1.
TEST(MujocoTwin, MujocosCompilerRejectsAnInertiaAgainstTheTriangleInequality) {
  const PhysicalParameters p{1.6e-5, 1.2e-5, 0.1, 0.02, 0.05};
  std::string xml = TwinMjcf(p, Eigen::Vector2d::Zero(), Eigen::Matrix3d::Identity(), TwinSettings{});
  const std::string good = "diaginertia=\"1.6e-05 1.6e-05 1.2e-05\"";
  ASSERT_NE(xml.find(good), std::string::npos);
  xml.replace(xml.find(good), good.size(), "diaginertia=\"1.6e-05 1.6e-05 4e-05\"");
  const std::string file = TempFile("bad_inertia.xml");
  std::ofstream(file) << xml;
  char error[1000] = "";
  mjModel* m = mj_loadXML(file.c_str(), nullptr, error, sizeof(error));
  EXPECT_EQ(m, nullptr);
  if (m) mj_deleteModel(m);
  EXPECT_NE(std::string(error).find("inertia"), std::string::npos) << error;
}

TEST(MujocoTwin, BallsMujocoCannotBuildAreNamed) {
  PhysicalParameters p{1.6e-5, 1.2e-5, 0.1, 0.02, 0.05};
  EXPECT_EQ(TwinBuildableMessage(p), "");
  p.inertia_3 = 2 * p.inertia_1 * (1 + 5e-13);  // within the reader's rigid-body rounding, not MuJoCo's
  EXPECT_EQ(p.Validate(), "");
  EXPECT_NE(TwinBuildableMessage(p).find("physical.inertia_3: value"), std::string::npos);
  EXPECT_THROW(TwinMjcf(p, Eigen::Vector2d::Zero(), Eigen::Matrix3d::Identity(), TwinSettings{}),
               std::invalid_argument);
  p.inertia_3 = 1.2e-5;
  p.plate_mass = 0.0;
  EXPECT_EQ(TwinBuildableMessage(p).rfind("physical.plate_mass: value 0:", 0), 0u);
}

TEST(MujocoTwin, ResultWithoutPhysicalBallIsNamed) {
  const std::string file = PlanResult(kSource + "/problems/circle.json", 8, "circle_lambda.json");
  try {
    ReadRigPlan(file);
    FAIL() << "a lambda-only ball was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("ball.physical: value (missing)", 0), 0u) << e.what();
  }
}

TEST(MujocoTwin, ResultOfAnotherBallThanItsProblemIsNamed) {
  const std::string file = PlanResult(kSource + "/problems/circle_physical.json", 8, "circle8.json");
  std::ifstream in(file);
  Json doc = Json::parse(in);
  doc["model"]["lambda"] = 0.96;
  std::ofstream(file) << DumpJson(doc);
  try {
    ReadRigPlan(file);
    FAIL() << "a result of another ball was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("model.lambda: value 0.96: the result was planned for another ball", 0), 0u)
        << e.what();
  }
}

TEST(MujocoTwin, OverlappingPulsesAndTooLittleFrictionAreNamed) {
  const RigPlan plan = ReadRigPlan(PlanResult(kSource + "/problems/circle_physical.json", 64, "circle64b.json"));
  const double flight = plan.impulses[1].t - plan.impulses[0].t;  // 0.19 s
  try {
    CheckPulseWindows(plan, 1.5 * flight, "--pulse-duration");
    FAIL() << "overlapping pulses were accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("the pulses of impulses 0 and 1 overlap"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(CheckPulseWindows(plan, 0.5 * flight, "--pulse-duration"));
  // With mu_s = 1e-3 the plate's weight (0.49 N) holds 0.5 mN: a 1 ms pulse needs more.
  ReplayOptions o;
  o.pulse_duration = 1e-3;
  o.settings.sliding_friction = 1e-3;
  try {
    ReplayInTwin(plan, PlannedTrajectory(plan), o);
    FAIL() << "a slipping pulse was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("pulse_duration: value 0.001: too short: impulse 0 would slip", 0), 0u)
        << e.what();
  }
}

}  // namespace
}  // namespace plateball::tools::rig
