#include "plateball/exact_arrival.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "plateball/isoparallel.h"
#include "plateball/isoparallel_plan.h"
#include "plateball/problem_io.h"
#include "plateball/so3.h"
#include "plateball/task_adapters.h"
#include "support/figure7_exact.h"
#include "support/test_support.h"

namespace plateball {
namespace {

// The tolerances, checked by an independent re-integration (FreeMotion over a stored
// period per arc, not the solver's direct arc integration).
constexpr double kPositionTol = 1e-12;
constexpr double kOrientationTol = 1e-10;

// Figure 7 (problems/figure7.json) along its shortest isoparallel path (tests/support).
const ExactArrivalProblem& Figure7() { return plateball::testing::Figure7ExactArrival(); }

void ExpectArrivesByReplay(const ExactArrivalProblem& p, const ExactArrivalSummary& s) {
  ASSERT_TRUE(s.IsSolutionUsable()) << s.BriefReport();
  ASSERT_EQ(static_cast<int>(s.impulses.size()), p.impulses);
  const ReplayResult replay = ReplayExactArrival(p, s.impulses);
  EXPECT_LE(replay.position_error, kPositionTol) << s.BriefReport();
  EXPECT_LE(replay.orientation_error, kOrientationTol) << s.BriefReport();
  // The total against the sum of the rounded durations: a few roundings of the total (relative, as
  // the total reaches 1e5 at mu = 1e-8, where one ulp is 1.5e-11).
  constexpr double kSumTol = 1e-13;
  EXPECT_NEAR(
      s.total_time,
      [&] {
        double t = 0;
        for (const ExactImpulse& e : s.impulses) t += e.duration;
        return t;
      }(),
      kSumTol * std::max(1.0, s.total_time));
  for (const ExactImpulse& e : s.impulses) EXPECT_GT(e.duration, 0.0);
}

TEST(ExactArrival, Figure7With12ImpulsesArrivesByIndependentReintegration) {
  const ExactArrivalProblem& p = Figure7();
  ASSERT_EQ(p.impulses, 12);
  const ExactArrivalSummary s = SolveExactArrival(p);
  ExpectArrivesByReplay(p, s);
  // The paper's plan was off (||A_goal - A~_12|| = 0.298), the exact one is not.
  EXPECT_GT(s.planned_orientation_error, 0.1);
  EXPECT_GT(s.deviation, 0.0);
  EXPECT_LT(s.max_pass_displacement, 0.5);
  // The first impulse is at the start, the reported positions are the replayed pass points.
  EXPECT_EQ(s.impulses.front().position, p.x0);
  EXPECT_EQ(s.impulses.front().t_impulse, 0.0);
}

// A goal made by applying a known impulse sequence (the paper's plan along a curve, perturbed)
// is reached again with the same number of impulses.
TEST(ExactArrival, GoalOfAKnownImpulseSequenceIsRecoveredWithTheSameCount) {
  ExactArrivalProblem p;
  p.model = BallModel::FromLambda(1.7);
  p.initial = {0.9, 0.3, -0.2};
  p.mu = 1.3;
  p.A0 = ExpSO3({0.2, -0.1, 0.4});
  p.x0 = {0.5, -0.25};
  p.reference = Path({SmoothCurve::Line(p.x0, Eigen::Vector2d(2.0, 0.5))});
  p.impulses = 4;
  // The known sequence: 4 impulses with chosen delta psi and flight times.
  std::vector<ExactImpulse> known(4);
  const double dpsi[4] = {0.4, -0.3, 0.25, -0.1};
  const double dur[4] = {0.35, 0.4, 0.3, 0.45};
  for (int k = 0; k < 4; ++k) {
    known[static_cast<std::size_t>(k)].delta_psi = dpsi[k];
    known[static_cast<std::size_t>(k)].duration = dur[k];
  }
  const ReplayResult goal = ReplayExactArrival(p, known);
  p.x1 = goal.x;
  p.A1 = goal.A;
  p.reference = Path({SmoothCurve::Line(p.x0, p.x1)});
  const ExactArrivalSummary s = SolveExactArrival(p);
  ExpectArrivesByReplay(p, s);
}

// Exact arrival costs less deviation from the reference when the paper's approximation was
// already good: D falls as n grows.
TEST(ExactArrival, DeviationFromTheReferenceFallsAsTheImpulseCountGrows) {
  ExactArrivalProblem p = Figure7();
  double previous = INFINITY;
  for (int n : {12, 24, 48}) {
    p.impulses = n;
    const ExactArrivalSummary s = SolveExactArrival(p);
    ExpectArrivesByReplay(p, s);
    EXPECT_LT(s.max_pass_displacement, previous) << "n = " << n;
    previous = s.max_pass_displacement;
  }
}

TEST(ExactArrival, BadInputNamesTheField) {
  using plateball::testing::InvalidArgumentMessage;
  ExactArrivalProblem p;
  p.impulses = 2;
  EXPECT_NE(InvalidArgumentMessage([&] { SolveExactArrival(p); }).find("impulses"), std::string::npos);
  p.impulses = 4;
  p.A1 = 2.0 * Eigen::Matrix3d::Identity();
  EXPECT_NE(InvalidArgumentMessage([&] { SolveExactArrival(p); }).find("A1"), std::string::npos);
  p.A1.setIdentity();
  p.x0 = {0.0, 1.0};
  EXPECT_NE(InvalidArgumentMessage([&] { SolveExactArrival(p); }).find("x0"), std::string::npos);
  p.x0.setZero();
  p.mu = -1;
  EXPECT_NE(InvalidArgumentMessage([&] { SolveExactArrival(p); }).find("mu"), std::string::npos);
  p.mu = 1;
  ExactArrivalOptions o;
  o.max_iterations = 0;
  EXPECT_NE(o.Validate().find("max_iterations"), std::string::npos);
  EXPECT_NE(InvalidArgumentMessage([&] { SolveExactArrival(p, o); }).find("max_iterations"), std::string::npos);
}

// A goal too far for the iteration budget is a status with the closest arrival, not a throw.
TEST(ExactArrival, GoalNotReachedIsAStatusWithTheClosestArrival) {
  ExactArrivalProblem p;
  p.model = BallModel::FromLambda(2.0);
  p.impulses = 3;
  p.x1 = {1.0, 0.0};
  p.A1 = ExpSO3({0.0, 0.0, 2.5});  // a large turn about the vertical
  ExactArrivalOptions o;
  o.max_iterations = 1;
  const ExactArrivalSummary s = SolveExactArrival(p, o);
  EXPECT_EQ(s.status, ExactArrivalStatus::kNotReached) << s.BriefReport();
  EXPECT_FALSE(s.IsSolutionUsable());
  EXPECT_GT(s.orientation_error + s.position_error, o.orientation_tolerance);
  EXPECT_EQ(s.impulses.size(), 3u);
  EXPECT_FALSE(s.message.empty());
}

}  // namespace
}  // namespace plateball

namespace plateball {
namespace {

// The steer problems in problems/ (what `plateball steer` runs): the reference is the shortest
// isoparallel path, the certified answers the arrival errors of the independent re-integration.
void CheckSteerProblem(const std::string& file) {
  const Problem p = ReadProblemFile(plateball::testing::SourcePath("problems/" + file));
  ASSERT_TRUE(p.steer.has_value()) << file;
  ASSERT_TRUE(p.isoparallel.has_value()) << file;
  const IsoparallelSetup iso = IsoparallelSetupFor(p);
  const IsoparallelSummary solved = SolveIsoparallel(iso.problem, iso.options);
  ASSERT_TRUE(solved.IsSolutionUsable()) << file;
  const ExactArrivalSetup setup = ExactArrivalSetupFor(p, solved.Shortest());
  EXPECT_EQ(setup.problem.impulses, p.steer->impulses);
  const ExactArrivalSummary s = SolveExactArrival(setup.problem, setup.options);
  ExpectArrivesByReplay(setup.problem, s);
  const ReplayResult replay = ReplayExactArrival(setup.problem, s.impulses);
  int checked = 0;
  for (const auto& [name, e] : p.expected) {
    double value = NAN;
    if (name == "position_error")
      value = replay.position_error;
    else if (name == "orientation_error")
      value = replay.orientation_error;
    else if (name == "shortest_length")
      value = solved.Shortest().length;
    else
      ADD_FAILURE() << file << ": unknown expected value '" << name << "'";
    EXPECT_NEAR(value, e.value, e.tolerance) << file << ": " << name;
    ++checked;
  }
  EXPECT_EQ(checked, 3) << file;
}

TEST(ExactArrivalProblems, Figure7ExactMatchesItsCertifiedAnswers) { CheckSteerProblem("figure7_exact.json"); }
TEST(ExactArrivalProblems, RotationExactMatchesItsCertifiedAnswers) {
  CheckSteerProblem("isoparallel_rotation_exact.json");
}

// mu only rescales time by 1/sqrt(mu) (eq. (9)): figure7_exact at mu = 1e-8, 1 and 1e12 gives
// the same pass points and delta psi, times scaled by 1/sqrt(mu), and arrives at each mu by the
// independent re-integration at that mu.
TEST(ExactArrivalProblems, Figure7ExactIsTheSameForEveryMuWithTimeScaled) {
  const Problem p = ReadProblemFile(plateball::testing::SourcePath("problems/figure7_exact.json"));
  const IsoparallelSetup iso = IsoparallelSetupFor(p);
  const IsoparallelSummary solved = SolveIsoparallel(iso.problem, iso.options);
  ASSERT_TRUE(solved.IsSolutionUsable());
  const ExactArrivalSetup setup = ExactArrivalSetupFor(p, solved.Shortest());
  ASSERT_EQ(setup.problem.mu, 1.0);
  const ExactArrivalSummary unit = SolveExactArrival(setup.problem, setup.options);
  ASSERT_TRUE(unit.IsSolutionUsable()) << unit.BriefReport();
  EXPECT_FALSE(unit.iteration_limit_reached) << unit.BriefReport();
  // Pass points of one solve at another scale: only the rounding of the time scaling differs.
  constexpr double kPassPointTol = 1e-12;
  constexpr double kRelativeTimeTol = 1e-14;  // one multiplication by 1/sqrt(mu)
  for (double mu : {1e-8, 1e12}) {
    ExactArrivalProblem q = setup.problem;
    q.mu = mu;
    const ExactArrivalSummary s = SolveExactArrival(q, setup.options);
    ExpectArrivesByReplay(q, s);
    EXPECT_NEAR(s.deviation, unit.deviation, kPassPointTol) << mu;
    ASSERT_EQ(s.impulses.size(), unit.impulses.size());
    const double scale = 1.0 / std::sqrt(mu);
    for (std::size_t k = 0; k < s.impulses.size(); ++k) {
      EXPECT_LE((s.impulses[k].position - unit.impulses[k].position).norm(), kPassPointTol) << mu << " " << k;
      EXPECT_NEAR(s.impulses[k].delta_psi, unit.impulses[k].delta_psi, kPassPointTol) << mu << " " << k;
      EXPECT_NEAR(s.impulses[k].duration, unit.impulses[k].duration * scale, kRelativeTimeTol * s.impulses[k].duration);
      EXPECT_EQ(s.impulses[k].mu_before, mu);
    }
    EXPECT_NEAR(s.total_time, unit.total_time * scale, kRelativeTimeTol * s.total_time * 10);
  }
}

// An arrival whose minimisation of the deviation stopped at the iteration limit says so.
TEST(ExactArrivalProblems, ArrivalAtTheIterationLimitSaysSo) {
  const Problem p = ReadProblemFile(plateball::testing::SourcePath("problems/figure7_exact.json"));
  const IsoparallelSetup iso = IsoparallelSetupFor(p);
  const IsoparallelSummary solved = SolveIsoparallel(iso.problem, iso.options);
  ASSERT_TRUE(solved.IsSolutionUsable());
  ExactArrivalSetup setup = ExactArrivalSetupFor(p, solved.Shortest());
  const ExactArrivalSummary full = SolveExactArrival(setup.problem, setup.options);
  ASSERT_TRUE(full.IsSolutionUsable());
  ASSERT_GT(full.iterations, 4);
  setup.options.max_iterations = full.iterations - 1;  // one short of settling
  const ExactArrivalSummary cut = SolveExactArrival(setup.problem, setup.options);
  EXPECT_TRUE(cut.iteration_limit_reached) << cut.BriefReport();
  EXPECT_EQ(cut.iterations, setup.options.max_iterations);
  if (cut.IsSolutionUsable()) {
    EXPECT_NE(cut.message.find("iteration limit"), std::string::npos) << cut.BriefReport();
  }
}

TEST(ExactArrivalProblems, AdapterRejectsTooFewImpulsesNamingTheField) {
  const Problem p = ReadProblemFile(plateball::testing::SourcePath("problems/figure7_exact.json"));
  IsoparallelSolution fake;
  fake.length = 1.0;
  const std::string m =
      plateball::testing::InvalidArgumentMessage([&] { ExactArrivalSetupFor(p, fake, 2, "--impulses"); });
  EXPECT_NE(m.find("--impulses"), std::string::npos) << m;
  const std::string missing = plateball::testing::InvalidArgumentMessage([&] { ExactArrivalSetupFor(p); });
  EXPECT_NE(missing.find("figure7_exact.json"), std::string::npos) << missing;
}

}  // namespace
}  // namespace plateball

namespace plateball {
namespace {

// The plan section's path as the reference (what `plateball steer` runs for a file with a plan):
// a straight line of length 2 rolled to its end with a half turn more than rolling gives.
TEST(ExactArrivalProblems, PlanPathReferenceFromAFileArrives) {
  const Problem p = ParseProblem(R"({"ball": {"lambda": 2},
    "initial": {"theta": 1.0471975511965976, "phi": 0.4, "psi": 0.1, "mu": 1},
    "plan": {"path": {"type": "line", "from": [0, 0], "to": [2, 0]}},
    "steer": {"goal": [2, 0], "goal_orientation": {"axis_angle": {"axis": [0, 1, 0.5], "angle": 2.5}}, "impulses": 8}})",
                                 "line_steer.json");
  const ExactArrivalSetup setup = ExactArrivalSetupFor(p);
  EXPECT_EQ(setup.problem.impulses, 8);
  EXPECT_EQ(setup.problem.x1, Eigen::Vector2d(2, 0));
  const ExactArrivalSummary s = SolveExactArrival(setup.problem, setup.options);
  ExpectArrivesByReplay(setup.problem, s);
  // The command line's count replaces the file's, and a bad one names the option.
  EXPECT_EQ(ExactArrivalSetupFor(p, 5).problem.impulses, 5);
  EXPECT_NE(plateball::testing::InvalidArgumentMessage([&] {
              ExactArrivalSetupFor(p, 201, "--impulses");
            }).find("--impulses: value 201"),
            std::string::npos);
}

// Three impulses (6 unknowns) along the Figure 7 path: the warm start is 2.9 rad off and the
// iteration does not reach the goal; the status says so and the closest arrival is reported.
TEST(ExactArrival, Figure7WithThreeImpulsesReportsTheClosestArrival) {
  ExactArrivalProblem p = Figure7();
  p.impulses = 3;
  const ExactArrivalSummary s = SolveExactArrival(p);
  if (s.IsSolutionUsable()) {  // a better globalisation may reach it: then it must be exact
    ExpectArrivesByReplay(p, s);
    return;
  }
  EXPECT_EQ(s.status, ExactArrivalStatus::kNotReached) << s.BriefReport();
  ASSERT_EQ(s.impulses.size(), 3u);
  EXPECT_LT(s.orientation_error, s.planned_orientation_error);    // closer than the warm start
  const ReplayResult replay = ReplayExactArrival(p, s.impulses);  // the reported arrival is real
  EXPECT_NEAR(replay.position_error, s.position_error, 1e-9);
  EXPECT_NEAR(replay.orientation_error, s.orientation_error, 1e-9);
}

}  // namespace
}  // namespace plateball

#include "exact_chain.h"
#include "plateball/free_motion.h"
#include "plateball/impulse.h"

namespace plateball {
namespace {

// The smooth impulse map of exact_chain.h equals the library's impulse through the angle chart
// (AnglesFromState, EnergyPreservingImpulse, ConservedMomentum), also at a tilted axis.
TEST(ExactChain, ImpulseMapEqualsTheLibrarysImpulse) {
  for (double lambda : {0.5, 1.0, 2.0}) {
    const BallModel model = BallModel::FromLambda(lambda);
    for (const AngleState& a : {AngleState{0.9, 0.3, -0.2}, AngleState{2.1, -1.4, 0.7}, AngleState{1e-3, 0.2, 0.4}}) {
      const BallState before = StateFromAngles(a, 1.3, model);
      for (double s : {0.4, -2.5, 3.0}) {
        const Impulse imp = EnergyPreservingImpulse(a, 1.3, s, model);
        const Eigen::Vector2d k_lib = ConservedMomentum(imp.state_after, model);
        const Eigen::Vector2d k_before = ConservedMomentum(before, model);
        Eigen::Vector2d k;
        internal::ImpulseMomentum(before.z.data(), k_before.data(), s, lambda, k.data());
        EXPECT_LE((k - k_lib).norm(), 1e-13) << "lambda " << lambda << ", s " << s;
      }
    }
  }
}

// The exact Jacobian of the chain (variational equations on ceres::Jet) against central
// differences of the 1e-14 rollouts: agreement to the differences' own error (~h^2).
TEST(ExactChain, JacobianMatchesCentralDifferences) {
  const BallModel model = BallModel::FromLambda(1.7);
  internal::ChainNode start = internal::StartNode(model, {0.9, 0.3, -0.2}, 1.3, {0.5, -0.25}, ExpSO3({0.2, -0.1, 0.4}));
  Eigen::VectorXd u(8);
  u << 0.4, -1.3, 2.25, 0.1, 1.35, 0.9, 1.3, 0.7;
  const IntegrationOptions tight{1e-14, 1e-14, 2'000'000};
  const Eigen::Matrix3d A1 = ExpSO3({0.5, 1.0, -0.3});
  std::vector<internal::ChainNode> nodes(5, start);
  internal::ChainJacobian jac;
  internal::RollChain(model.lambda(), u, tight, &nodes, &jac);
  const Eigen::MatrixXd arrival = internal::ArrivalJacobian(jac, nodes.back(), A1);
  const double h = 1e-6;
  for (int j = 0; j < 8; ++j) {
    Eigen::VectorXd up = u, um = u;
    up[j] += h;
    um[j] -= h;
    std::vector<internal::ChainNode> np(5, start), nm(5, start);
    internal::RollChain(model.lambda(), up, tight, &np);
    internal::RollChain(model.lambda(), um, tight, &nm);
    const Eigen::Matrix<double, 5, 1> fd = (internal::ArrivalResidual(np.back(), Eigen::Vector2d(1, 1), A1) -
                                            internal::ArrivalResidual(nm.back(), Eigen::Vector2d(1, 1), A1)) /
                                           (2 * h);
    EXPECT_LE((fd - arrival.col(j)).norm(), 1e-7 * (1 + fd.norm())) << "column " << j;
    for (int k = 1; k <= 4; ++k) {
      const Eigen::Vector2d fdx = (np[static_cast<std::size_t>(k)].x - nm[static_cast<std::size_t>(k)].x) / (2 * h);
      EXPECT_LE((fdx - jac.dx[static_cast<std::size_t>(k)].col(j)).norm(), 1e-7 * (1 + fdx.norm()))
          << "node " << k << ", column " << j;
    }
  }
}

// From rest and to rest: the first impulse sets the ball rolling (0 -> mu), the stop impulse
// cancels omega at the goal; the arrival is the same as from a rolling start (same geometry).
TEST(ExactArrival, StartAtRestAndStopAtTheGoal) {
  ExactArrivalProblem p = Figure7();
  p.start_at_rest = true;
  p.stop_at_goal = true;
  const ExactArrivalSummary s = SolveExactArrival(p);
  ExpectArrivesByReplay(p, s);
  const ExactImpulse& first = s.impulses.front();
  EXPECT_EQ(first.kind, ExactImpulseKind::kStart);
  EXPECT_EQ(first.mu_before, 0.0);
  EXPECT_EQ(first.mu_after, p.mu);
  const Impulse imp = EnergyPreservingImpulse(first.angles_before, p.mu, first.delta_psi, p.model);
  EXPECT_LE((first.delta_omega - imp.state_after.omega).norm(), 1e-15);
  for (std::size_t k = 1; k < s.impulses.size(); ++k)
    EXPECT_EQ(s.impulses[k].kind, ExactImpulseKind::kEnergyPreserving);
  ASSERT_TRUE(s.stop.has_value());
  EXPECT_EQ(s.stop->kind, ExactImpulseKind::kStop);
  EXPECT_NEAR(s.stop->t_impulse, s.total_time, 1e-12);
  EXPECT_LE((s.stop->position - p.x1).norm(), 1e-12);
  // Independent: the last arc re-integrated by FreeMotion ends with omega = -delta omega of the stop.
  const ExactImpulse& last = s.impulses.back();
  const Impulse li = EnergyPreservingImpulse(last.angles_before, p.mu, last.delta_psi, p.model);
  const MotionSample end =
      FreeMotion(
          p.model,
          FreeMotionStart{
              li.state_after, last.position, AlignOrientationToAxis(Eigen::Matrix3d::Identity(), li.state_after.z)})
          .At(last.duration);
  EXPECT_LE((end.state.omega + s.stop->delta_omega).norm(), 1e-10);
  // The rolling start gives the same trajectory.
  ExactArrivalProblem rolling = Figure7();
  const ExactArrivalSummary r = SolveExactArrival(rolling);
  EXPECT_NEAR(r.deviation, s.deviation, 1e-12);
  EXPECT_FALSE(r.stop.has_value());
}

}  // namespace
}  // namespace plateball
