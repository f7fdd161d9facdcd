#include "plateball/join.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <stdexcept>

#include "plateball/ball_state.h"
#include "plateball/free_motion.h"
#include "plateball/impulse.h"

using namespace plateball;

namespace {
// Every join must land on its target to this (the T1 goal); checked by an independent integration.
constexpr double kReachTolerance = 1e-10;
// Integration tolerance 1e-12 over arcs of length <= 1: state agreement between two integrations.
constexpr double kStateTolerance = 1e-10;

// The end point of the free motion from `start` with psi shifted by s, by direct integration
// (IntegrateFreeMotion: a different code path from the join's sensitivity rollout).
MotionSample Arrive(
    const BallModel& model, const AngleState& start, double mu, const Eigen::Vector2d& x0, double s, double t) {
  FreeMotionStart fs;
  fs.state = StateFromAngles({start.theta, start.phi, start.psi + s}, mu, model);
  fs.x0 = x0;
  Eigen::Matrix3d a0 = Eigen::Matrix3d::Identity();
  // Any frame whose third column is z.
  const Eigen::Vector3d z = fs.state.z;
  Eigen::Vector3d e1 = std::abs(z.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  e1 = (e1 - e1.dot(z) * z).normalized();
  a0.col(0) = e1;
  a0.col(1) = z.cross(e1);
  a0.col(2) = z;
  fs.A0 = a0;
  return IntegrateFreeMotion(model, fs, {t}).front();
}
}  // namespace

TEST(Join, ReachesEveryT1TargetCheckedByIndependentIntegration) {
  const BallModel model = BallModel::FromLambda(2.0);
  const AngleState start{M_PI / 3, 0.4, 0.1};
  const Eigen::Vector2d x0(0, 0);
  for (int k = 0; k < 64; ++k) {
    const double b = 2 * M_PI * k / 64;
    const Eigen::Vector2d target = 0.05 * Eigen::Vector2d(std::cos(b), std::sin(b));
    const JoinSummary j = Join(JoinProblem{model, start, 1.0, x0, target});
    ASSERT_EQ(j.status, JoinStatus::kConverged) << j.BriefReport();
    EXPECT_GT(j.t, 0.0);
    EXPECT_LE(j.residual, 1e-12);
    const MotionSample end = Arrive(model, start, 1.0, x0, j.delta_psi, j.t);
    EXPECT_LT((end.x - target).norm(), kReachTolerance) << "k = " << k;
    EXPECT_LT((end.state.z - j.state_after.z).norm(), kStateTolerance);
    EXPECT_LT((end.state.omega - j.state_after.omega).norm(), kStateTolerance);
  }
}

// The ways a join ends: the check rollout at the guess refined on the Taylor model is the answer
// (a short arc: 0 iterations); the check misses the tolerance and quasi-Newton steps on rollouts
// of (z, x) go on from it (the model's truncation error grows with the arc); the model as a guess
// only (t sqrt(mu) > 0.2: one rollout with the variational equations at the model's point, then
// quasi-Newton steps; 0.75 is T2's segment at n = 16). Levenberg-Marquardt only where those fail
// (below: the tight tolerance).
// Each lands on its target, checked by an independent integration, with a Jacobian conditioning
// that agrees with the one of the exact rollouts.
TEST(Join, ModelCheckAndIterationPathsAllReachTheTarget) {
  const BallModel model = BallModel::FromLambda(2.0);
  const AngleState start{M_PI / 3, 0.4, 0.1};
  const Eigen::Vector2d x0(0.3, -0.2);
  struct Case {
    double distance;
    bool zero_iterations;
  };
  for (const Case c : {Case{0.05, true}, Case{0.15, false}, Case{0.35, false}, Case{0.75, false}}) {
    for (int k = 0; k < 8; ++k) {
      const double b = 2 * M_PI * k / 8 + 0.1;
      const Eigen::Vector2d target = x0 + c.distance * Eigen::Vector2d(std::cos(b), std::sin(b));
      const JoinSummary j = Join(JoinProblem{model, start, 1.0, x0, target});
      ASSERT_EQ(j.status, JoinStatus::kConverged) << j.BriefReport();
      EXPECT_EQ(j.iterations == 0, c.zero_iterations) << "distance " << c.distance << ": " << j.BriefReport();
      EXPECT_LE(j.iterations, 6) << "distance " << c.distance << ": " << j.BriefReport();  // superlinear steps
      EXPECT_LE(j.residual, 1e-12);
      const MotionSample end = Arrive(model, start, 1.0, x0, j.delta_psi, j.t);
      EXPECT_LT((end.x - target).norm(), 1e-12) << "distance " << c.distance << ", k = " << k;
      // The same join with a tolerance no check reaches: the iteration on exact rollouts to
      // round-off. Both answers are within 1e-12 of the target, so (s, t) agree to ~1e-12 / |J|.
      JoinOptions tight;
      tight.residual_tolerance = 1e-15;
      const JoinSummary e = Join(JoinProblem{model, start, 1.0, x0, target}, tight);
      EXPECT_GE(e.iterations, 1);
      EXPECT_NEAR(e.delta_psi, j.delta_psi, 1e-9) << "distance " << c.distance << ", k = " << k;
      EXPECT_NEAR(e.t, j.t, 1e-9);
      EXPECT_NEAR(e.jacobian_conditioning, j.jacobian_conditioning, 1e-5);
    }
  }
}

// On arcs beyond the Taylor model's check (t sqrt(mu) 0.3 ... 1) the first rollout is at the
// guess refined on the model (at 0.75 on the order-13 one): its residual is 7e-8 / 1e-6 / 3e-5 at
// distances 0.25 / 0.35 / 0.75 where the ellipse guess left 1.3e-2 / 2.6e-2 / 0.12, and the joins
// take 1 / 1.1 / 1.75 quasi-Newton steps instead of 3.3 / 3.5 / 3.9 (docs/benchmarks.md, "The
// Taylor model as the long arcs' guess"). Each answer is checked by an independent integration.
TEST(Join, LongArcsStartFromTheGuessRefinedOnTheTaylorModel) {
  const BallModel model = BallModel::FromLambda(2.0);
  const AngleState start{M_PI / 3, 0.4, 0.1};
  const Eigen::Vector2d x0(0.3, -0.2);
  struct Case {
    double distance, first_residual;
    int iterations;  // over the 8 directions
  };
  for (const Case c : {Case{0.25, 1e-6, 8}, Case{0.35, 1e-5, 10}, Case{0.75, 1e-4, 15}}) {
    int iterations = 0;
    for (int k = 0; k < 8; ++k) {
      const double b = 2 * M_PI * k / 8 + 0.1;
      const Eigen::Vector2d target = x0 + c.distance * Eigen::Vector2d(std::cos(b), std::sin(b));
      const JoinSummary j = Join(JoinProblem{model, start, 1.0, x0, target});
      ASSERT_EQ(j.status, JoinStatus::kConverged) << j.BriefReport();
      EXPECT_GT(j.t * std::sqrt(j.mu), 0.2) << "beyond the model's check";
      EXPECT_LT(j.initial_guess_residual, c.first_residual) << "distance " << c.distance << ", k = " << k;
      iterations += j.iterations;
      const MotionSample end = Arrive(model, start, 1.0, x0, j.delta_psi, j.t);
      EXPECT_LT((end.x - target).norm(), 1e-12) << "distance " << c.distance << ", k = " << k;
    }
    EXPECT_LE(iterations, c.iterations) << "distance " << c.distance;
  }
}

TEST(Join, HomogeneousBallMovesStraightAtSpeedSqrtMu) {
  // lambda = 1: K = omega_h is constant, so x' is constant with |x'|^2 = mu (eq. (9)):
  // t = |target - x0| / sqrt(mu) exactly.
  const BallModel model = BallModel::FromLambda(1.0);
  const double mu = 2.5;
  const Eigen::Vector2d x0(1.0, -2.0);
  for (double b : {0.0, 1.0, 2.5, 4.0, 5.5}) {
    const Eigen::Vector2d target = x0 + 0.3 * Eigen::Vector2d(std::cos(b), std::sin(b));
    const JoinSummary j = Join(JoinProblem{model, {1.1, -0.3, 2.0}, mu, x0, target});
    ASSERT_EQ(j.status, JoinStatus::kConverged) << j.BriefReport();
    EXPECT_NEAR(j.t, 0.3 / std::sqrt(mu), 1e-12);
    // omega after the impulse points along e3 x (target - x0).
    const Eigen::Vector3d w = j.impulse.state_after.omega;
    const Eigen::Vector2d xdot(w.y(), -w.x());
    EXPECT_LT((xdot.normalized() - (target - x0).normalized()).norm(), 1e-12);
  }
}

TEST(Join, WorksForSeveralLambdaThroughThePolesAndForNegativeTheta) {
  const Eigen::Vector2d x0(0.5, 0.25);
  for (double lambda : {0.4, 1.5, 2.0, 5.0}) {
    const BallModel model = BallModel::FromLambda(lambda);
    for (const AngleState& start : {AngleState{0.0, 0.0, 0.3},
                                    AngleState{M_PI, 0.2, -1.0},
                                    AngleState{M_PI / 2, 1.0, 2.0},
                                    AngleState{-M_PI / 3, M_PI / 2, 0.0}}) {
      for (double b : {0.3, 2.0, 4.1}) {
        const Eigen::Vector2d target = x0 + 0.1 * Eigen::Vector2d(std::cos(b), std::sin(b));
        const JoinSummary j = Join(JoinProblem{model, start, 0.7, x0, target});
        ASSERT_EQ(j.status, JoinStatus::kConverged) << "lambda " << lambda << ": " << j.BriefReport();
        const MotionSample end = Arrive(model, start, 0.7, x0, j.delta_psi, j.t);
        EXPECT_LT((end.x - target).norm(), kReachTolerance);
        EXPECT_LE(j.t, j.time_limit);
      }
    }
  }
}

TEST(Join, TimeIsTheLocalBranchDistanceOverEllipseSpeed) {
  // Lemma 2.1 / (27): t = d / |x'_s(0)| + O(d^2); the local branch, never a later pass.
  const BallModel model = BallModel::FromLambda(2.0);
  const AngleState start{M_PI / 3, 0.4, 0.1};
  for (double d : {1e-2, 1e-3}) {
    const JoinSummary j = Join(JoinProblem{model, start, 1.0, {0, 0}, {d, 0.0}});
    ASSERT_TRUE(j.IsSolutionUsable());
    const Eigen::Vector3d w = j.impulse.state_after.omega;  // omega just after the impulse
    EXPECT_NEAR(j.t * w.head<2>().norm() / d, 1.0, 10 * d);
  }
}

TEST(Join, ImpulsePreservesEnergyAndArrivalStateHasTheSameEnergy) {
  const BallModel model = BallModel::FromLambda(2.0);
  const JoinSummary j = Join(JoinProblem{model, AngleState{M_PI / 3, 0.4, 0.1}, 1.3, {0, 0}, {0.02, 0.07}});
  ASSERT_TRUE(j.IsSolutionUsable());
  EXPECT_NEAR(j.impulse.mu_after, 1.3, 1e-14);
  EXPECT_NEAR(Energy(j.impulse.state_after, model), 1.3, 1e-12);
  EXPECT_NEAR(Energy(j.state_after, model), 1.3, 1e-10);  // eq. (9) is conserved by the flow
  EXPECT_NEAR(j.impulse.after.psi - j.impulse.before.psi, j.delta_psi, 1e-15);
  EXPECT_LT((j.x_after - j.target).norm(), 1e-12);
}

TEST(Join, TargetEqualToStartIsAStatus) {
  const BallModel model = BallModel::FromLambda(2.0);
  const JoinSummary j = Join(JoinProblem{model, AngleState{M_PI / 3, 0.4, 0.1}, 1.0, {1, 2}, {1, 2}});
  EXPECT_EQ(j.status, JoinStatus::kTargetEqualsStart);
  EXPECT_FALSE(j.IsSolutionUsable());
  EXPECT_EQ(j.t, 0.0);
  EXPECT_NE(j.BriefReport().find("target_equals_start"), std::string::npos);
}

TEST(Join, DistantTargetIsReportedBeyondLocalRadiusNotAWrongBranch) {
  const BallModel model = BallModel::FromLambda(2.0);
  const AngleState start{M_PI / 3, 0.4, 0.1};
  for (const Eigen::Vector2d& target : {Eigen::Vector2d(40.0, 3.0), Eigen::Vector2d(-7.0, 12.0)}) {
    const JoinSummary j = Join(JoinProblem{model, start, 1.0, {0, 0}, target});
    if (j.status == JoinStatus::kConverged) {
      // Only acceptable if it truly is a short arc with t within the local bound.
      EXPECT_LE(j.t, j.time_limit);
      const MotionSample end = Arrive(model, start, 1.0, {0, 0}, j.delta_psi, j.t);
      EXPECT_LT((end.x - target).norm(), kReachTolerance);
    } else {
      EXPECT_EQ(j.status, JoinStatus::kTargetBeyondLocalRadius) << j.BriefReport();
      EXPECT_FALSE(j.message.empty());
    }
  }
}

TEST(Join, InvalidInputNamesTheField) {
  const BallModel model = BallModel::FromLambda(2.0);
  const AngleState start{M_PI / 3, 0.4, 0.1};
  try {
    Join(JoinProblem{model, start, 1.0, {0, 0}, {NAN, 0}});
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("target"), std::string::npos) << e.what();
  }
  try {
    Join(JoinProblem{model, start, -1.0, {0, 0}, {0.1, 0}});
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("mu"), std::string::npos) << e.what();
  }
  JoinOptions bad;
  bad.residual_tolerance = 0.0;
  try {
    Join(JoinProblem{model, start, 1.0, {0, 0}, {0.1, 0}}, bad);
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("residual_tolerance"), std::string::npos) << e.what();
  }
  EXPECT_THROW(Join(JoinProblem{model, AngleState{INFINITY, 0, 0}, 1.0, {0, 0}, {0.1, 0}}), std::invalid_argument);
}

TEST(Join, HugePsiIsReducedOnceAndJoins) {
  // Psi = 1e6 said target_beyond_local_radius for a target 0.05 away. lambda = 1 rolls
  // straight at speed sqrt(mu) (eq. (9)): t = 0.05 / sqrt(mu) exactly, whatever psi is.
  const BallModel model = BallModel::FromLambda(1.0);
  for (double psi : {0.1, 1e6, -2.5e12}) {
    const JoinSummary j = Join(JoinProblem{model, AngleState{1.0, 0.4, psi}, 1.0, {0, 0}, {0.05, 0}});
    ASSERT_EQ(j.status, JoinStatus::kConverged) << "psi = " << psi << ": " << j.BriefReport();
    EXPECT_NEAR(j.t, 0.05, 1e-12) << psi;
    EXPECT_LE(std::abs(j.start.psi), M_PI) << "the summary holds the reduced angle";
    const MotionSample end = Arrive(model, j.start, 1.0, {0, 0}, j.delta_psi, j.t);
    EXPECT_LT((end.x - Eigen::Vector2d(0.05, 0)).norm(), kReachTolerance) << psi;
  }
  try {
    Join(JoinProblem{model, AngleState{1.0, 0.4, 1e16}, 1.0, {0, 0}, {0.05, 0}});
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("start.psi"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("1e+16"), std::string::npos) << e.what();
  }
}

TEST(Join, ResidualToleranceOutsideItsRangeIsRejected) {
  // 0.999 reported target_equals_start, 1e-300 target_beyond_local_radius.
  const BallModel model = BallModel::FromLambda(2.0);
  const AngleState start{M_PI / 3, 0.4, 0.1};
  for (double tol : {0.999, 1e-300, 2e-3, 9e-16, 0.0, -1.0, double(NAN), double(INFINITY)}) {
    JoinOptions o;
    o.residual_tolerance = tol;
    try {
      Join(JoinProblem{model, start, 1.0, {0, 0}, {0.05, 0}}, o);
      FAIL() << "expected std::invalid_argument for " << tol;
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("residual_tolerance"), std::string::npos) << what;
      EXPECT_NE(what.find("[1e-15, 1e-3]"), std::string::npos) << what;
    }
  }
  for (double tol : {1e-15, 1e-3}) {
    JoinOptions o;
    o.residual_tolerance = tol;
    const JoinSummary j = Join(JoinProblem{model, start, 1.0, {0, 0}, {0.05, 0}}, o);
    EXPECT_EQ(j.status, JoinStatus::kConverged) << tol << ": " << j.BriefReport();
    EXPECT_LE(j.residual, tol);
  }
}

TEST(Join, ChartFreeStateEntersThroughItsAngles) {
  const BallModel model = BallModel::FromLambda(2.0);
  const AngleState start{M_PI / 3, 0.4, 0.1};
  const BallState s = StateFromAngles(start, 1.0, model);
  const JoinSummary a = Join(JoinProblem{model, start, 1.0, {0, 0}, {0.03, -0.04}});
  const JoinSummary b = Join(JoinProblem{model, AnglesFromState(s, model), Energy(s, model), {0, 0}, {0.03, -0.04}});
  ASSERT_TRUE(a.IsSolutionUsable());
  ASSERT_TRUE(b.IsSolutionUsable());
  EXPECT_NEAR(a.t, b.t, 1e-12);
  EXPECT_LT((a.impulse.state_after.omega - b.impulse.state_after.omega).norm(), 1e-12);
}

TEST(Join, StepBoundExceededIsAnIntegrationFailureStatus) {
  JoinOptions o;
  o.integration.max_steps = 2;
  const JoinSummary j = Join(JoinProblem{BallModel::FromLambda(2.0), {M_PI / 3, 0.4, 0.1}, 1.0, {0, 0}, {0.3, 0.2}}, o);
  EXPECT_EQ(j.status, JoinStatus::kIntegrationFailure) << j.BriefReport();
  EXPECT_NE(j.message.find("max_steps"), std::string::npos) << j.message;
}
