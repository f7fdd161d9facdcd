// The appendix's closed forms (30)-(34) against numerical integration, and the corrections of
// docs/paper_notes.md ("Appendix closed forms"): each paper formula taken literally is shown to
// fail where the note says it does, and the corrected one to hold.
#include "plateball/closed_forms.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "plateball/angle_form.h"
#include "plateball/ball_state.h"
#include "plateball/free_motion.h"
#include "support/test_support.h"

namespace plateball {
namespace {

// Integration at 1e-12 over two periods has global error ~1e-11; closed forms are exact to
// round-off. 1e-9 leaves two orders of margin.
constexpr double kAgreement = 1e-9;
// A formula that is wrong misses by O(1) (a branch of pi, a sign); 1e-2 separates the two.
constexpr double kClearlyWrong = 1e-2;

// c > 0 and c < 0 starts, w0 beyond (-pi, pi], theta0 < 0, near the poles, and Figure 8's
// start (-pi/3, pi/2, 0), which has w0 = pi/2 and so lies on the pole family c = 0.
std::vector<AngleState> States() {
  return {{M_PI / 3, 0.4, 0.1},
          {2.5, 0.4, 2.9},
          {1.0, -1.0, 2.0},
          {2.0, 3.0, -0.7},
          {0.3, 7.0, 7.5},
          {-M_PI / 3, M_PI / 2, 0.0},
          {1.2, 0.0, 6.0},
          {M_PI / 2, 0.0, 0.0},
          {0.05, 1.0, 0.9},
          {3.0, -2.0, 1.0},
          {-2.0, 0.5, 0.2}};
}

AngleFormResult Integrate(const BallModel& model, const AngleState& a, double mu, const std::vector<double>& times) {
  const AngleFormResult r = IntegrateAngleForm(model, a, mu, {0, 0}, times);
  EXPECT_EQ(r.status, AngleFormStatus::kCompleted) << r.message;
  return r;
}

std::vector<double> Times(double period, int n = 80, double periods = 2.0) {
  std::vector<double> t;
  for (int i = 0; i <= n; ++i) t.push_back(periods * period * i / n);
  return t;
}

TEST(ClosedForms, MatchAngleFormIntegrationForEveryFamilyLambdaAndEnergy) {
  for (double lambda : {0.5, 1.0, 2.0, 5.0})
    for (double mu : {1.0, 0.3, 4.0})
      for (const AngleState& a : States()) {
        const BallModel model = BallModel::FromLambda(lambda);
        const AppendixSolution sol(model, a, mu);
        // The pole family cannot be integrated in angles (ThroughPolesFamily... covers it).
        if (sol.constants().family == ClosedFormFamily::kThroughPoles) continue;
        // Integrate from the solution's own start (theta0 < 0 is mapped to [0, pi]).
        const AngleFormResult r = Integrate(model, sol.initial(), mu, Times(sol.Period()));
        for (const AngleFormSample& s : r.samples) {
          const AngleState c = sol.At(s.t);
          SCOPED_TRACE("lambda " + std::to_string(lambda) + " mu " + std::to_string(mu) + " theta0 " +
                       std::to_string(a.theta) + " t " + std::to_string(s.t) + " family " +
                       ToString(sol.constants().family));
          EXPECT_NEAR(c.theta, s.angles.theta, kAgreement);
          EXPECT_NEAR(c.phi, s.angles.phi, kAgreement);
          EXPECT_NEAR(c.psi, s.angles.psi, kAgreement);
        }
      }
}

TEST(ClosedForms, NegativeThetaStartIsTheSamePhysicalMotion) {
  // Figure 8's theta0 = -pi/3: the closed form starts from the equivalent canonical state and
  // produces the same z and omega as the chart-free integration from the literal state.
  const BallModel model = BallModel::FromLambda(2.0);
  const AngleState a{-M_PI / 3, M_PI / 2, 0.0};
  const AppendixSolution sol(model, a, 1.0);
  const FreeMotion motion = FreeMotion::FromAngles(model, a, 1.0);
  for (double t : Times(sol.Period(), 20)) {
    const BallState c = StateFromAngles(sol.At(t), 1.0, model);
    const MotionSample m = motion.At(t);
    EXPECT_LT((c.z - m.state.z).norm(), kAgreement);
    EXPECT_LT((c.omega - m.state.omega).norm(), kAgreement);
  }
}

TEST(ClosedForms, ConstantsFollowFromTheInitialState) {
  const BallModel model = BallModel::FromLambda(2.0);
  for (const AngleState& a0 : States()) {
    const AppendixSolution sol(model, a0, 1.0);
    const AppendixConstants& k = sol.constants();
    const AngleState a = sol.initial();
    if (k.family == ClosedFormFamily::kThroughPoles) continue;
    const double w0 = a.phi - a.psi;
    EXPECT_NEAR(k.c, std::sin(a.theta) * std::cos(w0), 1e-15);   // (32)
    EXPECT_NEAR(k.c_bar, 1.0 / std::abs(k.c), 1e-12 * k.c_bar);  // c = 1/c_bar
    EXPECT_NEAR(k.m * k.m, model.lambda() - 1.0 + k.c_bar * k.c_bar, 1e-12 * k.m * k.m);
    EXPECT_NEAR(k.s, k.m / k.c_bar, 1e-14);  // (33) -> (34)
    // (30)-(31) at t = 0 on the c > 0 representative: C1(0) = -c2, C2(0) = c1.
    const double theta_r = k.c > 0 ? a.theta : M_PI - a.theta;
    const double w_r = k.c > 0 ? w0 : w0 + M_PI;
    EXPECT_NEAR(std::tan(w_r), k.c2, 1e-12 * std::max(1.0, std::abs(k.c2)));    // w(0) = -arctan(-c2)
    EXPECT_NEAR(std::atan2(std::sqrt(1 + k.c2 * k.c2), k.c1), theta_r, 1e-14);  // (30) at t = 0
  }
}

TEST(ClosedForms, Equations32And34HoldAlongIntegratedTrajectoriesWithTheDerivedD) {
  for (double lambda : {0.5, 2.0, 5.0})
    for (const AngleState& a : States()) {
      const BallModel model = BallModel::FromLambda(lambda);
      const AppendixSolution sol(model, a, 1.7);
      const AppendixConstants& k = sol.constants();
      if (k.family == ClosedFormFamily::kThroughPoles) continue;  // (34) checked in ThroughPoles...
      const AngleFormResult r = Integrate(model, sol.initial(), 1.7, Times(sol.Period()));
      for (const AngleFormSample& s : r.samples) {
        const double w = s.angles.phi - s.angles.psi;
        EXPECT_NEAR(AppendixC(s.angles), k.c, kAgreement);                                      // (32)
        EXPECT_NEAR(AppendixResidual34(s.angles, k.d34, model), 0.0, kAgreement);               // (34)
        EXPECT_NEAR(-std::sin(s.angles.phi - k.d34), k.c_bar * std::sin(w) / k.m, kAgreement);  // (33)
      }
    }
}

TEST(ClosedForms, PaperPrincipalArctanIn30IsWrongWhereC2IsNegative) {
  // (30) read with the principal arctan gives theta in (-pi/2, pi/2): it is off by pi whenever
  // C2 < 0 (half of every period). The branch in (0, pi), atan2(sqrt(1 + C1^2), C2), is right.
  const BallModel model = BallModel::FromLambda(2.0);
  const AppendixSolution sol(model, {M_PI / 3, 0.4, 0.1}, 1.0);
  const double c1 = sol.constants().c1, c2 = sol.constants().c2;
  const AngleFormResult r = Integrate(model, sol.initial(), 1.0, Times(sol.Period()));
  int negative_c2 = 0;
  for (const AngleFormSample& s : r.samples) {
    const double C1 = c1 * std::sin(s.t) - c2 * std::cos(s.t), C2 = c1 * std::cos(s.t) + c2 * std::sin(s.t);
    const double paper = std::atan(std::sqrt(1 + C1 * C1) / C2);
    const double corrected = std::atan2(std::sqrt(1 + C1 * C1), C2);
    EXPECT_NEAR(corrected, s.angles.theta, kAgreement);
    EXPECT_NEAR(-std::atan(C1), s.angles.phi - s.angles.psi, kAgreement);  // (31) as printed
    if (C2 < -1e-3) {
      ++negative_c2;
      EXPECT_GT(std::abs(paper - s.angles.theta), kClearlyWrong);
      EXPECT_NEAR(paper + M_PI, s.angles.theta, kAgreement);
    } else if (C2 > 1e-3) {
      EXPECT_NEAR(paper, s.angles.theta, kAgreement);
    }
  }
  EXPECT_GT(negative_c2, 10);
}

TEST(ClosedForms, PaperSignOfPhiAndTheInitialValueDOf34FailAlongTheTrajectory) {
  // The paper integrates phi' = -c_bar (...) and writes phi = +arcsin(z/m) + d. Taken literally
  // (z = c_bar sin u, u = arctan C1 = -w), phi - d = -arcsin(sin w / s): the wrong sign. Also the
  // d that merely satisfies (34) at t = 0, d0 = phi0 + arcsin(sin w0 / s), fails later for c > 0;
  // the d that holds along the whole trajectory is d34 = phi0 + pi - arcsin(sin w0 / s).
  const BallModel model = BallModel::FromLambda(2.0);
  const AngleState a{M_PI / 3, 0.4, -0.6};  // w0 = 1: sin(w) swings through both signs
  const AppendixSolution sol(model, a, 1.0);
  const AppendixConstants& k = sol.constants();
  ASSERT_EQ(k.family, ClosedFormFamily::kPositiveC);
  const double w0 = a.phi - a.psi;
  const double d_paper = a.phi - std::asin(-k.c_bar * std::sin(w0) / k.m);  // phi(0) = arcsin(z(0)/m) + d
  const double d0 = a.phi + std::asin(std::sin(w0) / k.s);                  // (34) at t = 0 only
  EXPECT_NEAR(AppendixResidual34(a, d0, model), 0.0, 1e-14);
  EXPECT_NEAR(std::remainder(k.d34 - (a.phi + M_PI - std::asin(std::sin(w0) / k.s)), 2 * M_PI), 0.0, 1e-14);
  const AngleFormResult r = Integrate(model, a, 1.0, Times(sol.Period()));
  double paper_miss = 0.0, d0_miss = 0.0;
  for (const AngleFormSample& s : r.samples) {
    const double w = s.angles.phi - s.angles.psi;
    const double u = std::atan(-std::tan(w));  // = arctan(C1)
    const double phi_paper = std::asin(k.c_bar * std::sin(u) / k.m) + d_paper;
    paper_miss = std::max(paper_miss, std::abs(phi_paper - s.angles.phi));
    d0_miss = std::max(d0_miss, std::abs(AppendixResidual34(s.angles, d0, model)));
    EXPECT_NEAR(sol.Phi(s.t), s.angles.phi, kAgreement);                       // corrected
    EXPECT_NEAR(AppendixResidual34(s.angles, k.d34, model), 0.0, kAgreement);  // corrected d
  }
  EXPECT_GT(paper_miss, kClearlyWrong);
  EXPECT_GT(d0_miss, kClearlyWrong);
}

TEST(ClosedForms, SolutionsAtEnergyMuAreUnitEnergySolutionsAtTimeSqrtMuT) {
  // Checked by integration alone (independent of the closed forms): (theta, phi, psi) at mu and
  // time t equal the mu = 1 solution at time sqrt(mu) t; x likewise (x' scales with sqrt(mu)).
  const BallModel model = BallModel::FromLambda(0.5);
  const AngleState a{1.1, 0.2, -0.4};
  for (double mu : {0.25, 3.0, 9.0}) {
    std::vector<double> t_mu, t_1;
    for (int i = 0; i <= 30; ++i) {
      t_mu.push_back(0.4 * i);
      t_1.push_back(0.4 * i * std::sqrt(mu));
    }
    const AngleFormResult r_mu = Integrate(model, a, mu, t_mu);
    const AngleFormResult r_1 = Integrate(model, a, 1.0, t_1);
    for (std::size_t i = 0; i < t_mu.size(); ++i) {
      EXPECT_NEAR(r_mu.samples[i].angles.theta, r_1.samples[i].angles.theta, kAgreement);
      EXPECT_NEAR(r_mu.samples[i].angles.phi, r_1.samples[i].angles.phi, kAgreement);
      EXPECT_NEAR(r_mu.samples[i].angles.psi, r_1.samples[i].angles.psi, kAgreement);
      EXPECT_LT((r_mu.samples[i].x - r_1.samples[i].x).norm(), kAgreement);
    }
  }
}

TEST(ClosedForms, MirrorMapIsASymmetryOfEquations22And23) {
  // (theta, w) -> (pi - theta, w + pi): theta' changes sign (as pi - theta must), w' and phi'
  // are unchanged; it maps c to -c.
  const BallModel model = BallModel::FromLambda(2.0);
  for (const AngleState& a : {AngleState{1.0, 0.3, -0.2}, AngleState{2.2, -1.0, 1.5}}) {
    const AngleState m{M_PI - a.theta, a.phi, a.psi - M_PI};  // w + pi at the same phi
    AngleState d, dm;
    AngleFormDerivative(a, 1.3, model, &d, nullptr);
    AngleFormDerivative(m, 1.3, model, &dm, nullptr);
    EXPECT_NEAR(dm.theta, -d.theta, 1e-14);
    EXPECT_NEAR(dm.phi - dm.psi, d.phi - d.psi, 1e-14);
    EXPECT_NEAR(dm.phi, d.phi, 1e-14);
    EXPECT_NEAR(AppendixC(m), -AppendixC(a), 1e-15);
  }
}

TEST(ClosedForms, ThroughPolesFamilyMatchesChartFreeIntegrationAcrossBothPoles) {
  // c = 0: w = +-pi/2 constant, theta linear in the extended chart; the trajectory crosses
  // theta = 0 and theta = pi every period. Compared on z and omega (chart-free, no angles).
  for (double lambda : {0.5, 2.0}) {
    const BallModel model = BallModel::FromLambda(lambda);
    for (const AngleState& a : {AngleState{1.0, M_PI / 2 + 0.3, 0.3},
                                AngleState{0.0, 1.7, 0.4},
                                AngleState{M_PI, -0.2, 2.0},
                                AngleState{2.0, -0.5, M_PI / 2 - 0.5}}) {
      const double mu = 2.0;
      const AppendixSolution sol(model, a, mu);
      ASSERT_EQ(sol.constants().family, ClosedFormFamily::kThroughPoles);
      const FreeMotion motion = FreeMotion::FromAngles(model, a, mu);
      // The start on a pole is re-expressed on its meridian: the same physical state.
      const BallState s_given = StateFromAngles(a, mu, model), s_used = StateFromAngles(sol.initial(), mu, model);
      EXPECT_LT((s_given.z - s_used.z).norm(), 1e-15);
      EXPECT_LT((s_given.omega - s_used.omega).norm(), 1e-15);
      for (double t : Times(sol.Period(), 40)) {
        const BallState c = StateFromAngles(sol.At(t), mu, model);
        const MotionSample m = motion.At(t);
        EXPECT_LT((c.z - m.state.z).norm(), kAgreement) << "t " << t;
        EXPECT_LT((c.omega - m.state.omega).norm(), kAgreement) << "t " << t;
        EXPECT_NEAR(AppendixC(sol.At(t)), 0.0, 1e-15);                                       // (32)
        EXPECT_NEAR(AppendixResidual34(sol.At(t), sol.constants().d34, model), 0.0, 1e-15);  // (34)
      }
    }
  }
}

TEST(ClosedForms, ClosedFormIsPeriodicWithTwoPiOverSqrtMu) {
  const BallModel model = BallModel::FromLambda(5.0);
  for (const AngleState& a : States()) {
    const AppendixSolution sol(model, a, 0.6);
    if (sol.constants().family == ClosedFormFamily::kThroughPoles) continue;
    for (double t : {0.0, 0.7, 3.1}) {
      const AngleState p = sol.At(t), q = sol.At(t + sol.Period());
      EXPECT_NEAR(p.theta, q.theta, 1e-12);
      EXPECT_NEAR(p.phi, q.phi, 1e-12);
      EXPECT_NEAR(p.psi, q.psi, 1e-12);
    }
  }
}

TEST(ClosedForms, RejectsInvalidInputNamingTheField) {
  const BallModel model = BallModel::FromLambda(2.0);
  const auto message = [](auto&& f) { return plateball::testing::InvalidArgumentMessage(f, "no exception"); };
  EXPECT_NE(message([&] { AppendixSolution(model, {1.0, 0.0, 0.0}, 0.0); }).find("mu: value"), std::string::npos);
  EXPECT_NE(message([&] { AppendixSolution(model, {1.0, NAN, 0.0}, 1.0); }).find("phi: value"), std::string::npos);
  EXPECT_NE(message([&] {
              AppendixSolution(model, {1.0, 0.0, 0.0}, 1.0).At(std::numeric_limits<double>::infinity());
            }).find("t: value"),
            std::string::npos);
  EXPECT_EQ(ToString(ClosedFormFamily::kThroughPoles), "through_poles");
}

}  // namespace
}  // namespace plateball
