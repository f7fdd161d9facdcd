// Closed-form elastica (section 2.2) checked against direct integration of the heading pendulum
// g'' = -G cos(g - g_W), x' = (cos g, sin g), against the paper's extremal equations, and
// against classical complete-integral formulas.
#include "plateball/elastica.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <boost/math/special_functions/ellint_1.hpp>
#include <boost/math/special_functions/ellint_2.hpp>
#include <boost/math/special_functions/jacobi_elliptic.hpp>
#include <boost/numeric/odeint.hpp>
#include <cmath>
#include <limits>
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
  odeint::integrate_adaptive(
      odeint::make_controlled(1e-13, 1e-13, odeint::runge_kutta_dopri5<State>()), rhs, y, 0.0, s_end, 1e-3);
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

// The elastica at tiny arguments and near the separatrix.

TEST(Elastica, JacobiFunctionsAreFiniteAndRightAtTinyArguments) {
  // The descending recursion divides by sin(c u) and used to overflow (NaN) below |u| ~ 1e-154.
  // Reference: the Maclaurin series sn = u - (1 + k^2) u^3 / 6, cn = 1 - u^2 / 2,
  // dn = 1 - k^2 u^2 / 2 (+ O(u^4)), on both sides of kJacobiTinyArgument.
  for (double k : {0.0, 0.6, 1.0 - 1e-8}) {
    for (double u : {5e-324, 1e-300, -1e-300, 1e-200, 1e-155, -1e-100, 1e-21, 1e-19, -1e-12, 1e-8}) {
      double sn, cn, dn;
      internal::JacobiSnCnDn(u, k, &sn, &cn, &dn);
      EXPECT_NEAR(sn / u, 1.0 - (1.0 + k * k) * u * u / 6.0, 5e-16) << k << " " << u;
      EXPECT_NEAR(cn, 1.0 - u * u / 2.0, 5e-16) << k << " " << u;
      EXPECT_NEAR(dn, 1.0 - k * k * u * u / 2.0, 5e-16) << k << " " << u;
    }
  }
}

TEST(Elastica, TangentCurvaturePositionAreFiniteAndRightAtTinyArcLengths) {
  // With phase 0 the Jacobi argument is rate * s itself: at |s| ~ 1e-300 Tangent and Curvature
  // were NaN. Position(s) = s Tangent(0) + O(s^2 curvature).
  for (PendulumRegime regime : {PendulumRegime::kOscillating, PendulumRegime::kRotating}) {
    for (double k : {0.0, 0.6, 1.0 - 1e-8}) {
      ElasticaParameters p;
      p.regime = regime;
      p.rate = regime == PendulumRegime::kOscillating ? 1.3 : -0.9;
      p.modulus = k;
      p.heading_w = 0.4;
      const Elastica e(p);
      const Eigen::Vector2d t0 = e.Tangent(0.0);
      const double kappa0 = e.Curvature(0.0);
      for (double s : {1e-300, -1e-300, 4e-310, -1e-160, 1e-30}) {
        const std::string what =
            ToString(regime) + " k " + std::to_string(k) + " s " + std::to_string(std::log10(std::abs(s)));
        EXPECT_LT((e.Tangent(s) - t0).norm(), 1e-15) << what;
        EXPECT_NEAR(e.Curvature(s), kappa0, 1e-15) << what;
        EXPECT_NEAR(e.Heading(s), e.Heading(0.0), 1e-15) << what;
        // A subnormal s keeps ~14 significant digits of s times the quadrature weights.
        EXPECT_LT((e.Position(s) / s - t0).norm(), std::abs(s) < 1e-300 ? 1e-12 : 1e-15) << what;
      }
    }
  }
}

namespace {

// K(k) and E(k) in long double (64-bit mantissa) by the arithmetic-geometric mean, independent of
// Carlson's forms: K = pi / (2 AGM(1, k')), E = K (1 - sum_n 2^(n-1) c_n^2), c_0 = k,
// c_(n+1) = (a_n - b_n) / 2 (Abramowitz and Stegun 17.6.3-4), with k'^2 = (1 - k)(1 + k) (exact
// in long double for a double k near 1).
struct LongDoubleKE {
  long double kk, ee;
};

LongDoubleKE AgmKE(long double k, long double kc) {
  long double a = 1.0L, b = kc, c = k, sum = 0.5L * k * k, weight = 0.5L;
  for (int i = 0; i < 40 && c != 0.0L; ++i) {
    c = 0.5L * (a - b);
    const long double next = 0.5L * (a + b);
    b = std::sqrt(a * b);
    a = next;
    weight *= 2.0L;
    sum += weight * c * c;
  }
  const long double kk = 3.14159265358979323846264338327950288L / (2.0L * a);
  return {kk, kk * (1.0L - sum)};
}

}  // namespace

TEST(Elastica, HalfPeriodParityMatchesFmod) {
  // The sign flip of odd half periods (Position, the closed rolling): IsOddInteger(m) against
  // std::fmod(m, 2) != 0 for the integer-valued m the reductions produce.
  for (double m : {0.0,
                   -0.0,
                   1.0,
                   -1.0,
                   2.0,
                   -3.0,
                   7.0,
                   1e6 + 1,
                   -(1e6 + 1),
                   9007199254740991.0,
                   9007199254740992.0,
                   -9007199254740990.0,
                   1e300,
                   -1e300}) {
    EXPECT_EQ(internal::IsOddInteger(m), std::fmod(m, 2.0) != 0.0) << m;
  }
  EXPECT_TRUE(internal::IsOddInteger(9007199254740991.0));  // 2^53 - 1
  EXPECT_FALSE(internal::IsOddInteger(-4.0));
}

TEST(Elastica, ShortArcPositionsMatchAnEightPointQuadratureOfTheTangent) {
  // Below |rate s| = 2e-4 (the searches' finite-difference arcs) Position uses the 2-point Gauss
  // rule, below 0.05 the 8-point rule, above the closed form: all agree with an 8-point
  // Gauss-Legendre quadrature of Tangent() written here (error O((rate s)^16)), at phases that
  // put s = 0 anywhere in the period, to a few ulps of |s| (a 2-point rule up to |rate s| = 0.05
  // would be off by ~90 ulps at 3e-3, a node off by 1e-4 by ~1e4 ulps at 1.9e-4).
  const double nodes[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
  const double weights[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
  for (PendulumRegime regime : {PendulumRegime::kOscillating, PendulumRegime::kRotating}) {
    for (double phase : {0.0, 0.7, 2.9, -5.0}) {
      ElasticaParameters p;
      p.regime = regime;
      p.rate = regime == PendulumRegime::kOscillating ? 1.7 : -2.4;
      p.modulus = 0.93;
      p.phase = phase;
      p.heading_w = 0.4;
      const Elastica e(p);
      for (double du : {3e-7, -1e-5, 1.9e-4, 2.1e-4, -3e-3, 0.049, 0.06}) {
        const double s = du / p.rate, half = 0.5 * s;
        Eigen::Vector2d expected = Eigen::Vector2d::Zero();
        for (int i = 0; i < 4; ++i)
          expected += half * weights[i] * (e.Tangent(half * (1 - nodes[i])) + e.Tangent(half * (1 + nodes[i])));
        // The quadratures see the tangent's own rounding (<= ~4 eps here); the closed form at
        // |rate s| = 0.06 divides an O(rate s) difference by the rate (~50 eps: why 0.05).
        const double tol = (std::abs(du) < 0.05 ? 8.0 : 64.0) * std::numeric_limits<double>::epsilon() * std::abs(s);
        EXPECT_LT((e.Position(s) - expected).norm(), tol) << ToString(regime) << " " << phase << " " << du;
      }
    }
  }
}

TEST(Elastica, PeriodAndDriftAreAccurateNearTheSeparatrix) {
  // Boost's ellint_1(k) / ellint_d(k) form 1 - k^2 and put K off by ~3e-10 at k = 1 - 1e-8 (and
  // by ~1e-5 relative at k = 1 - 1e-12); the Carlson forms with k'^2 = (1 - k)(1 + k) do not.
  // Reference: the long double AGM above, itself checked by Legendre's relation
  // E K' + E' K - K K' = pi / 2 (K', E' at the complementary modulus k').
  const long double pi = 3.14159265358979323846264338327950288L;
  for (double k : {1.0 - 1e-8, 1.0 - 1e-12, 0.999, 0.5}) {
    const long double kd = k, kc2 = (1.0L - kd) * (1.0L + kd), kc = std::sqrt(kc2);
    const LongDoubleKE ref = AgmKE(kd, kc), comp = AgmKE(kc, kd);
    ASSERT_LT(std::abs(ref.ee * comp.kk + comp.ee * ref.kk - ref.kk * comp.kk - pi / 2), 1e-16L) << k;
    const long double dd = (ref.kk - ref.ee) / (kd * kd);  // D = (K - E) / k^2
    for (double rate : {0.7, -2.3}) {
      ElasticaParameters p;
      p.rate = rate;
      p.modulus = k;
      p.phase = 0.2;
      p.heading_w = M_PI / 2;  // pendulum frame = plane: the drift is along x
      p.regime = PendulumRegime::kOscillating;
      const Elastica osc(p);
      const long double b = std::abs(rate);
      const double period_osc = static_cast<double>(4.0L * ref.kk / b);
      const double drift_osc = static_cast<double>((8.0L * ref.ee - 4.0L * ref.kk) / b);  // Love, section 263
      EXPECT_NEAR(osc.Period(), period_osc, 4e-15 * period_osc) << k << " " << rate;
      EXPECT_NEAR(osc.DriftPerPeriod().x(), drift_osc, 4e-15 * period_osc) << k << " " << rate;
      EXPECT_NEAR(osc.DriftPerPeriod().y(), 0.0, 1e-15 * period_osc);  // cos(pi/2) = 6e-17
      p.regime = PendulumRegime::kRotating;
      const Elastica rot(p);
      const double period_rot = static_cast<double>(2.0L * ref.kk / b);
      const double drift_rot = static_cast<double>((2.0L * ref.kk - 4.0L * dd) / b);
      EXPECT_NEAR(rot.Period(), period_rot, 4e-15 * period_rot) << k << " " << rate;
      EXPECT_NEAR(rot.DriftPerPeriod().x(), drift_rot, 4e-15 * period_rot) << k << " " << rate;
      // The closed-form position over whole periods agrees with the drift (same K in the
      // argument reduction modulo 4K and in D).
      EXPECT_LT((osc.Position(3.0 * osc.Period()) - 3.0 * osc.DriftPerPeriod()).norm(), 1e-13 * period_osc) << k;
      EXPECT_LT((rot.Position(3.0 * rot.Period()) - 3.0 * rot.DriftPerPeriod()).norm(), 1e-13 * period_rot) << k;
    }
  }
}

TEST(Elastica, IncompleteIntegralsAreAccurateNearTheSeparatrix) {
  // F(phi, k) and D(phi, k) at k = 1 - 1e-12 against their complete values at phi = pi/2 and
  // against F(phi, 1) = atanh(sin phi), D(phi, 1) = atanh(sin phi) - sin phi (k'^2 = 2e-12 moves
  // them by O(k'^2 log) only far from pi/2), and the complete values against the long double AGM.
  const double k = 1.0 - 1e-12;
  const double kc2 = internal::OneMinusSquare(k);
  const long double kd = k;
  const LongDoubleKE ref = AgmKE(kd, std::sqrt((1.0L - kd) * (1.0L + kd)));
  EXPECT_NEAR(internal::CompleteEllipticK(k), static_cast<double>(ref.kk), 4e-15 * static_cast<double>(ref.kk));
  const double dd = static_cast<double>((ref.kk - ref.ee) / (kd * kd));
  EXPECT_NEAR(internal::CompleteEllipticD(k), dd, 4e-15 * dd);
  EXPECT_NEAR(
      internal::EllipticFSinCos(1.0, 0.0, kc2), static_cast<double>(ref.kk), 4e-15 * static_cast<double>(ref.kk));
  EXPECT_NEAR(internal::EllipticDSinCos(1.0, 0.0, kc2), dd, 4e-15 * dd);
  for (double phi : {0.3, 1.0, 1.4}) {
    EXPECT_NEAR(internal::EllipticFSinCos(std::sin(phi), std::cos(phi), kc2), std::atanh(std::sin(phi)), 1e-10) << phi;
    EXPECT_NEAR(
        internal::EllipticDSinCos(std::sin(phi), std::cos(phi), kc2), std::atanh(std::sin(phi)) - std::sin(phi), 1e-10)
        << phi;
  }
}
