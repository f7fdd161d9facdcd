// The closed-form rolling along an elastica (costate frame and twist, elastica_closed_rolling.h)
// against independent rollings: a Dormand-Prince 5(4) integration of dQ/ds = hat(e3 x x') Q with
// tight step control (the closed-form tangent drives it, nothing of the closed form's costate
// frame or twist), the monodromy P^N of such integrations over one period for long lengths, and
// the sixth-order Magnus tables of elastica_rolling.h at fine steps; plus the group laws, the
// costate transport Q v(s0) = v(s1) and the twist against a quadrature of its unreduced rate
// psi' = <omega, u> - alpha' u3.
#include "elastica_closed_rolling.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "dopri5.h"
#include "elastica_rolling.h"
#include "plateball/isoparallel_families.h"
#include "plateball/so3.h"

using namespace plateball;
using plateball::internal::ElasticaClosedRolling;

namespace {

// dopri5 with relative and absolute tolerance 1e-15 per step: over the lengths below its global
// error stays under ~1e-13 (checked by halving the tolerance while writing the test).
constexpr double kStepTol = 1e-15;
constexpr double kTol = 1e-12;  // closed form vs dopri5

Eigen::Matrix3d DopriRolling(const Elastica& e, double s0, double s1) {
  std::array<double, 9> y{1, 0, 0, 0, 1, 0, 0, 0, 1};  // row-major Q
  auto rhs = [&e](const std::array<double, 9>& q, std::array<double, 9>& dq, double s) {
    const Eigen::Vector2d t = e.Tangent(s);
    const Eigen::Vector3d w(-t.y(), t.x(), 0.0);
    for (int c = 0; c < 3; ++c) {
      const Eigen::Vector3d col(q[c], q[3 + c], q[6 + c]);
      const Eigen::Vector3d d = w.cross(col);
      for (int r = 0; r < 3; ++r) dq[3 * r + c] = d[r];
    }
  };
  const double dir = s1 >= s0 ? 1.0 : -1.0;
  double s = s0, h = 0.01 * dir;
  while (dir * (s1 - s) > 0.0) {
    if (dir * (s + h - s1) > 0.0) h = s1 - s;
    std::array<double, 9> trial = y;
    const double err = internal::DormandPrince5Step<9>(rhs, trial, s, h, kStepTol, kStepTol);
    if (err <= 1.0) {
      y = trial;
      s = (h == s1 - s) ? s1 : s + h;
    }
    h *= std::clamp(0.9 * std::pow(std::max(err, 1e-10), -0.2), 0.2, 5.0);
  }
  Eigen::Matrix3d q;
  q << y[0], y[1], y[2], y[3], y[4], y[5], y[6], y[7], y[8];
  return q;
}

double MaxAbs(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) { return (a - b).cwiseAbs().maxCoeff(); }

ElasticaParameters Params(PendulumRegime regime, double rate, double k, double phase, double heading_w) {
  return {regime, rate, k, phase, heading_w};
}

// Random shapes of both regimes, k up to 0.999, rates of both signs.
std::vector<ElasticaParameters> RandomShapes(int count, unsigned seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<ElasticaParameters> out;
  for (int i = 0; i < count; ++i) {
    const auto regime = i % 2 == 0 ? PendulumRegime::kOscillating : PendulumRegime::kRotating;
    const double k = i % 5 == 4 ? 0.999 : 0.999 * unit(gen);
    const double rate = (unit(gen) < 0.5 ? -1.0 : 1.0) * (0.2 + 1.8 * unit(gen));
    out.push_back(
        Params(regime, rate, (unit(gen) < 0.3 ? -1.0 : 1.0) * k, 6.0 * unit(gen) - 3.0, 6.0 * unit(gen) - 3.0));
  }
  return out;
}

std::string Describe(const ElasticaParameters& p) {
  return ToString(p.regime) + " rate " + std::to_string(p.rate) + " k " + std::to_string(p.modulus) + " phase " +
         std::to_string(p.phase);
}

TEST(ElasticaClosedRollingTest, MatchesDopri5OnRandomShapes) {
  double worst = 0.0;
  for (const ElasticaParameters& p : RandomShapes(20, 7)) {
    const Elastica e(p);
    const ElasticaClosedRolling closed(e);
    const double s0 = 2.0 * p.phase;  // s0 != 0, either sign
    const double length = std::min(1.7 * e.Period(), 12.0);
    const double err = MaxAbs(closed.Rolling(s0, s0 + length), DopriRolling(e, s0, s0 + length));
    worst = std::max(worst, err);
    EXPECT_LT(err, kTol) << Describe(p);
  }
  RecordProperty("worst_error", std::to_string(worst));
}

// G = 1 +- 1e-2, 1e-4, 1e-6 and exactly 1 (oscillating b = 1; rotating a = 2, k = 0.5), from
// s0 at and near a zero of theta, where v_h nearly vanishes and the frame turns fast.
TEST(ElasticaClosedRollingTest, MatchesDopri5NearAndAtUnitG) {
  for (double delta : {1e-2, -1e-2, 1e-4, -1e-4, 1e-6, -1e-6, 0.0}) {
    for (double k : {0.3, 0.8, 0.999}) {
      const double b = std::sqrt(1.0 + delta);
      const double a = std::sqrt(1.0 + delta) / k;
      for (const ElasticaParameters& p : {Params(PendulumRegime::kOscillating, b, k, 0.0, 0.4),
                                          Params(PendulumRegime::kOscillating, -b, k, 1e-7, 0.4),
                                          Params(PendulumRegime::kRotating, a, k, 0.0, -1.0),
                                          Params(PendulumRegime::kRotating, -a, k, 0.3, -1.0)}) {
        const Elastica e(p);
        const ElasticaClosedRolling closed(e);
        for (double s0 : {0.0, 1e-6, 0.9}) {
          const double s1 = s0 + 1.3 * e.Period();
          EXPECT_LT(MaxAbs(closed.Rolling(s0, s1), DopriRolling(e, s0, s1)), kTol)
              << Describe(p) << " delta " << delta << " s0 " << s0;
        }
      }
    }
  }
  // One ulp from G = 1 (n ~ -1e31, the general chart): the frame turns by pi across |w| ~ 1e-16
  // around the zeros of theta; s0 at one (v_h = (0, G - 1)), inside that layer and outside.
  for (double b : {std::nextafter(1.0, 2.0), std::nextafter(1.0, 0.0)}) {
    const Elastica e(Params(PendulumRegime::kOscillating, b, 0.6, 0.0, 0.3));
    const ElasticaClosedRolling closed(e);
    ASSERT_FALSE(closed.UnitChart());
    for (double s0 : {0.0, 1e-16, -3e-16, 1e-6}) {
      const double s1 = s0 + 1.3 * e.Period();
      EXPECT_LT(MaxAbs(closed.Rolling(s0, s1), DopriRolling(e, s0, s1)), kTol) << b << " s0 " << s0;
    }
  }
  // Exactly G = 1 uses the chart theta / 2; these parameters give 1 - G == 0 in floating point.
  for (const ElasticaParameters& p : {Params(PendulumRegime::kOscillating, 1.0, 0.7, 0.2, 0.0),
                                      Params(PendulumRegime::kRotating, 2.0, 0.5, -0.4, 1.0),
                                      Params(PendulumRegime::kRotating, -4.0, 0.25, 0.0, 2.0)}) {
    const Elastica e(p);
    const ElasticaClosedRolling closed(e);
    EXPECT_TRUE(closed.UnitChart()) << Describe(p);
    for (double s0 : {0.0, -0.3}) {
      const double s1 = s0 + 2.5 * e.Period();
      EXPECT_LT(MaxAbs(closed.Rolling(s0, s1), DopriRolling(e, s0, s1)), kTol) << Describe(p);
    }
  }
}

// The rolling is continuous in G across the two charts.
TEST(ElasticaClosedRollingTest, ContinuousAcrossUnitG) {
  const Elastica at_one(Params(PendulumRegime::kOscillating, 1.0, 0.6, 0.5, 0.2));
  const Elastica near_one(Params(PendulumRegime::kOscillating, 1.0 + 1e-10, 0.6, 0.5, 0.2));
  const ElasticaClosedRolling a(at_one), b(near_one);
  ASSERT_TRUE(a.UnitChart());
  ASSERT_FALSE(b.UnitChart());
  for (double s : {0.5, 3.0, 10.0, 40.0}) EXPECT_LT(MaxAbs(a.Rolling(0.2, s), b.Rolling(0.2, s)), 1e-8) << s;
}

// Up to 50 periods: dopri5 over one period from s0 gives the monodromy P = Q(s0, s0 + T), and
// Q(s0, s0 + N T + r) = Q(s0, s0 + r) P^N (the tangent is T-periodic).
TEST(ElasticaClosedRollingTest, LongLengthsMatchMonodromyPowers) {
  for (const ElasticaParameters& p : RandomShapes(6, 11)) {
    const Elastica e(p);
    const ElasticaClosedRolling closed(e);
    const double t = e.Period(), s0 = -1.5 + p.phase;
    const Eigen::Matrix3d monodromy = DopriRolling(e, s0, s0 + t);
    const Eigen::Matrix3d rest = DopriRolling(e, s0, s0 + 0.37 * t);
    Eigen::Matrix3d power = Eigen::Matrix3d::Identity();
    for (int i = 0; i < 50; ++i) power = monodromy * power;
    const Eigen::Matrix3d expected = rest * power;
    // 1e-11: the closed form and the dopri monodromy each carry ~1e-13 per period (k = 0.999:
    // closed 1.2e-13, dopri 3.7e-14 against a Magnus table with steps 0.002, a few ulps of a
    // per-period twist of ~20 rad over a period of ~37); 50 periods give up to 6e-12.
    EXPECT_LT(MaxAbs(closed.Rolling(s0, s0 + 50.37 * t), expected), 1e-11) << Describe(p);
    // Backwards: Q(s1, s0) = Q(s0, s1)^T.
    EXPECT_LT(MaxAbs(closed.Rolling(s0 + 50.37 * t, s0), expected.transpose()), 1e-11) << Describe(p);
  }
}

// Against the Magnus table at fine steps (its error ~1e-10 at 400 steps per period).
TEST(ElasticaClosedRollingTest, MatchesFineMagnusTable) {
  for (const ElasticaParameters& p : RandomShapes(10, 3)) {
    const Elastica e(p);
    const ElasticaClosedRolling closed(e);
    const double length = 6.3 * e.Period();
    const internal::ElasticaRollingTable table(e, length, 400, 0.01);
    ASSERT_TRUE(table.Valid());
    for (double s : {0.37 * e.Period(), 2.0 * e.Period(), length}) {
      EXPECT_LT(MaxAbs(closed.Rolling(0.0, s), table.Rolling(s)), 1e-9) << Describe(p) << " s " << s;
      EXPECT_LT(MaxAbs(closed.Rolling(s), closed.Rolling(0.0, s)), 1e-15) << Describe(p) << " s " << s;
    }
  }
}

TEST(ElasticaClosedRollingTest, GroupLawsAndTransport) {
  for (const ElasticaParameters& p : RandomShapes(10, 5)) {
    const Elastica e(p);
    const ElasticaClosedRolling closed(e);
    const double t = e.Period();
    const double s0 = 0.3 - p.phase, s1 = s0 + 0.8 * t, s2 = s1 + 7.4 * t;
    const Eigen::Matrix3d q01 = closed.Rolling(s0, s1), q12 = closed.Rolling(s1, s2), q02 = closed.Rolling(s0, s2);
    EXPECT_TRUE(IsRotation(q01, 1e-14)) << Describe(p);
    EXPECT_TRUE(IsRotation(q02, 1e-14)) << Describe(p);
    EXPECT_LT(MaxAbs(q12 * q01, q02), 1e-13) << Describe(p);
    EXPECT_LT(MaxAbs(closed.Rolling(s1, s0) * q01, Eigen::Matrix3d::Identity()), 1e-14) << Describe(p);
    EXPECT_LT(MaxAbs(closed.Rolling(s1, s1), Eigen::Matrix3d::Identity()), 1e-15) << Describe(p);
    // Transport of the costate; |v| = V with V^2 = 1 + G^2 + 2E (Elastica's own energy).
    const Eigen::Vector3d v0 = closed.Costate(s0), v2 = closed.Costate(s2);
    EXPECT_LT((q02 * v0 - v2).norm(), 1e-12 * closed.CostateNorm()) << Describe(p);
    const double v_squared = 1.0 + e.G() * e.G() + 2.0 * e.Energy();
    EXPECT_NEAR(v0.squaredNorm(), v_squared, 1e-12 * v_squared) << Describe(p);
    EXPECT_NEAR(closed.CostateNorm() * closed.CostateNorm(), v_squared, 1e-12 * v_squared) << Describe(p);
    // The costate of isoparallel_families.h (from the heading, not the Jacobi functions).
    EXPECT_LT((v2 - ElasticaCostate(e, s2)).norm(), 1e-11 * closed.CostateNorm()) << Describe(p);
    // The frame: a rotation with third column v / V, first column horizontal.
    const Eigen::Matrix3d f = closed.Frame(s1);
    EXPECT_TRUE(IsRotation(f, 1e-14)) << Describe(p);
    EXPECT_LT((f.col(2) - closed.Costate(s1) / closed.CostateNorm()).norm(), 1e-14) << Describe(p);
    EXPECT_LT(std::abs(f(2, 0)), 1e-15) << Describe(p);
  }
}

// psi' = <omega, u> - alpha' u3 with alpha' = g' (1 - G cos theta) / |v_h|^2 (before the reduction
// to J and Pi), integrated by composite 8-point Gauss-Legendre quadrature.
double TwistByQuadrature(const Elastica& e, double length) {
  static const double kNodes[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
  static const double kWeights[4] = {0.3626837833783620, 0.3137066458778873, 0.2223810344533745, 0.1012285362903763};
  const double big_g = e.G(), gw = e.parameters().heading_w;
  const double v_norm = std::sqrt(1.0 + big_g * big_g + 2.0 * e.Energy());
  auto rate = [&](double s) {
    const double g = e.Heading(s), gp = e.Curvature(s), c = std::cos(g - gw + M_PI / 2);
    const Eigen::Vector2d vh(big_g * std::cos(gw) + std::sin(g), big_g * std::sin(gw) - std::cos(g));
    return (big_g * c - 1.0) / v_norm - gp * (1.0 - big_g * c) / vh.squaredNorm() * gp / v_norm;
  };
  const int panels = 4000;
  const double h = length / panels;
  double sum = 0.0;
  for (int i = 0; i < panels; ++i) {
    const double mid = (i + 0.5) * h;
    for (int j = 0; j < 4; ++j)
      sum += kWeights[j] * (rate(mid - 0.5 * h * kNodes[j]) + rate(mid + 0.5 * h * kNodes[j]));
  }
  return 0.5 * h * sum;
}

TEST(ElasticaClosedRollingTest, TwistMatchesQuadratureOfItsRate) {
  for (const ElasticaParameters& p : {Params(PendulumRegime::kOscillating, 0.8, 0.7, 0.3, 0.1),
                                      Params(PendulumRegime::kOscillating, -1.7, 0.9, 1.3, 2.0),
                                      Params(PendulumRegime::kOscillating, 1.1, 0.95, -0.4, 0.0),
                                      Params(PendulumRegime::kRotating, 0.9, 0.6, 0.2, -1.0),
                                      Params(PendulumRegime::kRotating, -1.3, 0.95, 2.0, 0.5),
                                      Params(PendulumRegime::kRotating, 1.5, 0.0, 0.1, 0.0)}) {
    const Elastica e(p);
    const ElasticaClosedRolling closed(e);
    const double length = 3.4 * e.Period();
    EXPECT_NEAR(closed.Twist(length), TwistByQuadrature(e, length), 1e-11) << Describe(p);
  }
}

// Straight lines (rate 0; oscillating k = 0, including G = 1 where the costate vanishes) and
// circles (rotating k = 0), whose rollings are exponentials / known products.
TEST(ElasticaClosedRollingTest, StraightLinesAndCircles) {
  for (const ElasticaParameters& p : {Params(PendulumRegime::kOscillating, 0.0, 0.5, 0.3, 1.0),
                                      Params(PendulumRegime::kRotating, 0.0, 0.2, 0.0, -2.0),
                                      Params(PendulumRegime::kOscillating, 1.0, 0.0, 0.7, 0.5),
                                      Params(PendulumRegime::kOscillating, -0.6, 0.0, 0.1, 0.5)}) {
    const Elastica e(p);
    const ElasticaClosedRolling closed(e);
    EXPECT_TRUE(closed.IsStraight());
    const Eigen::Vector2d t = e.Tangent(0.0);
    EXPECT_LT(MaxAbs(closed.Rolling(-1.0, 5.0), ExpSO3(6.0 * Eigen::Vector3d(-t.y(), t.x(), 0.0))), 1e-15);
  }
  // Circle of curvature 2a: in the frame turning with the tangent the angular velocity is the
  // constant omega(0) - 2a e3, so Q(0, s) = Rz(2 a s) exp(s hat(omega(0) - 2a e3)).
  for (double a : {0.4, -1.2, 3.0}) {
    const Elastica e(Params(PendulumRegime::kRotating, a, 0.0, 0.3, 0.7));
    const ElasticaClosedRolling closed(e);
    const Eigen::Vector2d t = e.Tangent(0.0);
    for (double s : {0.5, 7.0, 60.0}) {
      const Eigen::Matrix3d expected = RotationZ(2.0 * a * s) * ExpSO3(s * Eigen::Vector3d(-t.y(), t.x(), -2.0 * a));
      EXPECT_LT(MaxAbs(closed.Rolling(0.0, s), expected), 1e-12 * std::max(1.0, std::abs(a * s))) << a << " " << s;
    }
  }
}

// k to within 1e-12 of the separatrix, both regimes, against dopri5, over w = rate s + u0 in
// [-1.9 K, 1.9 K] (through both turning points w = +-K, where dn = k' is tiny and am is near
// +-pi/2). The range stays inside |w| < 2K, where Elastica::Tangent does not reduce w by its
// K(k) (Boost's ellint_1, which forms 1 - k^2: K is off by ~3e-10 at k = 1 - 1e-8).
TEST(ElasticaClosedRollingTest, MatchesDopri5NearTheSeparatrix) {
  for (double k : {1.0 - 1e-4, 1.0 - 1e-8, 1.0 - 1e-12}) {
    for (const ElasticaParameters& p : {Params(PendulumRegime::kOscillating, 0.7, k, 0.4, 0.0),
                                        Params(PendulumRegime::kRotating, -0.8, k, 1.0, 1.0)}) {
      const Elastica e(p);
      const ElasticaClosedRolling closed(e);
      const double quarter = p.regime == PendulumRegime::kOscillating ? e.Period() / 4 : e.Period() / 2;  // K / |rate|
      const double s0 = (-1.9 * quarter * std::abs(p.rate) - p.phase) / p.rate;
      const double s1 = (1.9 * quarter * std::abs(p.rate) - p.phase) / p.rate;
      EXPECT_LT(MaxAbs(closed.Rolling(s0, s1), DopriRolling(e, s0, s1)), kTol) << Describe(p);
    }
  }
}

// Parameters over many decades (rates 1e-12 to 1e12, k = 0 to one ulp below 1, G = 1 exactly,
// phases and arc lengths up to 1e6): always a rotation, never NaN, never an exception.
TEST(ElasticaClosedRollingTest, RotationOverManyDecades) {
  std::mt19937 gen(1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  auto sign = [&] { return unit(gen) < 0.5 ? -1.0 : 1.0; };
  for (int i = 0; i < 3000; ++i) {
    ElasticaParameters p;
    p.regime = unit(gen) < 0.5 ? PendulumRegime::kOscillating : PendulumRegime::kRotating;
    p.modulus = i % 7 == 0 ? 0.0 : i % 3 == 0 ? std::max(0.0, 1.0 - std::pow(10.0, -16.0 * unit(gen))) : unit(gen);
    p.modulus = std::min(p.modulus, std::nextafter(1.0, 0.0));
    p.rate = sign() * std::pow(10.0, 24.0 * unit(gen) - 12.0);
    if (i % 10 == 0) p.rate = p.regime == PendulumRegime::kRotating && p.modulus > 0.0 ? 1.0 / p.modulus : 1.0;
    p.phase = sign() * std::pow(10.0, 8.0 * unit(gen) - 4.0);
    p.heading_w = 7.0 * unit(gen);
    const double s0 = sign() * std::pow(10.0, 12.0 * unit(gen) - 6.0);
    const double s1 = sign() * std::pow(10.0, 12.0 * unit(gen) - 6.0);
    const ElasticaClosedRolling closed{Elastica(p)};
    ASSERT_TRUE(IsRotation(closed.Rolling(s0, s1), 1e-9)) << Describe(p) << " " << s0 << " " << s1;
    ASSERT_TRUE(IsRotation(closed.Rolling(s1), 1e-9)) << Describe(p) << " " << s1;
  }
}

TEST(ElasticaClosedRollingTest, BadInputNamesTheField) {
  const Elastica e(Params(PendulumRegime::kOscillating, 0.9, 0.5, 0.0, 0.0));
  const ElasticaClosedRolling closed(e);
  try {
    closed.Rolling(std::nan(""), 1.0);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& ex) {
    EXPECT_NE(std::string(ex.what()).find("s0"), std::string::npos) << ex.what();
  }
  try {
    closed.Rolling(0.0, 1e308 * 10.0);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& ex) {
    EXPECT_NE(std::string(ex.what()).find("s1"), std::string::npos) << ex.what();
  }
  try {  // finite s, but rate * s overflows
    ElasticaClosedRolling(Elastica(Params(PendulumRegime::kRotating, 1e10, 0.5, 0.0, 0.0))).Rolling(0.0, 1e300);
    FAIL() << "no exception";
  } catch (const std::invalid_argument& ex) {
    EXPECT_NE(std::string(ex.what()).find("s1"), std::string::npos) << ex.what();
  }
  try {  // G = rate^2 would overflow
    ElasticaClosedRolling(Elastica(Params(PendulumRegime::kOscillating, -1e200, 0.5, 0.0, 0.0)));
    FAIL() << "no exception";
  } catch (const std::invalid_argument& ex) {
    EXPECT_NE(std::string(ex.what()).find("rate: value -1e+200"), std::string::npos) << ex.what();
  }
  // Extreme but accepted rates: rotations, never NaN.
  for (double rate : {1e-300, 1e150, -1e150})
    for (auto regime : {PendulumRegime::kOscillating, PendulumRegime::kRotating})
      EXPECT_TRUE(
          IsRotation(ElasticaClosedRolling(Elastica(Params(regime, rate, 0.9, 0.1, 0.0))).Rolling(0.0, 3e-150), 1e-12))
          << rate;
  // The straight line with G = 1 has no costate frame (v = 0), but a rolling.
  const ElasticaClosedRolling line(Elastica(Params(PendulumRegime::kOscillating, 1.0, 0.0, 0.0, 0.0)));
  EXPECT_THROW(line.Frame(0.5), std::invalid_argument);
  EXPECT_THROW(line.Twist(0.5), std::invalid_argument);
  EXPECT_TRUE(IsRotation(line.Rolling(0.0, 0.5), 1e-15));
  // Arguments below ~1e-154 (where JacobiSnCnDn's recursion overflows): continuous, no NaN.
  for (const ElasticaParameters& p : {Params(PendulumRegime::kOscillating, 0.9, 0.5, 0.0, 0.0),
                                      Params(PendulumRegime::kRotating, 2.0, 0.5, 0.0, 0.0)}) {
    const ElasticaClosedRolling c(Elastica{p});
    EXPECT_LT(MaxAbs(c.Rolling(1e-300, 2.0), c.Rolling(0.0, 2.0)), 1e-15);
    EXPECT_LT(MaxAbs(c.Frame(-1e-300), c.Frame(0.0)), 1e-15);
  }
  // Large but finite arguments: a rotation, never NaN.
  EXPECT_TRUE(IsRotation(closed.Rolling(-1e12, 1e12), 1e-12));
}

// The closed-form derivatives of the chord x(s) - x(0) and of Q(0, s) with respect to the rate and
// the modulus (Sensitivity) against central differences of independently built elasticas and
// closed rollings (steps 2e-5 and 1e-5, extrapolated: truncation and round-off ~1e-10), over random shapes
// of both regimes, both rate signs, k from 0.01 to 0.99 and lengths up to three periods (several
// half periods of the twist's Pi); the spin omega from dQ = Q hat(omega).
TEST(ElasticaClosedRollingTest, SensitivityMatchesCentralDifferences) {
  std::mt19937 gen(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int checked = 0;
  double worst = 0.0;
  for (int i = 0; i < 60; ++i) {
    const auto regime = i % 2 == 0 ? PendulumRegime::kOscillating : PendulumRegime::kRotating;
    const double k = 0.01 + 0.98 * unit(gen);
    const double rate = (unit(gen) < 0.5 ? -1.0 : 1.0) * (0.2 + 1.8 * unit(gen));
    const ElasticaParameters p = Params(regime, rate, k, 6.0 * unit(gen) - 3.0, 6.0 * unit(gen) - 3.0);
    const Elastica e(p);
    const ElasticaClosedRolling closed(e);
    const double s = (0.1 + 2.9 * unit(gen)) * e.Period();
    ElasticaClosedRolling::PathSensitivity sens;
    const ElasticaClosedRolling::PathEnd end = closed.Path(e, s);
    EXPECT_EQ(end.chord, e.Position(s)) << Describe(p);  // bit for bit
    EXPECT_EQ(end.q, closed.Rolling(s)) << Describe(p);
    if (!closed.Sensitivity(end, &sens)) {
      // Only the layer |1 - G| < 1e-3 and short arcs are left to the caller among these shapes.
      EXPECT_TRUE(std::abs(1.0 - e.G()) < ElasticaClosedRolling::kSensitivityMinOneMinusG ||
                  std::abs(rate * s) < ElasticaClosedRolling::kSensitivityMinArc)
          << Describe(p);
      continue;
    }
    ++checked;
    const Eigen::Matrix3d q = closed.Rolling(s);
    for (int j = 0; j < 2; ++j) {
      // Central differences at steps h and h/2, Richardson-extrapolated (the derivatives grow
      // like s^n: plain central differences are off by ~1e-6 relative at three periods).
      const auto central = [&](double h, Eigen::Vector2d* chord, Eigen::Vector3d* spin) {
        ElasticaParameters pp = p, pm = p;
        (j == 0 ? pp.rate : pp.modulus) += h;
        (j == 0 ? pm.rate : pm.modulus) -= h;
        const Elastica ep(pp), em(pm);
        *chord = (ep.Position(s) - em.Position(s)) / (2 * h);
        *spin = Vee(q.transpose() * (ElasticaClosedRolling(ep).Rolling(s) - ElasticaClosedRolling(em).Rolling(s)) /
                    (2 * h));
      };
      Eigen::Vector2d chord, chord_half;
      Eigen::Vector3d spin, spin_half;
      central(2e-5, &chord, &spin);
      central(1e-5, &chord_half, &spin_half);
      chord = (4.0 * chord_half - chord) / 3.0;
      spin = (4.0 * spin_half - spin) / 3.0;
      const Eigen::Vector2d chord_a = j == 0 ? sens.chord_rate : sens.chord_modulus;
      const Eigen::Vector3d spin_a = j == 0 ? sens.spin_rate : sens.spin_modulus;
      const double scale = 1.0 + std::max(chord.norm(), spin.norm());
      const double err = std::max((chord_a - chord).norm(), (spin_a - spin).norm()) / scale;
      worst = std::max(worst, err);
      EXPECT_LT(err, 1e-8) << Describe(p) << " s " << s << (j == 0 ? " rate" : " modulus") << " chord "
                           << chord.transpose() << " vs " << chord_a.transpose() << " spin " << spin.transpose()
                           << " vs " << spin_a.transpose();
    }
  }
  EXPECT_GE(checked, 50);
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", worst);
  RecordProperty("worst_error", text);
}

// Where Sensitivity declines (the caller then differences whole paths): straight lines, circles and
// tiny or negative moduli, the layer |1 - G| < 1e-3, short arcs.
TEST(ElasticaClosedRollingTest, SensitivityDeclinesOutsideItsForms) {
  ElasticaClosedRolling::PathSensitivity sens;
  const auto declines = [&sens](const ElasticaParameters& p, double s) {
    const Elastica e(p);
    const ElasticaClosedRolling closed(e);
    return !closed.Sensitivity(closed.Path(e, s), &sens);
  };
  EXPECT_TRUE(declines(Params(PendulumRegime::kOscillating, 0.0, 0.5, 0.3, 0.0), 2.0));         // straight
  EXPECT_TRUE(declines(Params(PendulumRegime::kRotating, 0.7, 0.0, 0.3, 0.0), 2.0));            // circle
  EXPECT_TRUE(declines(Params(PendulumRegime::kOscillating, 0.7, -0.5, 0.3, 0.0), 2.0));        // negative modulus
  EXPECT_TRUE(declines(Params(PendulumRegime::kOscillating, 1.0 + 1e-4, 0.5, 0.3, 0.0), 2.0));  // |1 - G| ~ 2e-4
  EXPECT_TRUE(declines(Params(PendulumRegime::kRotating, 0.7, 0.5, 0.3, 0.0), 0.01));           // short arc
  EXPECT_FALSE(declines(Params(PendulumRegime::kRotating, 0.7, 0.5, 0.3, 0.0), 2.0));
}

}  // namespace
