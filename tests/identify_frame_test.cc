// Identification with measured orientations (markers) and body angular velocities (an IMU inside
// the ball): identify.h, IdentifyProblem::orientation and body_rate. The tracks are the library's
// FreeMotion (its A(t) and A^T omega), independent of the fit's model (identify_model.cc
// integrates its own fundamental matrix and variational equations).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <random>

#include "identify_model.h"
#include "plateball/free_motion.h"
#include "plateball/identify.h"
#include "plateball/so3.h"

namespace plateball {
namespace {

constexpr double kMu = 4.0;
const AngleState kAngles{0.8, 0.3, 0.2};  // a curved, drifting path (v0 != 0)
constexpr double kChi = 0.6;              // the frame's turn about the axis at t = 0

/// What a synthetic track carries besides the positions.
struct TrackSpec {
  double lambda = 1.3;
  double periods = 2.0;  ///< the track's length in periods
  int n = 200;
  double sigma = 0.0;        ///< positions (radii); 0: noiseless, no sigma given
  double sigma_frame = 0.0;  ///< orientations (rad) or body rates (rad per time)
  bool orientation = false;
  bool body_rate = false;
  unsigned seed = 1;
};

/// The free motion of the spec's lambda from kAngles with the frame A0 = Rz(phi) Ry(theta) Rz(kChi).
FreeMotion TruthMotion(double lambda) {
  const Eigen::Matrix3d a0 = internal::StartFrame(kAngles.theta, kAngles.phi, kChi);
  return FreeMotion::FromAngles(BallModel::FromLambda(lambda), kAngles, kMu, {0.5, -0.2}, a0);
}

/// A measured orientation: A exp(hat(e)) with e ~ N(0, sigma^2 I), as a quaternion (w, x, y, z).
Eigen::Vector4d NoisyQuaternion(const Eigen::Matrix3d& a, double sigma, std::mt19937_64& rng) {
  std::normal_distribution<double> noise(0.0, 1.0);
  const Eigen::Vector3d e(noise(rng), noise(rng), noise(rng));
  const Eigen::Quaterniond q(Eigen::Matrix3d(a * ExpSO3(sigma * e)));
  return {q.w(), q.x(), q.y(), q.z()};
}

IdentifyProblem MakeTrack(const TrackSpec& spec) {
  const FreeMotion motion = TruthMotion(spec.lambda);
  std::mt19937_64 rng(spec.seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  IdentifyProblem p;
  for (int i = 0; i < spec.n; ++i) {
    const double t = spec.periods * motion.Period() * i / (spec.n - 1);
    const MotionSample m = motion.At(t);
    p.t.push_back(t);
    p.x.push_back(m.x + spec.sigma * Eigen::Vector2d(noise(rng), noise(rng)));
    if (spec.sigma > 0) p.sigma.push_back(spec.sigma);
    if (spec.orientation) {
      p.orientation.push_back(NoisyQuaternion(m.A, spec.sigma_frame, rng));
      if (spec.sigma > 0) p.sigma_orientation.push_back(spec.sigma_frame);
    }
    if (spec.body_rate) {
      p.body_rate.push_back(m.A.transpose() * m.state.omega +
                            spec.sigma_frame * Eigen::Vector3d(noise(rng), noise(rng), noise(rng)));
      p.sigma_body_rate.push_back(spec.sigma_frame);
    }
  }
  return p;
}

IdentifyOptions NoProfile() {
  IdentifyOptions o;
  o.profile_interval = false;
  return o;
}

// The model's A(t) and A^T omega against FreeMotion (its stored period and monodromy: a second
// integration), and their Jacobians against central differences, with and without an impulse
// (the frame is continuous across it).
TEST(IdentifyFrame, ModelFrameAndItsJacobianMatchFreeMotionAndCentralDifferences) {
  const std::vector<double> q0{1.3, kMu, kAngles.theta, kAngles.phi, kAngles.psi, 0.5, -0.2, kChi};
  const std::vector<double> tau{0.0, 0.4, 1.0, 1.7, 2.6};
  const IntegrationOptions tight{1e-13, 1e-13, 2'000'000};
  const std::size_t n = tau.size();
  for (const std::vector<double>& impulses : {std::vector<double>{}, std::vector<double>{1.2}}) {
    std::vector<double> q = q0;
    if (!impulses.empty()) q.push_back(0.7);
    const std::size_t p = q.size();
    std::vector<double> x(2 * n), jac(2 * n * p), a(9 * n), aj(3 * n * p), b(3 * n), bj(3 * n * p);
    internal::BodyOutput out;
    out.orientation = a.data();
    out.orientation_jacobian = aj.data();
    out.body_rate = b.data();
    out.body_rate_jacobian = bj.data();
    internal::EvaluateImpulsiveTrack(
        q.data(), tau.data(), n, impulses, tight, x.data(), jac.data(), &tight, nullptr, &out);
    auto frame = [](const std::vector<double>& v, std::size_t i) {
      return Eigen::Matrix<double, 3, 3, Eigen::RowMajor>(v.data() + 9 * i);
    };
    for (std::size_t j = 0; j < p; ++j) {
      const double h = 1e-5;
      std::vector<double> qp = q, qm = q, xp(2 * n), ap(9 * n), am(9 * n), bp(3 * n), bm(3 * n);
      qp[j] += h;
      qm[j] -= h;
      internal::BodyOutput op, om;
      op.orientation = ap.data();
      op.body_rate = bp.data();
      om.orientation = am.data();
      om.body_rate = bm.data();
      internal::EvaluateImpulsiveTrack(
          qp.data(), tau.data(), n, impulses, tight, xp.data(), nullptr, nullptr, nullptr, &op);
      internal::EvaluateImpulsiveTrack(
          qm.data(), tau.data(), n, impulses, tight, xp.data(), nullptr, nullptr, nullptr, &om);
      for (std::size_t i = 0; i < n; ++i) {
        // The body-frame derivative vee(A^T dA/dq_j) ~ Log(A(q - h)^T A(q + h)) / (2h); central
        // differences: h^2 ~ 1e-10 truncation, 1e-13/h rounding.
        const Eigen::Vector3d fd = LogSO3(frame(am, i).transpose() * frame(ap, i)) / (2 * h);
        for (int c = 0; c < 3; ++c) {
          EXPECT_NEAR(aj[(3 * i + c) * p + j], fd[c], 1e-7) << "orientation sample " << i << " parameter " << j;
          EXPECT_NEAR(bj[(3 * i + c) * p + j], (bp[3 * i + c] - bm[3 * i + c]) / (2 * h), 1e-7)
              << "rate sample " << i << " parameter " << j;
        }
      }
    }
    if (!impulses.empty()) continue;
    const FreeMotion motion = TruthMotion(1.3);
    for (std::size_t i = 0; i < n; ++i) {
      const MotionSample m = motion.At(tau[i]);
      EXPECT_LT(RotationAngle(frame(a, i), m.A), 1e-10) << i;
      EXPECT_LT((Eigen::Vector3d(b.data() + 3 * i) - m.A.transpose() * m.state.omega).norm(), 1e-10) << i;
    }
  }
}

// Noiseless tracks: the fit reaches the truth to the integration tolerance (1e-11 on the values);
// 1e-8 leaves three digits of margin (as the contact-track tests).
constexpr double kNoiselessLambdaTolerance = 1e-8;

TEST(IdentifyFrame, NoiselessPositionsAndOrientationsRecoverLambdaAndTheFrame) {
  TrackSpec spec;
  spec.orientation = true;
  const IdentifySummary s = Identify(MakeTrack(spec), NoProfile());
  ASSERT_EQ(s.status, IdentifyStatus::kIdentified) << s.BriefReport();
  EXPECT_NEAR(s.lambda, 1.3, kNoiselessLambdaTolerance);
  EXPECT_NEAR(s.mu, kMu, kNoiselessLambdaTolerance * kMu);
  EXPECT_TRUE(s.frame_fitted);
  ASSERT_EQ(s.parameters.size(), 8u);
  EXPECT_EQ(s.parameters[7], "chi");
  EXPECT_EQ(s.residuals, 5 * spec.n);
  const Eigen::Vector4d& o = s.orientation;
  const Eigen::Quaterniond fitted(o[0], o[1], o[2], o[3]);
  EXPECT_LT(RotationAngle(fitted.toRotationMatrix(), internal::StartFrame(kAngles.theta, kAngles.phi, kChi)), 1e-8);
  EXPECT_LT(s.orientation_max_residual, 1e-8);
  std::printf("noiseless orientations: |lambda - 1.3| = %.2e, |mu - 4| = %.2e, largest orientation residual %.2e rad\n",
              std::abs(s.lambda - 1.3),
              std::abs(s.mu - kMu),
              s.orientation_max_residual);
}

TEST(IdentifyFrame, NoiselessPositionsAndBodyRatesRecoverLambda) {
  TrackSpec spec;
  spec.body_rate = true;
  spec.sigma = 1e-9;  // body rates need the noise given: 1e-9 keeps the track noiseless to the tolerance
  spec.sigma_frame = 1e-9;
  const IdentifySummary s = Identify(MakeTrack(spec), NoProfile());
  ASSERT_NE(s.status, IdentifyStatus::kFailed) << s.BriefReport();
  EXPECT_NEAR(s.lambda, 1.3, kNoiselessLambdaTolerance);
  EXPECT_LT(s.body_rate_max_residual, 1e-8);
  std::printf("near-noiseless body rates: |lambda - 1.3| = %.2e, largest rate residual %.2e\n",
              std::abs(s.lambda - 1.3),
              s.body_rate_max_residual);
}

// A short single flight (0.15 of a period): the contact track alone shows an arc that fits
// (nearly) any lambda; the reorientation along it depends on lambda, so the orientations
// identify it.
TEST(IdentifyFrame, OrientationsIdentifyLambdaOnAShortFlightThatPositionsDoNot) {
  TrackSpec spec;
  spec.periods = 0.15;
  spec.n = 60;
  spec.sigma = 2e-3;
  spec.sigma_frame = 1e-3;
  spec.seed = 7;
  const IdentifySummary contact = Identify(MakeTrack(spec));
  spec.orientation = true;
  const IdentifySummary frame = Identify(MakeTrack(spec));
  spec.orientation = false;
  spec.body_rate = true;
  const IdentifySummary imu = Identify(MakeTrack(spec));
  std::printf("0.15-period flight: lambda se contact %.3g, with orientations %.3g, with body rates %.3g\n",
              contact.standard_errors[0],
              frame.standard_errors[0],
              imu.standard_errors[0]);
  EXPECT_EQ(contact.status, IdentifyStatus::kLambdaNotIdentified) << contact.BriefReport();
  ASSERT_EQ(frame.status, IdentifyStatus::kIdentified) << frame.BriefReport();
  ASSERT_EQ(imu.status, IdentifyStatus::kIdentified) << imu.BriefReport();
  for (const IdentifySummary* s : {&frame, &imu}) {
    EXPECT_LT(std::abs(s->lambda - 1.3), 4.0 * s->standard_errors[0]);
    EXPECT_LT(s->lambda_low, 1.3);
    EXPECT_GT(s->lambda_high, 1.3);
  }
}

// At lambda = 1 every state rolls on a straight line that shows only the period: the contact track
// is reported not identifying lambda; its orientations show the turn about the axis (v0 != 0) and
// identify lambda = 1 within its standard error.
TEST(IdentifyFrame, OrientationsIdentifyLambdaOnTheStraightTrackOfLambdaOne) {
  TrackSpec spec;
  spec.lambda = 1.0;
  spec.sigma = 2e-3;
  spec.sigma_frame = 2e-3;
  spec.seed = 9;
  const IdentifySummary contact = Identify(MakeTrack(spec), NoProfile());
  EXPECT_EQ(contact.status, IdentifyStatus::kLambdaNotIdentified) << contact.BriefReport();
  EXPECT_TRUE(contact.straight_path);
  spec.orientation = true;
  const IdentifySummary s = Identify(MakeTrack(spec), NoProfile());
  ASSERT_EQ(s.status, IdentifyStatus::kIdentified) << s.BriefReport();
  EXPECT_TRUE(s.straight_path);
  EXPECT_LT(std::abs(s.lambda - 1.0), 4.0 * s.standard_errors[0]);
  std::printf("straight track of lambda = 1: lambda %.6f +- %.2g with orientations\n", s.lambda, s.standard_errors[0]);
}

/// Seeds whose 95% profile interval of lambda covers the truth, over `seeds` noisy short tracks.
int Coverage(TrackSpec spec, int seeds) {
  int covered = 0;
  for (int k = 0; k < seeds; ++k) {
    spec.seed = 1000 + static_cast<unsigned>(k);
    const IdentifySummary s = Identify(MakeTrack(spec));
    if (s.status != IdentifyStatus::kFailed && s.lambda_low <= spec.lambda && spec.lambda <= s.lambda_high) ++covered;
  }
  return covered;
}

// The 95% interval covers the truth in ~95% of the seeds. With 100 seeds the count is
// Binomial(100, 0.95): mean 95, standard deviation 2.2; P(count < 88) ~ 0.1% for a correct
// interval, so [88, 100] accepts, and a count below flags an interval that is too narrow.
constexpr int kCoverageSeeds = 100;
constexpr int kMinCovered = 88;

TEST(IdentifyFrame, OrientationIntervalCoversTheTruthInAbout95PercentOfSeeds) {
  TrackSpec spec;
  spec.periods = 0.25;
  spec.n = 40;
  spec.sigma = 2e-3;
  spec.sigma_frame = 2e-3;
  spec.orientation = true;
  const int covered = Coverage(spec, kCoverageSeeds);
  std::printf("orientations: the 95%% interval covers lambda = 1.3 in %d of %d seeds\n", covered, kCoverageSeeds);
  EXPECT_GE(covered, kMinCovered);
}

TEST(IdentifyFrame, BodyRateIntervalCoversTheTruthInAbout95PercentOfSeeds) {
  TrackSpec spec;
  spec.periods = 0.25;
  spec.n = 40;
  spec.sigma = 2e-3;
  spec.sigma_frame = 2e-3;
  spec.body_rate = true;
  const int covered = Coverage(spec, kCoverageSeeds);
  std::printf("body rates: the 95%% interval covers lambda = 1.3 in %d of %d seeds\n", covered, kCoverageSeeds);
  EXPECT_GE(covered, kMinCovered);
}

TEST(IdentifyFrame, BadFrameColumnsAreRejectedNamingFieldAndRow) {
  TrackSpec spec;
  spec.n = 20;
  spec.sigma = 1e-3;
  spec.sigma_frame = 1e-3;
  spec.orientation = true;
  const IdentifyProblem good = MakeTrack(spec);
  EXPECT_EQ(good.Validate(), "");
  IdentifyProblem p = good;
  p.orientation[4] *= 1.001;
  EXPECT_NE(p.Validate().find("orientation[4]: value ["), std::string::npos) << p.Validate();
  EXPECT_NE(p.Validate().find("not a unit quaternion (w, x, y, z): norm 1.001, allowed 1 +- 1e-05"), std::string::npos)
      << p.Validate();
  p = good;
  p.orientation[4] *= 1.0 + 0.5 * kIdentifyQuaternionTolerance;  // within the tolerance
  EXPECT_EQ(p.Validate(), "");
  p = good;
  p.orientation[2][3] = std::nan("");
  EXPECT_NE(p.Validate().find("orientation[2].z: value nan: must be finite"), std::string::npos) << p.Validate();
  p = good;
  p.orientation.pop_back();
  EXPECT_NE(p.Validate().find("orientation (rows): value 19: must have one row per time (20)"), std::string::npos)
      << p.Validate();
  p = good;
  p.sigma_orientation.clear();
  EXPECT_NE(p.Validate().find("sigma_orientation (rows): value 0: sigma is given"), std::string::npos) << p.Validate();
  p = good;
  p.sigma_orientation[6] = -1.0;
  EXPECT_NE(p.Validate().find("sigma_orientation[6]: value -1: must be finite and > 0"), std::string::npos)
      << p.Validate();
  // Body rates: with spin (mixed columns), without noise, NaN.
  spec.orientation = false;
  spec.body_rate = true;
  const IdentifyProblem rates = MakeTrack(spec);
  EXPECT_EQ(rates.Validate(), "");
  p = rates;
  p.spin.assign(20, 0.1);
  p.sigma_spin.assign(20, 0.1);
  EXPECT_NE(p.Validate().find("body_rate (rows): value 20: give either spin or body_rate, not both"), std::string::npos)
      << p.Validate();
  p = rates;
  p.sigma.clear();
  EXPECT_NE(p.Validate().find("sigma (rows): value 0: measured body rates need sigma given too"), std::string::npos)
      << p.Validate();
  p = rates;
  p.body_rate[3][1] = std::nan("");
  EXPECT_NE(p.Validate().find("body_rate[3][1]: value nan: must be finite"), std::string::npos) << p.Validate();
}

}  // namespace
}  // namespace plateball
