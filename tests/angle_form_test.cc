// The angle form (19)-(21), (25)-(26) against the chart-free form (free_motion.h), conservation
// of K along it, and its behaviour at the poles (a status, never a hang).
#include "plateball/angle_form.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "plateball/ball_state.h"
#include "plateball/free_motion.h"
#include "support/test_support.h"

namespace plateball {
namespace {

// Both integrations run at 1e-12 tolerances; over a few periods their global errors stay near
// 1e-11, so 1e-9 leaves two orders of margin (the requirement).
constexpr double kFormAgreement = 1e-9;
// Conserved quantities over 100 periods at 1e-12 tolerances drift by ~1e-11 (measured).
constexpr double kConservation = 1e-10;

struct Case {
  double lambda;
  AngleState angles;
  double mu;
};

std::vector<Case> AgreementCases() {
  std::vector<Case> cases;
  for (double lambda : {0.3, 0.5, 0.9, 1.0, 1.5, 2.0, 5.0})
    for (const AngleState& a : {AngleState{M_PI / 3, 0.4, 0.1},
                                AngleState{2.4, -1.2, 0.7},
                                AngleState{1.1, 2.0, -2.5},
                                AngleState{0.5, 0.0, 1.2}})
      for (double mu : {1.0, 0.37, 4.2}) cases.push_back({lambda, a, mu});
  return cases;
}

TEST(AngleForm, AgreesWithChartFreeFormOnZOmegaAndX) {
  for (const Case& c : AgreementCases()) {
    const BallModel model = BallModel::FromLambda(c.lambda);
    const FreeMotion motion = FreeMotion::FromAngles(model, c.angles, c.mu, {0.3, -0.2});
    std::vector<double> times;
    for (int i = 0; i <= 60; ++i) times.push_back(i * 3.0 * motion.Period() / 60.0);
    const AngleFormResult r = IntegrateAngleForm(model, c.angles, c.mu, {0.3, -0.2}, times);
    ASSERT_EQ(r.status, AngleFormStatus::kCompleted) << r.message;
    ASSERT_EQ(r.samples.size(), times.size());
    for (const AngleFormSample& s : r.samples) {
      const MotionSample m = motion.At(s.t);
      const BallState from_angles = StateFromAngles(s.angles, c.mu, model);
      SCOPED_TRACE("lambda " + std::to_string(c.lambda) + " mu " + std::to_string(c.mu) + " t " + std::to_string(s.t));
      EXPECT_LT((from_angles.z - m.state.z).norm(), kFormAgreement);
      EXPECT_LT((from_angles.omega - m.state.omega).norm(), kFormAgreement);
      EXPECT_LT((s.x - m.x).norm(), kFormAgreement);
    }
  }
}

TEST(AngleForm, ConservesHorizontalMomentumOverHundredPeriods) {
  for (double lambda : {0.5, 1.0, 2.0, 5.0}) {
    const BallModel model = BallModel::FromLambda(lambda);
    for (const AngleState& a : {AngleState{M_PI / 3, 0.4, 0.1}, AngleState{2.2, 1.0, -0.3}}) {
      const double mu = 1.3;
      const double period = 2.0 * M_PI / std::sqrt(mu);
      std::vector<double> times;
      for (int k = 0; k <= 100; ++k) times.push_back(k * period + 0.37 * period * (k % 2));
      AngleFormOptions options;  // 1e-13: at 1e-12 the drift over 100 periods is ~1e-10 (measured)
      options.integration.absolute_tolerance = options.integration.relative_tolerance = 1e-13;
      const AngleFormResult r = IntegrateAngleForm(model, a, mu, {0, 0}, times, options);
      ASSERT_EQ(r.status, AngleFormStatus::kCompleted) << r.message;
      const Eigen::Vector2d k0 = ConservedMomentum(StateFromAngles(a, mu, model), model);
      double worst = 0.0;
      for (const AngleFormSample& s : r.samples)
        worst = std::max(worst, (ConservedMomentum(StateFromAngles(s.angles, mu, model), model) - k0).norm());
      EXPECT_LT(worst, kConservation) << "lambda " << lambda;
    }
  }
}

TEST(AngleForm, Equation2HoldsForTheHorizontalComponentsOnly) {
  // (2) integrates to (1 + beta) omega + (alpha - 1) v0 z = const; only its horizontal part (K)
  // is conserved: with omega_3 = 0 the vertical part would need v0 z3 constant, which fails for
  // alpha != 1 (the no-spin constraint exerts a vertical torque that (2) as printed omits).
  const BallModel model = BallModel::FromAlphaBeta(1.6, 0.5);
  const AngleState a{1.0, 0.3, -0.2};
  const double mu = 1.0;
  std::vector<double> times;
  for (int i = 0; i <= 40; ++i) times.push_back(0.15 * i);
  const AngleFormResult r = IntegrateAngleForm(model, a, mu, {0, 0}, times);
  ASSERT_EQ(r.status, AngleFormStatus::kCompleted);
  auto conserved = [&](const AngleState& s) {
    const PhaseVariables p = PhaseFromAngles(s, mu, model);
    return Eigen::Vector3d((1 + model.beta()) * p.omega + (model.alpha() - 1) * p.v0 * p.z);
  };
  const Eigen::Vector3d c0 = conserved(a);
  double horizontal = 0.0, vertical = 0.0;
  for (const AngleFormSample& s : r.samples) {
    const Eigen::Vector3d c = conserved(s.angles);
    horizontal = std::max(horizontal, (c - c0).head<2>().norm());
    vertical = std::max(vertical, std::abs(c.z() - c0.z()));
  }
  EXPECT_LT(horizontal, kConservation);
  EXPECT_GT(vertical, 1e-2);
}

TEST(AngleForm, ReturnsToInitialAnglesAfterOnePeriod) {
  // The periodicity theorem (docs/paper_notes.md): the whole angle state is 2 pi/sqrt(mu)
  // periodic for every lambda, phi and psi included (no winding).
  for (double lambda : {0.5, 2.0, 5.0}) {
    const BallModel model = BallModel::FromLambda(lambda);
    const AngleState a{1.0, 0.3, -0.8};
    const double mu = 2.0;
    const AngleFormResult r = IntegrateAngleForm(model, a, mu, {0, 0}, {2.0 * M_PI / std::sqrt(mu)});
    ASSERT_EQ(r.status, AngleFormStatus::kCompleted);
    EXPECT_NEAR(r.samples[0].angles.theta, a.theta, 1e-10);
    EXPECT_NEAR(r.samples[0].angles.phi, a.phi, 1e-10);
    EXPECT_NEAR(r.samples[0].angles.psi, a.psi, 1e-10);
  }
}

TEST(AngleForm, StopsWithStatusWhenTrajectoryReachesPole) {
  // c = sin(theta) cos(w) = 0 with w = pi/2: theta = theta0 - sqrt(mu) t reaches 0 at
  // t = theta0 / sqrt(mu); the integration must stop there with kReachedPole, not spin.
  const BallModel model = BallModel::FromLambda(2.0);
  const double mu = 1.0, theta0 = 0.8;
  const AngleState a{theta0, M_PI / 2, 0.0};
  AngleFormOptions options;
  options.pole_threshold = 1e-6;
  const AngleFormResult r = IntegrateAngleForm(model, a, mu, {0, 0}, {0.5, 2.0, 5.0}, options);
  EXPECT_EQ(r.status, AngleFormStatus::kReachedPole) << r.message;
  EXPECT_EQ(ToString(r.status), "reached_pole");
  ASSERT_EQ(r.samples.size(), 1u);  // t = 0.5 was reached, t = 2 was not
  // The pole is located inside the step that crosses it: theta = theta0 - t to ~threshold.
  EXPECT_NEAR(r.t_reached, theta0, 1e-5);
  EXPECT_LT(std::abs(std::sin(r.last.angles.theta)), 1e-5);
  EXPECT_LE(r.t_reached, 2.0);
}

TEST(AngleForm, StopsNearPoleForNearlyPolarTrajectory) {
  // |c| = 1e-9 < threshold: min |sin theta| = |c| on this trajectory.
  const BallModel model = BallModel::FromLambda(0.5);
  const double c = 1e-9, theta0 = 1.0;
  const double w0 = std::acos(c / std::sin(theta0));
  const AngleFormResult r = IntegrateAngleForm(model, {theta0, w0, 0.0}, 1.0, {0, 0}, {10.0});
  EXPECT_EQ(r.status, AngleFormStatus::kReachedPole) << r.message;
  EXPECT_LT(std::abs(std::sin(r.last.angles.theta)), 1e-3);
}

TEST(AngleForm, NearlyPolarTrajectoriesAboveTheThresholdAgreeWithChartFreeForm) {
  // min |sin theta| = |c| on a trajectory; for c = 1e-3 and 1e-5 (above the 1e-6 threshold) the
  // angle form passes close to the pole, where w turns by ~pi quickly, and still agrees.
  const BallModel model = BallModel::FromLambda(2.0);
  for (double c : {1e-3, 1e-5}) {
    const AngleState a{1.0, std::acos(c / std::sin(1.0)), 0.0};
    const FreeMotion motion = FreeMotion::FromAngles(model, a, 1.0);
    const AngleFormResult r = IntegrateAngleForm(model, a, 1.0, {0, 0}, {0.9, 1.0, 1.1, motion.Period()});
    ASSERT_EQ(r.status, AngleFormStatus::kCompleted) << r.message;
    for (const AngleFormSample& s : r.samples) {
      EXPECT_LT((StateFromAngles(s.angles, 1.0, model).z - motion.At(s.t).state.z).norm(), kFormAgreement);
      EXPECT_LT((s.x - motion.At(s.t).x).norm(), kFormAgreement);
    }
  }
}

TEST(AngleForm, StartOnPoleIsReportedNotIntegrated) {
  const BallModel model = BallModel::FromLambda(2.0);
  const AngleFormResult r = IntegrateAngleForm(model, {0.0, 0.2, 0.3}, 1.0, {0, 0}, {0.0, 1.0});
  EXPECT_EQ(r.status, AngleFormStatus::kReachedPole);
  EXPECT_EQ(r.t_reached, 0.0);
  EXPECT_EQ(r.samples.size(), 1u);
}

TEST(AngleForm, StepLimitIsAStatus) {
  const BallModel model = BallModel::FromLambda(2.0);
  AngleFormOptions options;
  options.integration.max_steps = 10;
  const AngleFormResult r = IntegrateAngleForm(model, {1.0, 0.2, 0.3}, 1.0, {0, 0}, {100.0}, options);
  EXPECT_EQ(r.status, AngleFormStatus::kStepLimit);
  EXPECT_EQ(ToString(r.status), "step_limit");
  EXPECT_GT(r.t_reached, 0.0);
  EXPECT_LT(r.t_reached, 100.0);
}

TEST(AngleForm, RejectsInvalidInputNamingTheField) {
  const BallModel model = BallModel::FromLambda(2.0);
  const auto message = [](auto&& f) { return plateball::testing::InvalidArgumentMessage(f, "no exception"); };
  EXPECT_NE(message([&] {
              IntegrateAngleForm(model, {1.0, 0.0, 0.0}, 0.0, {0, 0}, {1.0});
            }).find("mu"),
            std::string::npos);
  EXPECT_NE(message([&] {
              IntegrateAngleForm(model, {NAN, 0.0, 0.0}, 1.0, {0, 0}, {1.0});
            }).find("theta"),
            std::string::npos);
  EXPECT_NE(message([&] {
              IntegrateAngleForm(model, {1.0, 0.0, 0.0}, 1.0, {0, 0}, {2.0, 1.0});
            }).find("times[1]"),
            std::string::npos);
  AngleFormOptions bad;
  bad.pole_threshold = -1.0;
  EXPECT_NE(message([&] {
              IntegrateAngleForm(model, {1.0, 0.0, 0.0}, 1.0, {0, 0}, {1.0}, bad);
            }).find("pole_threshold"),
            std::string::npos);
}

TEST(AngleForm, DerivativeMatchesEquations19To21) {
  // Hand numbers: theta = pi/2 (cot = 0) leaves only theta' = -b sin(w) and x'.
  const BallModel model = BallModel::FromLambda(2.0);
  AngleState d;
  Eigen::Vector2d dx;
  AngleFormDerivative({M_PI / 2, 0.0, -M_PI / 6}, 4.0, model, &d, &dx);  // w = pi/6, b = 2
  EXPECT_NEAR(d.theta, -1.0, 1e-15);
  EXPECT_NEAR(d.phi, 0.0, 1e-15);
  EXPECT_NEAR(d.psi, 0.0, 1e-15);
  // a = b / sqrt(lambda) = sqrt(2); (25)-(26) at phi = 0: x' = (-b sin w, -a cos w).
  EXPECT_NEAR(dx.x(), -1.0, 1e-15);
  EXPECT_NEAR(dx.y(), -std::sqrt(2.0) * std::cos(M_PI / 6), 1e-15);
}

}  // namespace
}  // namespace plateball
