// Identification across energy-preserving impulses at known times (identify.h, impulse_times):
// tracks of a plan of the library's own planner (PlanImpulses on problems/circle.json), each
// flight sampled from FreeMotion started at the planner's state after its impulse. FreeMotion and
// the planner are independent of the fit's model (the flights chained through ImpulseMomentum,
// differentiated by Jets).
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

#include "exact_chain.h"
#include "identify_model.h"
#include "kinematics.h"
#include "plateball/free_motion.h"
#include "plateball/identify.h"
#include "plateball/impulse.h"
#include "plateball/impulse_planner.h"
#include "plateball/problem_io.h"
#include "plateball/task_adapters.h"
#include "support/test_support.h"

namespace plateball {
namespace {

/// The circle of problems/circle.json with 8 impulses (lambda = 2, mu = 1): 8 flights of about a
/// quarter period each.
const PlanSummary& CirclePlan(int n = 8) {
  static std::map<int, PlanSummary> plans;
  PlanSummary& plan = plans[n];
  if (plan.steps.empty()) {
    const Problem problem = ReadProblemFile(plateball::testing::SourcePath("problems/circle.json"));
    const PlanSetup setup = PlanSetupFor(problem, n);
    plan = PlanImpulses(setup.problem, setup.options);
  }
  return plan;
}

struct ImpulsiveTrack {
  IdentifyProblem problem;
  double lambda = 2.0, mu = 1.0;
  AngleState start;                // after the plan's first impulse, at t = 0
  std::vector<double> delta_psi;   // of the impulses 1 .. n-1 (the track's impulses)
  std::vector<std::size_t> first;  // first sample of each flight, and the sample count at the end
};

/// `per_flight` samples per flight (the last at the impulse belongs to the flight before it),
/// Gaussian noise sigma on each coordinate, sigma given when `give_sigma`.
ImpulsiveTrack MakeTrack(int per_flight, double sigma, unsigned seed, bool give_sigma = true, int n = 8) {
  const PlanSummary& plan = CirclePlan(n);
  ImpulsiveTrack track;
  track.start = plan.steps.front().impulse.after;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  for (std::size_t k = 0; k < plan.steps.size(); ++k) {
    const PlanStep& step = plan.steps[k];
    if (k > 0) {
      track.problem.impulse_times.push_back(step.t_impulse);
      track.delta_psi.push_back(step.delta_psi);
    }
    track.first.push_back(track.problem.t.size());
    const FreeMotion flight = FreeMotion::FromAngles(BallModel::FromLambda(2.0), step.impulse.after, step.mu, x);
    for (int i = k == 0 ? 0 : 1; i <= per_flight; ++i) {
      const double tau = step.duration * i / per_flight;
      track.problem.t.push_back(step.t_impulse + tau);
      track.problem.x.push_back(flight.PositionAt(tau) + sigma * Eigen::Vector2d(noise(rng), noise(rng)));
      if (give_sigma) track.problem.sigma.push_back(sigma);
    }
    x = flight.PositionAt(step.duration);
  }
  track.first.push_back(track.problem.t.size());
  return track;
}

// The planner's flights are integrated at 1e-12 and the fit at 1e-11: a noiseless track gives
// lambda and every delta psi to ~1e-9; 1e-7 leaves two digits of margin.
constexpr double kNoiselessTolerance = 1e-7;

IdentifyOptions FastOptions() {
  IdentifyOptions o;
  o.profile_interval = false;
  return o;
}

TEST(IdentifyImpulses, ModelJacobianMatchesCentralDifferences) {
  // Two impulses; samples in every flight, one exactly at the first impulse.
  const std::vector<double> q{1.3, 4.0, 0.8, 0.3, 0.2, 0.5, -0.2, 0.7, -1.1};
  const std::vector<double> tau{0.0, 0.4, 1.0, 1.7, 2.6, 3.9};
  const std::vector<double> impulses{1.0, 2.2};
  const IntegrationOptions tight{1e-13, 1e-13, 2'000'000};
  const std::size_t n = tau.size(), p = q.size();
  std::vector<double> x(2 * n), jac(2 * n * p), xp(2 * n), xm(2 * n);
  internal::EvaluateImpulsiveTrack(q.data(), tau.data(), n, impulses, tight, x.data(), jac.data(), &tight);
  for (std::size_t j = 0; j < p; ++j) {
    const double h = 1e-5;
    std::vector<double> qp = q, qm = q;
    qp[j] += h;
    qm[j] -= h;
    internal::EvaluateImpulsiveTrack(qp.data(), tau.data(), n, impulses, tight, xp.data(), nullptr);
    internal::EvaluateImpulsiveTrack(qm.data(), tau.data(), n, impulses, tight, xm.data(), nullptr);
    for (std::size_t k = 0; k < 2 * n; ++k)  // central difference: h^2 ~ 1e-10 truncation, 1e-13/h rounding
      EXPECT_NEAR(jac[k * p + j], (xp[k] - xm[k]) / (2 * h), 1e-7) << "residual " << k << " parameter " << j;
  }
  // The values against FreeMotion flight by flight, each impulse applied by
  // EnergyPreservingImpulse (impulse.h) to the angles FreeMotion reaches.
  const BallModel model = BallModel::FromLambda(q[0]);
  AngleState angles{q[2], q[3], q[4]};
  Eigen::Vector2d x0(q[5], q[6]);
  double t0 = 0.0;
  std::size_t i = 0;
  for (std::size_t f = 0; f <= impulses.size(); ++f) {
    const FreeMotion flight = FreeMotion::FromAngles(model, angles, q[1], x0);
    for (; i < n && (f == impulses.size() || tau[i] <= impulses[f]); ++i)
      EXPECT_NEAR((flight.PositionAt(tau[i] - t0) - Eigen::Vector2d(x[2 * i], x[2 * i + 1])).norm(), 0.0, 1e-10) << i;
    if (f == impulses.size()) break;
    const MotionSample end = flight.At(impulses[f] - t0);
    angles = EnergyPreservingImpulse(end.angles, q[1], q[7 + f], model).after;
    x0 = end.x;
    t0 = impulses[f];
  }
}

TEST(IdentifyImpulses, NoiselessPlanTrackRecoversLambdaAndEveryDeltaPsi) {
  const ImpulsiveTrack track = MakeTrack(40, 0.0, 1, false);
  ASSERT_EQ(track.problem.impulse_times.size(), 7u);
  const IdentifySummary s = Identify(track.problem, FastOptions());
  ASSERT_EQ(s.status, IdentifyStatus::kIdentified) << s.BriefReport();
  EXPECT_NEAR(s.lambda, track.lambda, kNoiselessTolerance);
  EXPECT_NEAR(s.mu, track.mu, kNoiselessTolerance);
  EXPECT_NEAR(s.x0.norm(), 0.0, kNoiselessTolerance);
  ASSERT_EQ(s.delta_psi.size(), track.delta_psi.size());
  for (std::size_t k = 0; k < s.delta_psi.size(); ++k)
    EXPECT_NEAR(internal::WrapPi(s.delta_psi[k] - track.delta_psi[k]), 0.0, kNoiselessTolerance) << k;
  ASSERT_EQ(s.standard_errors.size(), 7u + track.delta_psi.size());
  ASSERT_EQ(s.correlation.rows(), 14);
  // The flights' fitted starts: the plan's states after each impulse.
  ASSERT_EQ(s.flights.size(), CirclePlan().steps.size());
  for (std::size_t k = 0; k < s.flights.size(); ++k) {
    const PlanStep& step = CirclePlan().steps[k];
    EXPECT_NEAR(s.flights[k].t_start, step.t_impulse, 1e-12);
    EXPECT_NEAR((s.flights[k].x - step.p_begin).norm(), 0.0, 1e-7) << k;
    EXPECT_NEAR(StateFromAngles(s.flights[k].angles, s.mu, BallModel::FromLambda(2.0)).omega.norm(),
                StateFromAngles(step.impulse.after, step.mu, BallModel::FromLambda(2.0)).omega.norm(),
                1e-7);
    EXPECT_NEAR((StateFromAngles(s.flights[k].angles, s.mu, BallModel::FromLambda(2.0)).z -
                 StateFromAngles(step.impulse.after, step.mu, BallModel::FromLambda(2.0)).z)
                    .norm(),
                0.0,
                1e-7)
        << k;
  }
  EXPECT_FALSE(s.straight_path);
  double worst = std::abs(s.lambda - track.lambda);
  for (std::size_t k = 0; k < s.delta_psi.size(); ++k)
    worst = std::max(worst, std::abs(internal::WrapPi(s.delta_psi[k] - track.delta_psi[k])));
  std::printf("noiseless: largest error of lambda and delta psi %.2e, rms residual %.2e, %d starts\n",
              worst,
              s.rms_residual,
              s.starts);
}

// Noise 1e-3 radii, given: lambda and each delta psi within 4 standard errors of the truth
// (probability of a miss ~6e-5 each for a right error), over three seeds.
constexpr double kNoisySigma = 1e-3;
constexpr double kStandardErrors = 4.0;

TEST(IdentifyImpulses, NoisyPlanTrackRecoversLambdaAndDeltaPsiWithinTheirStandardErrors) {
  for (unsigned seed : {11u, 12u, 13u}) {
    const ImpulsiveTrack track = MakeTrack(25, kNoisySigma, seed);
    const IdentifySummary s = Identify(track.problem, FastOptions());
    ASSERT_EQ(s.status, IdentifyStatus::kIdentified) << s.BriefReport();
    EXPECT_LT(std::abs(s.lambda - track.lambda), kStandardErrors * s.standard_errors[0]) << seed;
    EXPECT_LT(std::abs(s.mu - track.mu), kStandardErrors * s.standard_errors[1]) << seed;
    for (std::size_t k = 0; k < s.delta_psi.size(); ++k)
      EXPECT_LT(std::abs(internal::WrapPi(s.delta_psi[k] - track.delta_psi[k])),
                kStandardErrors * s.standard_errors[7 + k])
          << seed << " impulse " << k;
    // Reduced chi-square near 1: the model fits to the noise.
    EXPECT_NEAR(s.chi_square / (s.residuals - 15), 1.0, 0.3) << seed;
  }
}

// The joint fit's Fisher information for lambda is at least the sum of the flights' separate
// ones (the separate fits have 7 free parameters per flight where the joint fit has one delta psi
// each), so its standard error is at most the flights' combined 1/sqrt(sum 1/se_k^2), and below
// every single flight's.
TEST(IdentifyImpulses, JointFitGivesATighterLambdaThanTheFlightsSeparately) {
  const ImpulsiveTrack track = MakeTrack(25, kNoisySigma, 21);
  const IdentifySummary joint = Identify(track.problem, FastOptions());
  ASSERT_EQ(joint.status, IdentifyStatus::kIdentified) << joint.BriefReport();
  double information = 0.0, best_single = std::numeric_limits<double>::infinity();
  for (std::size_t f = 0; f + 1 < track.first.size(); ++f) {
    IdentifyProblem flight;
    // The flight's own samples, from the impulse's sample (the end of the flight before) on.
    for (std::size_t i = f == 0 ? 0 : track.first[f] - 1; i < track.first[f + 1]; ++i) {
      flight.t.push_back(track.problem.t[i]);
      flight.x.push_back(track.problem.x[i]);
      flight.sigma.push_back(track.problem.sigma[i]);
    }
    IdentifyOptions o = FastOptions();
    const PlanStep& step = CirclePlan().steps[f];
    // The separate fits start at the truth: this compares information, not the search.
    o.guess = IdentifyGuess{track.lambda, track.mu, step.impulse.after, step.p_begin, {}};
    const IdentifySummary s = Identify(flight, o);
    ASSERT_NE(s.status, IdentifyStatus::kFailed) << s.BriefReport();
    ASSERT_NE(s.status, IdentifyStatus::kNoFit) << s.BriefReport();
    if (std::isfinite(s.standard_errors[0])) information += 1.0 / (s.standard_errors[0] * s.standard_errors[0]);
    best_single = std::min(best_single, s.standard_errors[0]);
  }
  const double combined = 1.0 / std::sqrt(information);
  EXPECT_LT(joint.standard_errors[0], combined);
  EXPECT_LT(joint.standard_errors[0], best_single);
  std::printf("lambda standard error: joint %.3g, flights combined %.3g, best single flight %.3g\n",
              joint.standard_errors[0],
              combined,
              best_single);
}

// Coverage of the 95% profile interval of lambda across impulses: the count of covering seeds is
// Binomial(200, 0.95) when the interval is right; [179, 198] holds it with probability 0.999.
// Short tracks (10 samples per flight, noise 3e-3, sigma given) fitted from the truth (the search
// is tested above) so that the 200 fits stay cheap.
constexpr int kCoverageSeeds = 200;
constexpr int kCoverageLow = 179, kCoverageHigh = 198;

TEST(IdentifyImpulses, ProfileIntervalCoversLambdaInAbout95PercentOfSeeds) {
  int covered = 0;
  for (int seed = 0; seed < kCoverageSeeds; ++seed) {
    const ImpulsiveTrack track = MakeTrack(10, 3e-3, 5000u + static_cast<unsigned>(seed));
    IdentifyOptions o;
    o.integration = {1e-9, 1e-9, 2'000'000};
    o.guess = IdentifyGuess{track.lambda, track.mu, track.start, Eigen::Vector2d::Zero(), track.delta_psi};
    const IdentifySummary s = Identify(track.problem, o);
    ASSERT_EQ(s.status, IdentifyStatus::kIdentified) << seed << ": " << s.BriefReport();
    covered += s.lambda_low < track.lambda && track.lambda < s.lambda_high;
  }
  std::printf("the 95%% profile interval covered lambda in %d of %d seeds\n", covered, kCoverageSeeds);
  EXPECT_GE(covered, kCoverageLow);
  EXPECT_LE(covered, kCoverageHigh);
}

// Plans of 16 and 32 impulses: flights of 1/8 and 1/16 period with 8 samples each, so the
// multi-start's first window spans several flights and each start chooses their delta psi.
TEST(IdentifyImpulses, ManyShortFlightsFromTheMultiStart) {
  for (int n : {16, 32}) {
    for (unsigned seed : {31u, 32u}) {
      const ImpulsiveTrack track = MakeTrack(8, kNoisySigma, seed, true, n);
      const IdentifySummary s = Identify(track.problem, FastOptions());
      ASSERT_EQ(s.status, IdentifyStatus::kIdentified) << s.BriefReport();
      EXPECT_LT(std::abs(s.lambda - track.lambda), kStandardErrors * s.standard_errors[0]) << n << " " << seed;
      std::printf(
          "n %d seed %u: lambda %.6f +- %.2g, rms %.3g\n", n, seed, s.lambda, s.standard_errors[0], s.rms_residual);
    }
  }
}

TEST(IdentifyImpulses, BadImpulseTimesAreRejectedNamingTheFieldAndValue) {
  ImpulsiveTrack track = MakeTrack(10, 0.0, 1, false);
  EXPECT_EQ(track.problem.Validate(), "");
  auto message = [&](std::vector<double> times) {
    IdentifyProblem p = track.problem;
    p.impulse_times = std::move(times);
    return p.Validate();
  };
  const double t1 = track.problem.impulse_times[0], t2 = track.problem.impulse_times[1];
  EXPECT_NE(message({t2, t1}).find("impulse_times[1]: value"), std::string::npos) << message({t2, t1});
  EXPECT_NE(message({t2, t1}).find("strictly increasing"), std::string::npos);
  EXPECT_NE(message({t1, t1}).find("impulse_times[1]"), std::string::npos);
  EXPECT_NE(message({-1.0}).find("impulse_times[0]: value -1: must be inside the track"), std::string::npos)
      << message({-1.0});
  EXPECT_NE(message({1e9}).find("impulse_times[0]: value 1e+09"), std::string::npos) << message({1e9});
  EXPECT_NE(message({std::nan("")}).find("impulse_times[0]"), std::string::npos);
  // Two impulses one sample apart: the flight between them has 1 sample.
  const double between = track.problem.t[track.first[1]];
  const std::string few = message({t1, between});
  EXPECT_NE(few.find("impulse_times[1]: value"), std::string::npos) << few;
  EXPECT_NE(few.find("too few samples in the flight before it: 1"), std::string::npos) << few;
  // A last flight of 2 samples names the last impulse.
  const double late = track.problem.t[track.problem.t.size() - 3];
  EXPECT_NE(message({late}).find("too few samples in the flight after it: 2"), std::string::npos) << message({late});
  // A guess with more delta psi than impulses.
  IdentifyOptions o = FastOptions();
  o.guess = IdentifyGuess{2.0, 1.0, track.start, {0, 0}, std::vector<double>(9, 0.0)};
  try {
    Identify(track.problem, o);
    ADD_FAILURE() << "accepted 9 delta psi for 7 impulses";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("guess.delta_psi (count): value 9"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace plateball
