#include "plateball/impulse_planner.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

#include "plateball/free_motion.h"
#include "plateball/partition.h"
#include "plateball/rolling.h"
#include "plateball/so3.h"
#include "plateball/task_adapters.h"
#include "support/test_support.h"

using namespace plateball;

namespace {
// The T1/T2 goal: the impulsive trajectory passes through every partition point to this.
constexpr double kPassTolerance = 1e-10;
// Orientations from integrations at tolerance 1e-12 over at most a few hundred steps.
constexpr double kOrientationTolerance = 1e-9;

const BallModel kModel = BallModel::FromLambda(2.0);
const AngleState kStart{M_PI / 3, 0.4, 0.1};

std::string ErrorOf(const std::function<void()>& f) { return plateball::testing::InvalidArgumentMessage(f, ""); }

Path T2Circle() { return Path({SmoothCurve::Circle({-2, 0}, 2, 0, 2 * M_PI)}); }

PlanProblem MakePlan(const Path& path,
                     std::vector<PartitionRule> partition,
                     std::vector<EnergyChange> changes = {},
                     double mu = 1.0,
                     const Eigen::Matrix3d& A0 = Eigen::Matrix3d::Identity()) {
  return PlanProblem{{kModel, kStart, mu, A0}, path, std::move(partition), std::move(changes)};
}

PlanSummary PlanUniform(const Path& path,
                        int n,
                        const std::vector<EnergyChange>& changes = {},
                        const PlanOptions& options = {}) {
  return PlanImpulses(MakePlan(path, {UniformParameter{n}}, changes), options);
}
}  // namespace

TEST(ImpulsePlanner, PassesThroughEveryPartitionPointCheckedByFreeMotion) {
  const PlanSummary plan = PlanUniform(T2Circle(), 24);
  ASSERT_TRUE(plan.IsSolutionUsable()) << plan.BriefReport();
  ASSERT_EQ(plan.steps.size(), 24u);
  Eigen::Matrix3d a = plan.A0;
  Eigen::Vector2d x(0, 0);
  for (const PlanStep& s : plan.steps) {
    // Re-simulate the arc with FreeMotion (one period stored, evaluated at t_k): a second method.
    FreeMotionStart fs;
    fs.state = s.impulse.state_after;
    fs.x0 = x;
    fs.A0 = a;
    const FreeMotion m(kModel, fs);
    const MotionSample end = m.At(s.duration);
    EXPECT_LT((end.x - s.p_end).norm(), kPassTolerance) << "segment " << s.global_index;
    EXPECT_LT((end.A - s.A_impulsive).norm(), kOrientationTolerance) << "segment " << s.global_index;
    EXPECT_NEAR(s.impulse.mu_after, 1.0, 1e-14);  // energy-preserving impulses
    EXPECT_GT(s.duration, 0.0);
    x = end.x;
    a = end.A;
  }
  EXPECT_LE(plan.max_pass_miss, kPassTolerance);
  // The orientation carries the symmetry axis: A e3 = z.
  EXPECT_LT((plan.A_impulsive.col(2) - plan.final_state.z).norm(), 1e-9);
  EXPECT_TRUE(plateball::testing::IsRotationMatrix(plan.A_impulsive, 1e-12));
}

TEST(ImpulsePlanner, PlannedOrientationOnACircleMatchesTheClosedForm) {
  // Rolling along c + rho (cos tau, sin tau): omega = e3 x p' = Rz(tau) w0 with w0 = (-rho, 0, 0),
  // so A = Rz(tau) B gives B' = hat(w0 - e3) B: A(tau) = Rz(tau) exp(tau hat(w0 - e3)) A0 (any c).
  const double rho = 2.0;
  const PlanSummary plan = PlanUniform(T2Circle(), 16);
  ASSERT_TRUE(plan.IsSolutionUsable());
  const Eigen::Vector3d w0(-rho, 0, 0);
  for (const PlanStep& s : plan.steps) {
    const Eigen::Matrix3d exact = RotationZ(s.tau_end) * ExpSO3(s.tau_end * (w0 - Eigen::Vector3d::UnitZ())) * plan.A0;
    EXPECT_LT(OperatorNormDistance(exact, s.A_planned), kOrientationTolerance) << "tau " << s.tau_end;
  }
}

TEST(ImpulsePlanner, PathMaximaPerStepAreNeverBelowADenseIndependentSampling) {
  // Every step's max|p'|, max|p''| against |p'|, |p''| from central differences of p itself at 401
  // points of [tau_k, tau_k+1] (independent of the curves' derivative code): never below them; on
  // lines and circles (constants) equal to them, elsewhere (5 samples plus the largest change)
  // within 10%. And p_begin (carried from the previous step) is p(tau_begin).
  const std::vector<Path> paths{T2Circle(),
                                Path({SmoothCurve::Circle({1, 0}, 1.5, M_PI, 0.0)}),  // reversed
                                Path({SmoothCurve::Line({0, 0}, {1.2, -0.7})}),
                                Path({SmoothCurve::Ellipse({0, 0}, {2, 1}, 0.3, 0, 2 * M_PI)})};
  for (const Path& path : paths) {
    const PlanSummary plan = PlanUniform(path, 24);
    ASSERT_TRUE(plan.IsSolutionUsable()) << plan.message;
    const SmoothCurve& curve = path.pieces()[0];
    const bool constant = curve.kind() == CurveKind::kLine || curve.kind() == CurveKind::kCircle;
    for (const PlanStep& s : plan.steps) {
      double speed = 0.0, acceleration = 0.0;
      const double h = 1e-4;
      for (int i = 0; i <= 400; ++i) {
        const double tau = s.tau_begin + (s.tau_end - s.tau_begin) * i / 400;
        const Eigen::Vector2d pm = curve.Value(tau - h), p0 = curve.Value(tau), pp = curve.Value(tau + h);
        speed = std::max(speed, ((pp - pm) / (2 * h)).norm());
        acceleration = std::max(acceleration, ((pp - 2 * p0 + pm) / (h * h)).norm());
      }
      EXPECT_GE(s.path_max_speed, speed - 1e-7);
      EXPECT_GE(s.path_max_acceleration, acceleration - 1e-5);
      EXPECT_LE(s.path_max_speed, constant ? speed + 1e-7 : 1.1 * speed);
      EXPECT_LE(s.path_max_acceleration, constant ? acceleration + 1e-5 : 1.1 * acceleration);
      EXPECT_EQ(s.p_begin, curve.Value(s.tau_begin));
    }
  }
}

TEST(ImpulsePlanner, PolylineOrientationIsTheProductOfSegmentRolls) {
  const Path path({SmoothCurve::Lemniscate({0, 0}, 2, 0, 0, 2 * M_PI)});
  const PlanSummary plan = PlanUniform(path, 20);
  ASSERT_TRUE(plan.IsSolutionUsable());
  std::vector<Eigen::Vector2d> pts{plan.steps.front().p_begin};
  for (const auto& s : plan.steps) pts.push_back(s.p_end);
  EXPECT_LT(OperatorNormDistance(RollAlongPolyline(pts) * plan.A0, plan.A_polyline), 1e-12);
}

TEST(ImpulsePlanner, ReportedBoundHoldsAndCorollary3IsAboveTheorem26) {
  for (int n : {16, 64}) {
    const PlanSummary plan = PlanUniform(T2Circle(), n);
    ASSERT_TRUE(plan.IsSolutionUsable());
    EXPECT_LE(plan.measured_error, plan.bounds.a_posteriori);
    EXPECT_LE(plan.polyline_error, plan.bounds.a_posteriori_path);
    EXPECT_LE(plan.polyline_error, plan.bounds.theorem_2_5);
    EXPECT_LE(plan.measured_error, plan.bounds.theorem_2_6);
    EXPECT_LE(plan.bounds.theorem_2_6, plan.bounds.corollary_3 * (1 + 1e-12));
    // Uniform partition of [0, 2 pi]: Corollary 3 is (Kbar + Ktilde) T^3 / n^2.
    const auto& c = plan.bounds.constants;
    EXPECT_NEAR(plan.bounds.corollary_3,
                (c.K_bar_p + c.K_tilde_p) * std::pow(2 * M_PI, 3) / (n * n),
                1e-12 * plan.bounds.corollary_3);
    // On a circle of radius 2: |p'| = 2, |p''| = 2 exactly.
    EXPECT_NEAR(c.K_p, 2.0, 1e-12);
    EXPECT_NEAR(c.M_prime_p, 2.0, 1e-12);
  }
}

TEST(ImpulsePlanner, EnergyChangingImpulsesKeepTheGeometry) {
  const Path path({SmoothCurve::Ellipse({0, 0}, {2, 1}, 0.3, 0, 2 * M_PI)});
  const PlanSummary plain = PlanUniform(path, 32);
  const PlanSummary changed = PlanUniform(path, 32, {{3, 2.0}, {10, 0.5}, {10, 0.8}});
  ASSERT_TRUE(plain.IsSolutionUsable());
  ASSERT_TRUE(changed.IsSolutionUsable());
  double speed = 1.0;
  for (std::size_t k = 0; k < plain.steps.size(); ++k) {
    const PlanStep& a = plain.steps[k];
    const PlanStep& b = changed.steps[k];
    if (k == 3) speed *= 2.0;
    if (k == 10) speed *= 0.4;
    EXPECT_EQ(b.energy_changes.size(), k == 3 ? 1u : k == 10 ? 2u : 0u);
    EXPECT_NEAR(b.mu, speed * speed, 1e-12);
    // Same path on the plate, traversed 1/speed faster: same impulse angle, time / speed.
    EXPECT_NEAR(std::remainder(a.delta_psi - b.delta_psi, 2 * M_PI), 0.0, 1e-9) << k;
    EXPECT_NEAR(b.duration * speed, a.duration, 1e-9) << k;
    EXPECT_LT(OperatorNormDistance(a.A_impulsive, b.A_impulsive), kOrientationTolerance) << k;
    EXPECT_LT((a.x_end - b.x_end).norm(), kPassTolerance);
  }
  EXPECT_NEAR(changed.mu_final, 0.64, 1e-12);  // (2 * 0.5 * 0.8)^2
  EXPECT_NEAR(plain.measured_error, changed.measured_error, 1e-9);
}

TEST(ImpulsePlanner, PiecewisePathIsPlannedPieceByPiece) {
  const Path path({SmoothCurve::Line({0, 0}, {2, 0}),
                   SmoothCurve::Circle({2, 1}, 1, -M_PI / 2, M_PI / 2),
                   SmoothCurve::Line({2, 2}, {0, 3})});
  const PlanSummary plan = PlanUniform(path, 12);
  ASSERT_TRUE(plan.IsSolutionUsable()) << plan.BriefReport();
  EXPECT_EQ(plan.segments, 36);
  EXPECT_EQ(plan.steps[12].piece, 1);
  EXPECT_EQ(plan.steps[12].index, 0);
  EXPECT_LE(plan.max_pass_miss, kPassTolerance);
  EXPECT_LE(plan.measured_error, plan.bounds.a_posteriori);
  // Straight pieces: chords are the path, so the polyline is exact there (path bound 0).
  EXPECT_EQ(plan.steps[0].path_bound, 0.0);
}

TEST(ImpulsePlanner, FailedJoinIsAStatusNamingTheSegment) {
  PlanOptions o;
  o.join.max_iterations = 1;  // cannot converge from the ellipse guess on long segments
  o.reach_fallback = false;   // and no global reach to fall back on
  const PlanSummary plan = PlanUniform(T2Circle(), 4, {}, o);
  EXPECT_EQ(plan.status, PlanStatus::kSegmentBeyondLocalRadius);
  EXPECT_NE(plan.message.find("segment 0"), std::string::npos) << plan.message;
  EXPECT_FALSE(plan.IsSolutionUsable());
}

TEST(ImpulsePlanner, BadInputNamesTheField) {
  const Path path = T2Circle();
  const std::vector<PartitionRule> part{UniformParameter{8}};
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  EXPECT_NE(ErrorOf([&] { PlanImpulses(MakePlan(path, {})); }).find("partition (rule count)"), std::string::npos);
  EXPECT_NE(ErrorOf([&] { PlanImpulses(MakePlan(path, {ExplicitTaus{{0.0}}})); }).find("at least 2 points"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] { PlanImpulses(MakePlan(path, {UniformArcLength{0}})); }).find("partition.n"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] {
              PlanImpulses(MakePlan(path, part, {{8, 2.0}}));
            }).find("energy_changes[0].index"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] {
              PlanImpulses(MakePlan(path, part, {{1, 0.0}}));
            }).find("energy_changes[0].factor"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] { PlanImpulses(MakePlan(path, part, {}, 0.0)); }).find("mu"), std::string::npos);
  EXPECT_NE(ErrorOf([&] { PlanImpulses(MakePlan(path, part, {}, 1.0, 2.0 * I)); }).find("A0"), std::string::npos);
  Problem p;
  p.model = kModel;
  p.plan = PlanTask{};
  p.plan->path = PathSpec{CircleSpec{{-2, 0}, 2, 0, 2 * M_PI}};
  p.x0 = {1, 1};
  EXPECT_NE(ErrorOf([&] { PlanSetupFor(p); }).find("initial.x0: value"), std::string::npos);
  p.x0 = {0, 0};
  const PlanSetup setup = PlanSetupFor(p);
  EXPECT_TRUE(PlanImpulses(setup.problem, setup.options).IsSolutionUsable());
  Problem none;
  none.source = "none.json";
  EXPECT_NE(ErrorOf([&] { PlanSetupFor(none); }).find("none.json: plan: value (missing)"), std::string::npos);
}

// An integration failure is a status, not an exception (the file's integration section).
TEST(ImpulsePlanner, StepBoundExceededIsAnIntegrationFailureStatus) {
  PlanOptions o;
  o.integration.max_steps = 5;
  o.join.integration.max_steps = 5;
  const PlanSummary plan = PlanUniform(T2Circle(), 8, {}, o);
  EXPECT_EQ(plan.status, PlanStatus::kIntegrationFailure) << plan.BriefReport();
  EXPECT_FALSE(plan.message.empty());
}
