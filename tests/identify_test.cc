// Identification of lambda, mu and the state (identify.h) from synthetic tracks of the library's
// own free motion: FreeMotion (one stored period, evaluated at any time) is independent of the
// fit's model (the variational equations on ceres::Jet read from the dense output).
#include "plateball/identify.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "identify_model.h"
#include "plateball/free_motion.h"

namespace plateball {
namespace {

struct Truth {
  double lambda = 1.3;
  double mu = 4.0;
  AngleState angles{0.8, 0.3, 0.2};  // w = phi - psi = 0.1: a large axial spin v0, a curved path
  Eigen::Vector2d x0{0.5, -0.2};
};

double PeriodOf(const Truth& t) { return 2.0 * M_PI / std::sqrt(t.mu); }

/// n samples of x(t) on [t0, t0 + span] of FreeMotion (state `truth` at t0), Gaussian noise sigma.
IdentifyProblem MakeTrack(const Truth& truth, double t0, double span, int n, double sigma, unsigned seed) {
  const FreeMotion motion =
      FreeMotion::FromAngles(BallModel::FromLambda(truth.lambda), truth.angles, truth.mu, truth.x0);
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  IdentifyProblem p;
  for (int i = 0; i < n; ++i) {
    const double t = t0 + span * i / (n - 1);
    p.t.push_back(t);
    p.x.push_back(motion.PositionAt(t - t0) + sigma * Eigen::Vector2d(noise(rng), noise(rng)));
  }
  return p;
}

// Noiseless tracks: the fit reaches the truth to the integration tolerance (1e-11 on the values);
// lambda's sensitivity over two periods is O(1), so 1e-8 leaves three digits of margin.
constexpr double kNoiselessLambdaTolerance = 1e-8;

TEST(Identify, NoiselessTracksRecoverLambdaAndMuFromTheMultiStart) {
  for (double lambda : {0.5, 1.3, 2.0}) {
    Truth truth;
    truth.lambda = lambda;
    const IdentifyProblem p = MakeTrack(truth, 0.7, 2.0 * PeriodOf(truth), 300, 0.0, 1);
    IdentifyOptions o;
    o.profile_interval = false;
    const IdentifySummary s = Identify(p, o);
    ASSERT_EQ(s.status, IdentifyStatus::kIdentified) << s.BriefReport();
    EXPECT_NEAR(s.lambda, lambda, kNoiselessLambdaTolerance) << lambda;
    EXPECT_NEAR(s.mu, truth.mu, kNoiselessLambdaTolerance * truth.mu) << lambda;
    EXPECT_NEAR((s.x0 - truth.x0).norm(), 0.0, 1e-9);
    EXPECT_DOUBLE_EQ(s.t_ref, 0.7);
    EXPECT_GT(s.starts, 1);
    // z -> -z gives the same contact track: theta is determined up to theta -> pi - theta.
    EXPECT_NEAR(
        std::min(std::abs(s.angles.theta - truth.angles.theta), std::abs(M_PI - s.angles.theta - truth.angles.theta)),
        0.0,
        1e-7);
  }
}

TEST(Identify, NoiselessTrackGetsTheWaldIntervalAroundTheTruth) {
  Truth truth;
  truth.lambda = 2.0;
  const IdentifyProblem p = MakeTrack(truth, 0.0, 2.0 * PeriodOf(truth), 200, 0.0, 1);
  const IdentifySummary s = Identify(p);
  ASSERT_EQ(s.status, IdentifyStatus::kIdentified) << s.BriefReport();
  EXPECT_EQ(s.interval_method, "wald");
  EXPECT_EQ(s.profile_fits, 0);
  EXPECT_LT(s.lambda_low, s.lambda);
  EXPECT_GT(s.lambda_high, s.lambda);
  EXPECT_LT(s.lambda_high - s.lambda_low, kNoiselessLambdaTolerance);
  EXPECT_NEAR(s.lambda, truth.lambda, kNoiselessLambdaTolerance);
}

TEST(Identify, ModelJacobianMatchesCentralDifferences) {
  const double q[7] = {1.3, 4.0, 0.8, 0.3, 0.2, 0.5, -0.2};
  const std::vector<double> tau{0.0, 0.4, 1.7, 3.9};
  const IntegrationOptions tight{1e-13, 1e-13, 2'000'000};
  std::vector<double> x(8), jac(8 * 7), xp(8), xm(8);
  internal::EvaluateTrack(q, tau.data(), tau.size(), tight, x.data(), jac.data(), &tight);
  for (int j = 0; j < 7; ++j) {
    const double h = 1e-5;
    double qp[7], qm[7];
    std::copy(q, q + 7, qp);
    std::copy(q, q + 7, qm);
    qp[j] += h;
    qm[j] -= h;
    internal::EvaluateTrack(qp, tau.data(), tau.size(), tight, xp.data(), nullptr);
    internal::EvaluateTrack(qm, tau.data(), tau.size(), tight, xm.data(), nullptr);
    for (int k = 0; k < 8; ++k)  // central difference: h^2 ~ 1e-10 truncation, 1e-13/h rounding
      EXPECT_NEAR(jac[static_cast<std::size_t>(k * 7 + j)],
                  (xp[static_cast<std::size_t>(k)] - xm[static_cast<std::size_t>(k)]) / (2 * h),
                  1e-7)
          << "residual " << k << " parameter " << kIdentifyParameterNames[j];
  }
  // The values agree with FreeMotion (an independent integration of one stored period).
  const FreeMotion motion = FreeMotion::FromAngles(BallModel::FromLambda(1.3), {0.8, 0.3, 0.2}, 4.0, {0.5, -0.2});
  for (std::size_t i = 0; i < tau.size(); ++i)
    EXPECT_NEAR((motion.PositionAt(tau[i]) - Eigen::Vector2d(x[2 * i], x[2 * i + 1])).norm(), 0.0, 1e-10);
}

// Coverage of the 95% profile interval over 200 seeds per lambda: the count of covering seeds is
// Binomial(200, 0.95) when the interval is right; [179, 198] holds it with probability 0.999
// (each tail < 0.0005). The fits start at the truth (the multi-start is tested above) on short
// tracks (40 samples, 1.5 periods) so that the 600 fits stay cheap.
constexpr int kCoverageSeeds = 200;
constexpr int kCoverageLow = 179, kCoverageHigh = 198;

TEST(Identify, ProfileIntervalCoversTheTruthInAbout95PercentOfSeeds) {
  for (double lambda : {0.5, 1.3, 2.0}) {
    Truth truth;
    truth.lambda = lambda;
    int covered = 0;
    for (int seed = 0; seed < kCoverageSeeds; ++seed) {
      const IdentifyProblem p =
          MakeTrack(truth, 0.0, 1.5 * PeriodOf(truth), 40, 0.003, 1000u + static_cast<unsigned>(seed));
      IdentifyOptions o;
      o.integration = {1e-9, 1e-9, 2'000'000};
      o.guess = IdentifyGuess{truth.lambda, truth.mu, truth.angles, truth.x0, {}};
      const IdentifySummary s = Identify(p, o);
      ASSERT_EQ(s.status, IdentifyStatus::kIdentified) << seed << ": " << s.BriefReport();
      EXPECT_LT(s.lambda_low, s.lambda);
      EXPECT_GT(s.lambda_high, s.lambda);
      EXPECT_EQ(s.interval_method, "profile");
      if (s.lambda_low <= lambda && lambda <= s.lambda_high) ++covered;
    }
    EXPECT_GE(covered, kCoverageLow) << "lambda " << lambda;
    EXPECT_LE(covered, kCoverageHigh) << "lambda " << lambda;
  }
}

TEST(Identify, NoisyTrackWithGivenSigmaFromTheMultiStart) {
  Truth truth;
  truth.lambda = 2.0;
  IdentifyProblem p = MakeTrack(truth, -3.0, 2.0 * PeriodOf(truth), 500, 0.01, 7);
  p.sigma.assign(p.t.size(), 0.01);
  const IdentifySummary s = Identify(p);
  ASSERT_EQ(s.status, IdentifyStatus::kIdentified) << s.BriefReport();
  EXPECT_FALSE(s.sigma_estimated);
  // 4 standard errors: a fixed seed, far outside would be a biased fit or wrong errors.
  EXPECT_NEAR(s.lambda, truth.lambda, 4 * s.standard_errors[0]);
  EXPECT_NEAR(s.mu, truth.mu, 4 * s.standard_errors[1]);
  EXPECT_LE(s.lambda_low, s.lambda);
  EXPECT_GE(s.lambda_high, s.lambda);
  EXPECT_NEAR(s.rms_residual, 0.01, 0.002);  // the given noise
  EXPECT_NEAR(s.correlation(0, 0), 1.0, 1e-12);
}

// The multi-start's grid points and the profile's two sides on two threads: the same fit, the same
// interval and the same counts to the last bit (each start is independent, and its result keeps its
// grid index whatever thread ran it).
TEST(Identify, ThreadsDoNotChangeTheResult) {
  Truth truth;
  IdentifyProblem p = MakeTrack(truth, 0.0, 2.0 * PeriodOf(truth), 300, 0.005, 3);
  IdentifyOptions one, two;
  two.threads = 2;
  const IdentifySummary a = Identify(p, one), b = Identify(p, two);
  ASSERT_EQ(a.status, IdentifyStatus::kIdentified) << a.BriefReport();
  EXPECT_EQ(b.status, a.status);
  EXPECT_EQ(b.lambda, a.lambda);
  EXPECT_EQ(b.mu, a.mu);
  EXPECT_EQ(b.lambda_low, a.lambda_low);
  EXPECT_EQ(b.lambda_high, a.lambda_high);
  EXPECT_EQ(b.standard_errors, a.standard_errors);
  EXPECT_EQ(b.starts, a.starts);
  EXPECT_EQ(b.iterations, a.iterations);
  EXPECT_EQ(b.profile_fits, a.profile_fits);
  IdentifyOptions bad;
  bad.threads = 0;
  EXPECT_EQ(bad.Validate(), "threads: value 0: must be in [1, 256]");
}

// A straight track: with w = phi - psi = pi/2 the axial spin v0 stays 0, K is perpendicular to
// z_h, the ball tumbles about a fixed horizontal axis and x moves on a line at speed sqrt(mu),
// the same for every lambda. The track shows the speed (the period), never lambda.
// The fitted path's end points carry the noise 0.003 over a chord of 2 sqrt(mu) periods ~ 12.6
// radii: 1e-3 relative on the speed is ~5 x that noise's share.
constexpr double kSpeedTolerance = 2e-3;

TEST(Identify, PeriodOnlyTrackIsReportedAsNotIdentifyingLambda) {
  Truth truth;
  truth.lambda = 1.7;
  truth.angles = {0.9, 0.4, 0.4 - M_PI / 2};
  const IdentifyProblem p = MakeTrack(truth, 0.0, 2.0 * PeriodOf(truth), 200, 0.003, 3);
  const IdentifySummary s = Identify(p);
  ASSERT_EQ(s.status, IdentifyStatus::kLambdaNotIdentified) << s.BriefReport();
  EXPECT_FALSE(s.IsSolutionUsable());
  EXPECT_FALSE(s.lambda_identified);
  EXPECT_NE(s.message.find("lambda not identified"), std::string::npos);
  EXPECT_TRUE(s.straight_path) << s.path_deviation;
  EXPECT_NE(s.message.find("not identifiable from the contact track alone"), std::string::npos) << s.message;
  EXPECT_NE(std::find(s.unidentified.begin(), s.unidentified.end(), "lambda"), s.unidentified.end());
  // What the track shows is the speed sqrt(mu) of the straight path: the fitted path's chord over
  // the span. mu itself is fitted within its standard error: near lambda = 1 every state rolls on
  // a straight line too, and there the speed no longer fixes mu.
  const double span = p.t.back() - p.t.front();
  EXPECT_NEAR((s.fitted.back() - s.fitted.front()).norm() / span, std::sqrt(truth.mu), kSpeedTolerance);
  EXPECT_NEAR(s.mu, truth.mu, 4 * s.standard_errors[1]);
}

// At lambda = 1 the conserved K is omega itself: every state rolls on a straight line, so a
// contact track alone cannot identify lambda = 1 (docs/identify.md).
TEST(Identify, LambdaOneContactTrackIsNotIdentified) {
  Truth truth;
  truth.lambda = 1.0;
  const IdentifyProblem p = MakeTrack(truth, 0.0, 2.0 * PeriodOf(truth), 200, 0.0, 1);
  IdentifyOptions o;
  o.profile_interval = false;
  const IdentifySummary s = Identify(p, o);
  EXPECT_EQ(s.status, IdentifyStatus::kLambdaNotIdentified) << s.BriefReport();
  EXPECT_LT(s.rms_residual, 1e-9);
  // The reason is reported, not only a large standard error: the path is straight.
  EXPECT_TRUE(s.straight_path) << s.path_deviation;
  EXPECT_NE(s.message.find("lambda = 1"), std::string::npos) << s.message;
  EXPECT_NE(std::find(s.unidentified.begin(), s.unidentified.end(), "lambda"), s.unidentified.end());
}

// The same state at lambda = 1.3 drifts on a curved path (v0 != 0): not straight, identified.
TEST(Identify, CurvedContactTrackIsNotFlaggedStraight) {
  const Truth truth;
  const IdentifyProblem p = MakeTrack(truth, 0.0, 2.0 * PeriodOf(truth), 200, 0.003, 1);
  IdentifyOptions o;
  o.profile_interval = false;
  const IdentifySummary s = Identify(p, o);
  ASSERT_EQ(s.status, IdentifyStatus::kIdentified) << s.BriefReport();
  EXPECT_FALSE(s.straight_path);
  EXPECT_GT(s.path_deviation, 10 * s.sigma);
}

TEST(Identify, TrackThatNoFreeMotionFitsIsNoFitWithItsResidual) {
  IdentifyProblem p;
  for (int i = 0; i < 60; ++i) {  // a zigzag: the contact point reverses every 10 samples
    p.t.push_back(0.1 * i);
    p.x.emplace_back((i / 10) % 2 == 0 ? 0.2 * (i % 10) : 2.0 - 0.2 * (i % 10), 0.0);
  }
  IdentifyProblem with_sigma = p;
  with_sigma.sigma.assign(p.t.size(), 1e-3);
  for (const IdentifyProblem* q : {&p, &with_sigma}) {
    const IdentifySummary s = Identify(*q);
    EXPECT_EQ(s.status, IdentifyStatus::kNoFit) << s.BriefReport();
    EXPECT_FALSE(s.IsSolutionUsable());
    EXPECT_GT(s.rms_residual, 0.01);
    EXPECT_NE(s.message.find("no free motion fits"), std::string::npos);
  }
}

TEST(Identify, DefaultSummaryIsNotRun) {
  const IdentifySummary s;
  EXPECT_EQ(s.status, IdentifyStatus::kNotRun);
  EXPECT_FALSE(s.IsSolutionUsable());
  EXPECT_EQ(ToString(s.status), "not_run");
}

struct BadCase {
  const char* what;
  void (*edit)(IdentifyProblem*);
  const char* field;
};

TEST(Identify, BadInputIsRejectedNamingTheFieldAndRow) {
  const BadCase cases[] = {
      {"unsorted", [](IdentifyProblem* p) { std::swap(p->t[3], p->t[4]); }, "t[4]: value"},
      {"duplicate", [](IdentifyProblem* p) { p->t[5] = p->t[4]; }, "t[5]: value"},
      {"nan time", [](IdentifyProblem* p) { p->t[2] = std::nan(""); }, "t[2]: value nan"},
      {"nan x", [](IdentifyProblem* p) { p->x[6].x() = std::nan(""); }, "x[6]: value nan"},
      {"inf y", [](IdentifyProblem* p) { p->x[1].y() = INFINITY; }, "y[1]: value inf"},
      {"too few",
       [](IdentifyProblem* p) {
         p->t.resize(7);
         p->x.resize(7);
       },
       "t (rows): value 7"},
      {"rows differ", [](IdentifyProblem* p) { p->x.pop_back(); }, "x (rows)"},
      {"sigma rows", [](IdentifyProblem* p) { p->sigma.assign(3, 0.1); }, "sigma (rows): value 3"},
      {"sigma zero",
       [](IdentifyProblem* p) {
         p->sigma.assign(p->t.size(), 0.1);
         p->sigma[9] = 0;
       },
       "sigma[9]: value 0"},
  };
  const IdentifyProblem good = MakeTrack(Truth{}, 0.0, 1.0, 20, 0.0, 1);
  EXPECT_EQ(good.Validate(), "");
  for (const BadCase& c : cases) {
    IdentifyProblem p = good;
    c.edit(&p);
    try {
      Identify(p);
      ADD_FAILURE() << c.what << ": no error";
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(c.field), std::string::npos) << c.what << ": " << e.what();
    }
  }
  IdentifyOptions o;
  o.radius = -1;
  EXPECT_NE(o.Validate().find("radius: value -1"), std::string::npos);
  o = {};
  o.lambda_starts = {5000};
  EXPECT_NE(o.Validate().find("lambda_starts[0]: value 5000"), std::string::npos);
  o = {};
  o.integration.relative_tolerance = 0;
  EXPECT_NE(o.Validate().find("integration."), std::string::npos);
  EXPECT_THROW(Identify(good, o), std::invalid_argument);
}

TEST(Identify, RadiusScalesTheTrackToModelUnits) {
  Truth truth;
  IdentifyProblem p = MakeTrack(truth, 0.0, 2.0 * PeriodOf(truth), 200, 0.0, 1);
  for (auto& x : p.x) x *= 0.02;  // metres, r = 2 cm
  IdentifyOptions o;
  o.radius = 0.02;
  o.profile_interval = false;
  const IdentifySummary s = Identify(p, o);
  ASSERT_EQ(s.status, IdentifyStatus::kIdentified) << s.BriefReport();
  EXPECT_NEAR(s.lambda, truth.lambda, kNoiselessLambdaTolerance);
  EXPECT_NEAR((s.x0 - truth.x0).norm(), 0.0, 1e-9);
}

}  // namespace
}  // namespace plateball
