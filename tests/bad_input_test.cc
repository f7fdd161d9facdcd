// Table-driven bad-input suite over the library: every case must end in a
// std::invalid_argument whose message names the offending field (and, where there is one, the
// value), or in a reported status — never a crash, a hang or a NaN.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "plateball/ball_model.h"
#include "plateball/ball_state.h"
#include "plateball/cubic_spline.h"
#include "plateball/free_motion.h"
#include "plateball/impulse.h"
#include "plateball/join.h"
#include "plateball/partition.h"
#include "plateball/path.h"
#include "plateball/problem_io.h"
#include "plateball/rolling.h"
#include "plateball/so3.h"
#include "plateball/task_adapters.h"

namespace plateball {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

struct BadInputCase {
  std::string name;
  std::function<void()> call;
  std::vector<std::string> message_must_contain;  // field name, and the value where it has one
};

const BallModel& Model() {
  static const BallModel m = BallModel::FromLambda(2.0);
  return m;
}

PhysicalParameters GoodPhysical() {
  PhysicalParameters p;
  p.inertia_1 = 0.4;
  p.inertia_3 = 0.5;
  p.ball_mass = 1.0;
  p.radius = 1.0;
  p.plate_mass = 0.2;
  return p;
}

PathSpec Circle(double radius) { return {CircleSpec{{-radius, 0.0}, radius, 0.0, 1.0}}; }

std::string MinimalProblem(const std::string& initial_extra, const std::string& top_extra = "") {
  return R"({"ball": {"lambda": 2}, "initial": {"theta": 1.0, "phi": 0.4, "psi": 0.1, "mu": 1)" + initial_extra + "}" +
         top_extra + "}";
}

std::vector<BadInputCase> Cases() {
  std::vector<BadInputCase> c;
  c.push_back({"lambda zero", [] { BallModel::FromLambda(0.0); }, {"lambda", "0"}});
  c.push_back({"lambda negative", [] { BallModel::FromLambda(-1.5); }, {"lambda", "-1.5"}});
  c.push_back({"lambda NaN", [] { BallModel::FromLambda(kNaN); }, {"lambda", "nan"}});
  c.push_back({"lambda infinite", [] { BallModel::FromLambda(kInf); }, {"lambda", "inf"}});
  c.push_back({"negative ball mass",
               [] {
                 auto p = GoodPhysical();
                 p.ball_mass = -2;
                 BallModel::FromPhysical(p);
               },
               {"ball_mass", "-2"}});
  c.push_back({"negative plate mass",
               [] {
                 auto p = GoodPhysical();
                 p.plate_mass = -0.5;
                 BallModel::FromPhysical(p);
               },
               {"plate_mass", "-0.5"}});
  c.push_back({"I3 above I1 + I2",
               [] {
                 auto p = GoodPhysical();
                 p.inertia_3 = 0.9;
                 BallModel::FromPhysical(p);
               },
               {"inertia_3", "0.9"}});
  c.push_back({"zero radius",
               [] {
                 auto p = GoodPhysical();
                 p.radius = 0;
                 BallModel::FromPhysical(p);
               },
               {"radius", "0"}});
  c.push_back({"NaN inertia",
               [] {
                 auto p = GoodPhysical();
                 p.inertia_1 = kNaN;
                 BallModel::FromPhysical(p);
               },
               {"inertia_1", "nan"}});
  c.push_back({"negative energy", [] { StateFromAngles({1.0, 0.4, 0.1}, -1.0, Model()); }, {"mu", "-1"}});
  c.push_back({"zero energy", [] { StateFromAngles({1.0, 0.4, 0.1}, 0.0, Model()); }, {"mu", "0"}});
  c.push_back({"NaN theta", [] { StateFromAngles({kNaN, 0.4, 0.1}, 1.0, Model()); }, {"theta", "nan"}});
  c.push_back({"infinite psi", [] { StateFromAngles({1.0, 0.4, kInf}, 1.0, Model()); }, {"psi", "inf"}});
  c.push_back({"non-unit symmetry axis",
               [] {
                 FreeMotionStart s;
                 s.state.z = {0.0, 0.0, 2.0};
                 s.state.omega = {1.0, 0.0, 0.0};
                 FreeMotion(Model(), s);
               },
               {"z", "2"}});
  c.push_back({"spinning state",
               [] {
                 FreeMotionStart s;
                 s.state.omega = {1.0, 0.0, 0.5};
                 FreeMotion(Model(), s);
               },
               {"omega", "0.5"}});
  c.push_back({"ball at rest has no period",
               [] {
                 FreeMotionStart s;
                 FreeMotion(Model(), s);
               },
               {"mu", "0"}});
  c.push_back({"initial orientation not a rotation",
               [] {
                 FreeMotion::FromAngles(Model(), {1.0, 0.4, 0.1}, 1.0, {0, 0}, 2.0 * Eigen::Matrix3d::Identity());
               },
               {"A0"}});
  c.push_back({"NaN evaluation time",
               [] {
                 FreeMotion::FromAngles(Model(), {1.0, 0.4, 0.1}, 1.0).At(kNaN);
               },
               {"t", "nan"}});
  c.push_back({"absurd evaluation time",
               [] {
                 FreeMotion::FromAngles(Model(), {1.0, 0.4, 0.1}, 1.0).At(1e200);
               },
               {"t", "1e+200"}});
  c.push_back({"negative tolerance",
               [] {
                 IntegrationOptions o;
                 o.absolute_tolerance = -1e-9;
                 FreeMotion::FromAngles(Model(), {1.0, 0.4, 0.1}, 1.0, {0, 0}, Eigen::Matrix3d::Identity(), o);
               },
               {"absolute_tolerance", "-1e-09"}});
  c.push_back({"zero step budget",
               [] {
                 IntegrationOptions o;
                 o.max_steps = 0;
                 FreeMotion::FromAngles(Model(), {1.0, 0.4, 0.1}, 1.0, {0, 0}, Eigen::Matrix3d::Identity(), o);
               },
               {"max_steps", "0"}});
  c.push_back({"NaN join target",
               [] {
                 Join(JoinProblem{Model(), AngleState{1.0, 0.4, 0.1}, 1.0, {0, 0}, {kNaN, 0.0}});
               },
               {"target", "nan"}});
  c.push_back({"zero join iterations",
               [] {
                 JoinOptions o;
                 o.max_iterations = 0;
                 Join(JoinProblem{Model(), AngleState{1.0, 0.4, 0.1}, 1.0, {0, 0}, {0.01, 0.0}}, o);
               },
               {"max_iterations", "0"}});
  c.push_back({"negative join tolerance",
               [] {
                 JoinOptions o;
                 o.residual_tolerance = -1.0;
                 Join(JoinProblem{Model(), AngleState{1.0, 0.4, 0.1}, 1.0, {0, 0}, {0.01, 0.0}}, o);
               },
               {"residual_tolerance", "-1"}});
  c.push_back({"zero speed-up factor",
               [] {
                 EnergyChangingImpulse({1.0, 0.4, 0.1}, 1.0, 0.0, Model());
               },
               {"factor", "0"}});
  c.push_back({"infinite impulse",
               [] {
                 EnergyPreservingImpulse({1.0, 0.4, 0.1}, 1.0, kInf, Model());
               },
               {"delta_psi", "inf"}});
  c.push_back({"negative circle radius", [] { PathFromSpec(Circle(-1.0)); }, {"radius", "-1"}});
  c.push_back({"repeated sample points",
               [] {
                 PathFromSpec(PathSpec{SamplesSpec{{{0, 0}, {1, 0}, {1, 0}, {2, 1}}}});
               },
               {"points[2]"}});
  c.push_back({"NaN sample point",
               [] {
                 PathFromSpec(PathSpec{SamplesSpec{{{0, 0}, {kNaN, 0}, {2, 1}}}});
               },
               {"points[1]", "nan"}});
  c.push_back({"single sample point", [] { CubicSpline2d({Eigen::Vector2d(1, 2)}); }, {"points", "1"}});
  c.push_back({"zero-speed line", [] { PathFromSpec(PathSpec{LineSpec{{1, 1}, {1, 1}}}); }, {"path"}});
  c.push_back({"zero wavelength sine",
               [] {
                 PathFromSpec(PathSpec{SineSpec{{0, 0}, 0.0, 2, 0.5, 0}});
               },
               {"wavelength", "0"}});
  c.push_back(
      {"partition of one point", [] { MakePartition(PathFromSpec(Circle(1.0)), {UniformParameter{0}}); }, {"n", "0"}});
  c.push_back({"non-increasing explicit partition",
               [] {
                 MakePartition(PathFromSpec(Circle(1.0)), {ExplicitTaus{{0.0, 0.5, 0.4, 1.0}}});
               },
               {"taus"}});
  c.push_back({"zero quaternion",
               [] { QuaternionToRotation(Eigen::Vector4d::Zero(), "goal_orientation"); },
               {"goal_orientation"}});
  c.push_back({"NaN polyline point", [] { RollAlongPolyline({{0, 0}, {kNaN, 1}}); }, {"points[1]", "nan"}});
  c.push_back(
      {"malformed problem file", [] { ParseProblem("{\"ball\": {\"lambda\": 2,,}", "bad.json"); }, {"bad.json"}});
  c.push_back({"unknown key in problem file",
               [] { ParseProblem(MinimalProblem("", R"(, "colour": "red")"), "p.json"); },
               {"p.json", "colour"}});
  c.push_back({"negative energy in problem file",
               [] {
                 ParseProblem(R"({"ball": {"lambda": 2}, "initial": {"theta": 1, "phi": 0, "psi": 0, "mu": -3}})",
                              "p.json");
               },
               {"p.json", "initial.mu", "-3"}});
  c.push_back(
      {"orientation matrix that is not a rotation",
       [] { ParseProblem(MinimalProblem(R"(, "orientation": {"matrix": [[1,0,0],[0,1,0],[0,0,-1]]})"), "p.json"); },
       {"p.json", "orientation"}});
  c.push_back({"wrong type in problem file",
               [] {
                 ParseProblem(R"({"ball": {"lambda": "two"}, "initial": {"theta": 1, "phi": 0, "psi": 0, "mu": 1}})",
                              "p.json");
               },
               {"p.json", "ball.lambda"}});
  c.push_back({"non-finite number in problem file",
               [] {
                 ParseProblem(R"({"ball": {"lambda": 1e999}, "initial": {"theta": 1, "phi": 0, "psi": 0, "mu": 1}})",
                              "p.json");
               },
               {"p.json"}});
  return c;
}

TEST(BadInput, EveryCaseThrowsInvalidArgumentNamingFieldAndValue) {
  const std::vector<BadInputCase> cases = Cases();
  EXPECT_GE(cases.size(), 30u);
  for (const BadInputCase& bad : cases) {
    SCOPED_TRACE(bad.name);
    try {
      bad.call();
      ADD_FAILURE() << "no error for case '" << bad.name << "'";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      for (const std::string& needle : bad.message_must_contain)
        EXPECT_NE(what.find(needle), std::string::npos)
            << "message '" << what << "' does not contain '" << needle << "'";
    } catch (const std::exception& e) {
      ADD_FAILURE() << "case '" << bad.name << "' threw a non-input error: " << e.what();
    }
  }
}

TEST(BadInput, TargetEqualToStartIsAStatusNotAnError) {
  const JoinSummary j = Join(JoinProblem{Model(), AngleState{1.0, 0.4, 0.1}, 1.0, {0.3, 0.2}, {0.3, 0.2}});
  EXPECT_EQ(j.status, JoinStatus::kTargetEqualsStart);
  EXPECT_FALSE(j.IsSolutionUsable());
  EXPECT_TRUE(std::isfinite(j.t));
}

TEST(BadInput, StarvedIntegrationEndsInABoundedError) {
  // A step budget far too small for one period: the integration must stop with a message naming
  // the bound, not run on or return a truncated period as if it were whole.
  IntegrationOptions o;
  o.max_steps = 3;
  try {
    FreeMotion::FromAngles(Model(), {1.0, 0.4, 0.1}, 1.0, {0, 0}, Eigen::Matrix3d::Identity(), o);
    FAIL() << "a 3-step budget cannot cover a period";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("max_steps"), std::string::npos) << e.what();
  }
}

TEST(BadInput, StarvedJoinReturnsAStatusWithFiniteNumbers) {
  // One iteration from the guess cannot reach 1e-12 for a target at distance 1.5 (t sqrt(mu) ~ 1.5:
  // the join needs three without the cap): a status comes back, with finite numbers.
  JoinOptions o;
  o.max_iterations = 1;
  const JoinProblem problem{Model(), AngleState{1.0, 0.4, 0.1}, 1.0, {0, 0}, {1.2, 0.9}};
  ASSERT_EQ(Join(problem).status, JoinStatus::kConverged);
  const JoinSummary j = Join(problem, o);
  EXPECT_NE(j.status, JoinStatus::kConverged);
  EXPECT_TRUE(std::isfinite(j.residual));
  EXPECT_TRUE(std::isfinite(j.delta_psi));
  EXPECT_TRUE(std::isfinite(j.t));
}

}  // namespace
}  // namespace plateball
