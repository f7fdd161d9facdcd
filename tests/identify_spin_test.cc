// Identification with a measured axial spin v0 = <omega, z> (identify.h, IdentifyProblem::spin):
// the rate an IMU measures about the ball's symmetry axis. The tracks are the library's FreeMotion
// (its state's v0, AxialSpin of ball_state.h), independent of the fit's model.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "identify_model.h"
#include "plateball/free_motion.h"
#include "plateball/identify.h"

namespace plateball {
namespace {

/// n samples over `periods` periods of FreeMotion from `angles`, noise sigma on the positions
/// and sigma_spin on the spin (both given), with the spin when `with_spin`.
IdentifyProblem MakeTrack(double lambda,
                          const AngleState& angles,
                          int n,
                          double sigma,
                          double sigma_spin,
                          unsigned seed,
                          bool with_spin = true) {
  const double mu = 4.0;
  const FreeMotion motion = FreeMotion::FromAngles(BallModel::FromLambda(lambda), angles, mu, {0.5, -0.2});
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> noise(0.0, 1.0);
  IdentifyProblem p;
  for (int i = 0; i < n; ++i) {
    const double t = 2.0 * motion.Period() * i / (n - 1);
    const MotionSample m = motion.At(t);
    p.t.push_back(t);
    p.x.push_back(m.x + sigma * Eigen::Vector2d(noise(rng), noise(rng)));
    p.sigma.push_back(sigma);
    if (!with_spin) continue;
    p.spin.push_back(AxialSpin(m.state) + sigma_spin * noise(rng));
    p.sigma_spin.push_back(sigma_spin);
  }
  return p;
}

IdentifyOptions FastOptions() {
  IdentifyOptions o;
  o.profile_interval = false;
  return o;
}

TEST(IdentifySpin, ModelSpinAndItsJacobianMatchFreeMotionAndCentralDifferences) {
  const std::vector<double> q{1.3, 4.0, 0.8, 0.3, 0.2, 0.5, -0.2, 0.7};
  const std::vector<double> tau{0.0, 0.4, 1.0, 1.7, 2.6};
  const IntegrationOptions tight{1e-13, 1e-13, 2'000'000};
  for (const std::vector<double>& impulses : {std::vector<double>{}, std::vector<double>{1.2}}) {
    const std::size_t n = tau.size(), p = 7 + impulses.size();
    std::vector<double> x(2 * n), jac(2 * n * p), v(n), vj(n * p), vp(n), vm(n);
    internal::BodyOutput out;
    out.spin = v.data();
    out.spin_jacobian = vj.data();
    internal::EvaluateImpulsiveTrack(
        q.data(), tau.data(), n, impulses, tight, x.data(), jac.data(), &tight, nullptr, &out);
    for (std::size_t j = 0; j < p; ++j) {
      const double h = 1e-5;
      std::vector<double> qp = q, qm = q;
      qp[j] += h;
      qm[j] -= h;
      internal::BodyOutput op, om;
      op.spin = vp.data();
      om.spin = vm.data();
      internal::EvaluateImpulsiveTrack(
          qp.data(), tau.data(), n, impulses, tight, x.data(), nullptr, nullptr, nullptr, &op);
      internal::EvaluateImpulsiveTrack(
          qm.data(), tau.data(), n, impulses, tight, x.data(), nullptr, nullptr, nullptr, &om);
      for (std::size_t i = 0; i < n; ++i)  // central difference: h^2 ~ 1e-10 truncation, 1e-13/h rounding
        EXPECT_NEAR(vj[i * p + j], (vp[i] - vm[i]) / (2 * h), 1e-7) << "sample " << i << " parameter " << j;
    }
    if (!impulses.empty()) continue;
    const FreeMotion motion = FreeMotion::FromAngles(BallModel::FromLambda(1.3), {0.8, 0.3, 0.2}, 4.0, {0.5, -0.2});
    for (std::size_t i = 0; i < n; ++i) EXPECT_NEAR(v[i], AxialSpin(motion.At(tau[i]).state), 1e-10) << i;
  }
}

// At lambda = 1 every state rolls on a straight line: the contact track alone cannot tell lambda
// = 1 from the v0 = 0 family (any lambda), and is reported not identified. The spin shows v0 != 0
// (w = phi - psi = 0.1: a large axial spin), which leaves lambda = 1: identified, within its
// standard error.
TEST(IdentifySpin, SpinIdentifiesLambdaOnTheStraightTrackOfLambdaOne) {
  const AngleState angles{0.8, 0.3, 0.2};
  const IdentifySummary contact = Identify(MakeTrack(1.0, angles, 300, 1e-3, 1e-3, 1, false), FastOptions());
  EXPECT_EQ(contact.status, IdentifyStatus::kLambdaNotIdentified) << contact.BriefReport();
  EXPECT_TRUE(contact.straight_path);
  const IdentifySummary s = Identify(MakeTrack(1.0, angles, 300, 1e-3, 1e-3, 1), FastOptions());
  ASSERT_EQ(s.status, IdentifyStatus::kIdentified) << s.BriefReport();
  EXPECT_TRUE(s.straight_path);
  EXPECT_LT(std::abs(s.lambda - 1.0), 4.0 * s.standard_errors[0]);
  EXPECT_LT(s.standard_errors[0], 0.05);
  EXPECT_EQ(s.residuals, 900);
  EXPECT_NEAR(s.spin_rms_residual, 1e-3, 3e-4);  // the spin noise
}

// w = phi - psi = pi/2: v0 = 0, the ball tumbles about a horizontal axis and lambda enters
// nothing, the spin included: still not identified.
TEST(IdentifySpin, ZeroSpinTrackStaysNotIdentified) {
  const IdentifySummary s = Identify(MakeTrack(1.7, {0.9, 0.4, 0.4 - M_PI / 2}, 200, 1e-3, 1e-3, 2), FastOptions());
  EXPECT_EQ(s.status, IdentifyStatus::kLambdaNotIdentified) << s.BriefReport();
  EXPECT_TRUE(s.straight_path);
}

// A curved track: lambda from positions and spin; the spin tightens the standard error.
TEST(IdentifySpin, SpinTightensLambdaOnACurvedTrack) {
  const AngleState angles{0.8, 0.3, 0.2};
  const IdentifySummary contact = Identify(MakeTrack(1.3, angles, 200, 5e-3, 1e-3, 3, false), FastOptions());
  const IdentifySummary s = Identify(MakeTrack(1.3, angles, 200, 5e-3, 1e-3, 3), FastOptions());
  ASSERT_EQ(contact.status, IdentifyStatus::kIdentified) << contact.BriefReport();
  ASSERT_EQ(s.status, IdentifyStatus::kIdentified) << s.BriefReport();
  EXPECT_LT(std::abs(s.lambda - 1.3), 4.0 * s.standard_errors[0]);
  EXPECT_LT(s.standard_errors[0], contact.standard_errors[0]);
  std::printf(
      "lambda standard error: contact %.3g, with spin %.3g\n", contact.standard_errors[0], s.standard_errors[0]);
}

TEST(IdentifySpin, BadSpinIsRejectedNamingTheField) {
  const IdentifyProblem good = MakeTrack(1.3, {0.8, 0.3, 0.2}, 20, 1e-3, 1e-3, 4);
  EXPECT_EQ(good.Validate(), "");
  IdentifyProblem p = good;
  p.sigma_spin.clear();
  EXPECT_NE(p.Validate().find("sigma_spin (rows): value 0"), std::string::npos) << p.Validate();
  p = good;
  p.sigma.clear();
  EXPECT_NE(p.Validate().find("sigma (rows): value 0: a measured spin needs sigma given too"), std::string::npos)
      << p.Validate();
  p = good;
  p.spin.pop_back();
  EXPECT_NE(p.Validate().find("spin (rows): value 19"), std::string::npos) << p.Validate();
  p = good;
  p.spin[3] = std::nan("");
  EXPECT_NE(p.Validate().find("spin[3]: value nan: must be finite"), std::string::npos) << p.Validate();
  p = good;
  p.sigma_spin[5] = 0.0;
  EXPECT_NE(p.Validate().find("sigma_spin[5]: value 0: must be finite and > 0"), std::string::npos) << p.Validate();
}

}  // namespace
}  // namespace plateball
