// Closed-form elastica (section 2.2) checked against direct integration of the heading pendulum
// g'' = -G cos(g - g_W), x' = (cos g, sin g), against the paper's extremal equations, and
// against classical complete-integral formulas.
#include "plateball/elastica.h"

#include <boost/math/special_functions/jacobi_elliptic.hpp>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <array>
#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/ellint_2.hpp>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "jacobi_elliptic.h"

using namespace plateball;

namespace {

// Direct integration at 1e-13 leaves ~1e-11 of error over the lengths used; the closed forms
// are exact, so these tolerances bound the integrator, not the code under test.
constexpr double kHeadingTol = 1e-9;
constexpr double kPositionTol = 1e-9;

struct Case {
  double G, heading_w, heading0, curvature0;
  std::string what;
};

std::vector<Case> Cases() {
  return {{1.0, 0.3, 0.2, 0.5, "oscillating small"},
          {2.5, -1.0, 2.0, -1.2, "oscillating large amplitude"},
          {0.7, 1.1, 0.4, 2.5, "rotating left"},
          {0.7, 1.1, 0.4, -2.5, "rotating right"},
          {0.0, 0.0, 0.3, 0.8, "circle"},
          {0.0, 0.0, 1.3, 0.0, "straight line"},
          {3.0, 0.0, -M_PI / 2 + 1e-3, 0.0, "oscillating near rest"}};
}

using State = std::array<double, 4>;  // g, g', x1, x2

State Integrate(const Case& c, double s_end) {
  namespace odeint = boost::numeric::odeint;
  State y{c.heading0, c.curvature0, 0.0, 0.0};
  auto rhs = [&c](const State& q, State& dq, double) {
    dq[0] = q[1];
    dq[1] = -c.G * std::cos(q[0] - c.heading_w);
    dq[2] = std::cos(q[0]);
    dq[3] = std::sin(q[0]);
  };
  odeint::integrate_adaptive(odeint::make_controlled(1e-13, 1e-13, odeint::runge_kutta_dopri5<State>()), rhs, y,
                             0.0, s_end, 1e-3);
  return y;
}

}  // namespace

TEST(Elastica, HeadingCurvatureAndPositionMatchDirectIntegration) {
  for (const Case& c : Cases()) {
    const Elastica e = Elastica::FromInitialState(c.G, c.heading_w, c.heading0, c.curvature0);
    for (double s : {0.0, 0.37, 1.9, 4.2, 11.3}) {
      const State y = Integrate(c, s);
      EXPECT_NEAR(e.Heading(s), y[0], kHeadingTol) << c.what << " s = " << s;
      EXPECT_NEAR(e.Curvature(s), y[1], kHeadingTol) << c.what << " s = " << s;
      EXPECT_NEAR(e.Position(s).x(), y[2], kPositionTol) << c.what << " s = " << s;
      EXPECT_NEAR(e.Position(s).y(), y[3], kPositionTol) << c.what << " s = " << s;
      EXPECT_NEAR(e.Tangent(s).x(), std::cos(y[0]), kHeadingTol) << c.what;
      EXPECT_NEAR(e.Tangent(s).y(), std::sin(y[0]), kHeadingTol) << c.what;
    }
  }
}

TEST(Elastica, PendulumEnergyIsConservedAndMatchesInitialState) {
  for (const Case& c : Cases()) {
    const Elastica e = Elastica::FromInitialState(c.G, c.heading_w, c.heading0, c.curvature0);
    const double theta0 = c.heading0 - c.heading_w + M_PI / 2;
    const double e0 = 0.5 * c.curvature0 * c.curvature0 - c.G * std::cos(theta0);
    EXPECT_NEAR(e.G(), c.G, 1e-12) << c.what;
    EXPECT_NEAR(e.Energy(), e0, 1e-12 * (1 + std::abs(e0))) << c.what;
    for (double s : {0.5, 3.0, 7.7}) {
      const double k = e.Curvature(s), th = e.PendulumAngle(s);
      EXPECT_NEAR(0.5 * k * k - c.G * std::cos(th), e0, 1e-11 * (1 + std::abs(e0))) << c.what;
    }
  }
}

TEST(Elastica, TangentAndCurvatureArePeriodicAndPositionDriftsByOnePeriod) {
  for (const Case& c : Cases()) {
    const Elastica e = Elastica::FromInitialState(c.G, c.heading_w, c.heading0, c.curvature0);
    if (e.IsStraight()) continue;
    const double t = e.Period();
    for (double s : {0.1, 1.3, 2.9}) {
      EXPECT_NEAR(e.Curvature(s + t), e.Curvature(s), 1e-11) << c.what;
      EXPECT_LT((e.Tangent(s + t) - e.Tangent(s)).norm(), 1e-11) << c.what;
      EXPECT_LT((e.Position(s + 2 * t) - e.Position(s) - 2 * e.DriftPerPeriod()).norm(), 1e-10) << c.what;
    }
  }
}

TEST(Elastica, OscillatingDriftIsClassicalCompleteIntegralFormula) {
  // Over one period of an oscillating elastica the chord is (8 E(k) - 4 K(k)) / sqrt(G) along the
  // direction perpendicular to W (Love, Treatise on elasticity, section 263), computed here with
  // the complete integrals of Boost only.
  for (double k : {0.1, 0.5, 0.9, 0.99}) {
    for (double b : {0.5, 2.0}) {
      ElasticaParameters p;
      p.regime = PendulumRegime::kOscillating;
      p.rate = b;
      p.modulus = k;
      p.phase = 0.3;
      p.heading_w = M_PI / 2;  // pendulum frame = plane
      const Elastica e(p);
      const double expected = (8 * boost::math::ellint_2(k) - 4 * boost::math::ellint_1(k)) / b;
      EXPECT_NEAR(e.DriftPerPeriod().x(), expected, 1e-11) << k;
      EXPECT_NEAR(e.DriftPerPeriod().y(), 0.0, 1e-11) << k;
      EXPECT_NEAR(e.Period(), 4 * boost::math::ellint_1(k) / b, 1e-12);
    }
  }
}

TEST(Elastica, SatisfiesThePapersExtremalEquations) {
  // Section 2.2: v' = (e3 x x') x v and x'' = v^3 e3 x x', with v^3 = g' and the horizontal part
  // v_h = W - e3 x x', W = G (cos g_W, sin g_W) (docs/paper_notes.md). Checked by central
  // differences (step 1e-4: truncation ~1e-8).
  for (const Case& c : Cases()) {
    const Elastica e = Elastica::FromInitialState(c.G, c.heading_w, c.heading0, c.curvature0);
    const Eigen::Vector2d w = c.G * Eigen::Vector2d(std::cos(c.heading_w), std::sin(c.heading_w));
    auto v = [&](double s) {
      const Eigen::Vector2d t = e.Tangent(s);
      const Eigen::Vector2d n(-t.y(), t.x());
      return Eigen::Vector3d(w.x() - n.x(), w.y() - n.y(), e.Curvature(s));
    };
    for (double s : {0.4, 2.2, 5.1}) {
      const double h = 1e-4;
      const Eigen::Vector3d dv = (v(s + h) - v(s - h)) / (2 * h);
      const Eigen::Vector2d t = e.Tangent(s);
      const Eigen::Vector3d xdot(t.x(), t.y(), 0.0);
      const Eigen::Vector3d e3xx = Eigen::Vector3d::UnitZ().cross(xdot);
      EXPECT_LT((dv - e3xx.cross(v(s))).norm(), 1e-7) << c.what;
      const Eigen::Vector2d xdd = (e.Tangent(s + h) - e.Tangent(s - h)) / (2 * h);
      EXPECT_LT((xdd - v(s).z() * e3xx.head<2>()).norm(), 1e-7) << c.what;
    }
  }
}

TEST(Elastica, InvalidParametersNameTheField) {
  ElasticaParameters p;
  p.modulus = 1.0;
  try {
    Elastica e(p);
    FAIL() << "modulus 1 accepted";
  } catch (const std::invalid_argument& ex) {
    EXPECT_NE(std::string(ex.what()).find("modulus"), std::string::npos);
  }
  p.modulus = 0.5;
  p.rate = std::nan("");
  EXPECT_THROW(Elastica{p}, std::invalid_argument);
  // Separatrix: E = G exactly (theta0 = 0, curvature0^2 / 2 = 2 G).
  EXPECT_THROW(Elastica::FromInitialState(1.0, M_PI / 2, 0.0, 2.0), std::invalid_argument);
  EXPECT_THROW(Elastica::FromInitialState(-1.0, 0.0, 0.0, 0.0), std::invalid_argument);
}

TEST(Elastica, FastJacobiFunctionsMatchBoost) {
  // The AGM implementation used by the closed forms against boost::math::jacobi_elliptic.
  for (double k : {0.0, 0.3, 0.9, 0.999}) {
    for (double u = -9.0; u <= 9.0; u += 0.173) {
      double sn, cn, dn, bcn, bdn;
      internal::JacobiSnCnDn(u, k, &sn, &cn, &dn);
      const double bsn = boost::math::jacobi_elliptic(k, u, &bcn, &bdn);
      EXPECT_NEAR(sn, bsn, 1e-14) << k << " " << u;
      EXPECT_NEAR(cn, bcn, 1e-14) << k << " " << u;
      EXPECT_NEAR(dn, bdn, 1e-14) << k << " " << u;
    }
  }
}
