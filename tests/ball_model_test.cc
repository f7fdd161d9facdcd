// Physical parameters -> (alpha, beta, lambda) by hand numbers, and rejection of invalid values
// with the field named.
#include "plateball/ball_model.h"

#include <gtest/gtest.h>

#include "support/test_support.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace plateball {
namespace {

std::string Message(const PhysicalParameters& p) {
  try {
    BallModel::FromPhysical(p);
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "no exception";
}

PhysicalParameters Example() {
  PhysicalParameters p;
  p.inertia_1 = 2.0;
  p.inertia_3 = 3.0;
  p.ball_mass = 1.5;
  p.radius = 0.5;
  p.plate_mass = 0.25;
  return p;
}

TEST(BallModel, PhysicalParametersGiveAlphaBetaLambdaByHand) {
  // M = 1.5 + 2 * 0.25 = 2; alpha = 3/2; beta = M r^2 / I1 = 2 * 0.25 / 2 = 0.25;
  // lambda = (1.5 + 0.25) / (1 + 0.25) = 1.4.
  const BallModel m = BallModel::FromPhysical(Example());
  EXPECT_TRUE(m.has_inertia());
  EXPECT_DOUBLE_EQ(Example().EffectiveMass(), 2.0);
  EXPECT_DOUBLE_EQ(m.alpha(), 1.5);
  EXPECT_DOUBLE_EQ(m.beta(), 0.25);
  EXPECT_DOUBLE_EQ(m.lambda(), 1.4);
  // mu = 2E / (I1 + M r^2) = 6 / 2.5.
  EXPECT_DOUBLE_EQ(BallModel::EnergyToMu(Example(), 3.0), 2.4);
}

TEST(BallModel, UniformSolidBallHasLambdaOne) {
  // I1 = I3 = 2/5 M r^2: alpha = 1, so lambda = 1 whatever beta.
  PhysicalParameters p;
  p.ball_mass = 3.0;
  p.radius = 0.2;
  p.inertia_1 = p.inertia_3 = 0.4 * 3.0 * 0.04;
  p.plate_mass = 7.0;
  EXPECT_NEAR(BallModel::FromPhysical(p).lambda(), 1.0, 1e-15);
  EXPECT_NEAR(BallModel::FromAlphaBeta(0.5, 0.0).lambda(), 0.5, 1e-15);  // beta = 0: lambda = alpha
  EXPECT_NEAR(BallModel::FromAlphaBeta(2.0, 1.0).lambda(), 1.5, 1e-15);
  EXPECT_FALSE(BallModel::FromLambda(2.0).has_inertia());
}

TEST(BallModel, InvalidPhysicalParametersAreRejectedNamingTheField) {
  struct Bad {
    const char* field;
    PhysicalParameters p;
  };
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::vector<Bad> bad;
  auto with = [](auto f) {
    PhysicalParameters p = Example();
    f(p);
    return p;
  };
  bad.push_back({"inertia_1", with([](PhysicalParameters& p) { p.inertia_1 = 0.0; })});
  bad.push_back({"inertia_1", with([&](PhysicalParameters& p) { p.inertia_1 = nan; })});
  bad.push_back({"inertia_3", with([](PhysicalParameters& p) { p.inertia_3 = -1.0; })});
  bad.push_back({"inertia_3", with([](PhysicalParameters& p) { p.inertia_3 = 4.5; })});  // > 2 I1
  bad.push_back({"ball_mass", with([](PhysicalParameters& p) { p.ball_mass = -0.1; })});
  bad.push_back({"plate_mass", with([](PhysicalParameters& p) { p.plate_mass = -2.0; })});
  bad.push_back({"radius", with([](PhysicalParameters& p) { p.radius = 0.0; })});
  bad.push_back({"radius", with([&](PhysicalParameters& p) { p.radius = std::numeric_limits<double>::infinity(); })});
  for (const Bad& b : bad) {
    const std::string m = Message(b.p);
    EXPECT_NE(m.find(std::string("physical.") + b.field + ": value"), std::string::npos) << m;
    EXPECT_FALSE(b.p.Validate().empty());
  }
  EXPECT_TRUE(Example().Validate().empty());
}

TEST(BallModel, InvalidDimensionlessValuesAreRejectedNamingTheField) {
  const auto message = [](auto&& f) { return plateball::testing::InvalidArgumentMessage(f, "no exception"); };
  for (double lambda : {0.0, -1.0, std::nan(""), std::numeric_limits<double>::infinity()})
    EXPECT_NE(message([&] { BallModel::FromLambda(lambda); }).find("lambda: value"), std::string::npos);
  EXPECT_NE(message([] { BallModel::FromAlphaBeta(0.0, 1.0); }).find("alpha: value"), std::string::npos);
  EXPECT_NE(message([] { BallModel::FromAlphaBeta(2.5, 1.0); }).find("alpha: value"), std::string::npos);
  EXPECT_NE(message([] { BallModel::FromAlphaBeta(1.0, -0.5); }).find("beta: value"), std::string::npos);
  EXPECT_NE(message([] { BallModel::EnergyToMu(Example(), -1.0); }).find("kinetic_energy: value"), std::string::npos);
}

}  // namespace
}  // namespace plateball
