#include "plateball/partition.h"

#include <gtest/gtest.h>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

#include "plateball/task_adapters.h"
#include "support/test_support.h"

using namespace plateball;

namespace {
std::string ErrorOf(const std::function<void()>& f) { return plateball::testing::InvalidArgumentMessage(f, ""); }
}  // namespace

TEST(Partition, UniformParameterHasEqualSteps) {
  const SmoothCurve c = SmoothCurve::Circle({0, 0}, 1, 0.5, 2.5);
  const auto t = UniformParameterPartition(c, 8);
  ASSERT_EQ(t.size(), 9u);
  EXPECT_EQ(t.front(), 0.5);
  EXPECT_EQ(t.back(), 2.5);
  for (std::size_t k = 1; k < t.size(); ++k) EXPECT_NEAR(t[k] - t[k - 1], 0.25, 1e-15);
  EXPECT_NEAR(ParameterNorm(t), 0.25, 1e-15);
  EXPECT_NEAR(PointNorm(c, t), 2 * std::sin(0.125), 1e-15);  // chord of a unit circle
}

TEST(Partition, UniformArcLengthHasEqualLengthsByAnIndependentQuadrature) {
  const SmoothCurve c = SmoothCurve::Ellipse({0, 0}, {3, 1}, 0.2, 0, 2 * M_PI);
  const auto t = UniformArcLengthPartition(c, 12);
  auto speed = [&](double tau) { return c.Derivative(tau).norm(); };
  double first = -1;
  for (std::size_t k = 1; k < t.size(); ++k) {
    const double len = boost::math::quadrature::gauss_kronrod<double, 61>::integrate(speed, t[k - 1], t[k], 10, 1e-14);
    if (first < 0) first = len;
    EXPECT_NEAR(len, first, 1e-11) << "segment " << k;
  }
}

TEST(Partition, BadPartitionsNameWhatIsWrong) {
  const SmoothCurve c = SmoothCurve::Circle({0, 0}, 1, 0, 2 * M_PI);
  EXPECT_NE(ErrorOf([&] { UniformParameterPartition(c, 0); }).find("at least 2 points"), std::string::npos);
  EXPECT_NE(ErrorOf([&] { ExplicitPartition(c, {0.0}); }).find("at least 2 points"), std::string::npos);
  // A full circle in one step: p(0) = p(2 pi).
  EXPECT_NE(ErrorOf([&] {
              ExplicitPartition(c, {0.0, 2 * M_PI});
            }).find("1e-12 x the path length apart"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] {
              ExplicitPartition(c, {0.0, 1.0, 1.0, 2 * M_PI});
            }).find("partition.taus[2]"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] {
              ExplicitPartition(c, {0.1, 2 * M_PI});
            }).find("start of the parameter interval"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] { ExplicitPartition(c, {0.0, NAN, 2 * M_PI}); }).find("must be finite"), std::string::npos);
  const Path path({SmoothCurve::Line({0, 0}, {1, 0}), SmoothCurve::Line({1, 0}, {1, 1})});
  EXPECT_NE(ErrorOf([&] { PartitionFromSpec(ExplicitTaus{{0, 1}}, path); }).find("single-piece"), std::string::npos);
  EXPECT_NE(ErrorOf([&] { MakePartition(path, {UniformParameter{0}}); }).find("partition.n"), std::string::npos);
}

TEST(Partition, PiecewisePathsGetOnePartitionPerPiece) {
  const Path path({SmoothCurve::Line({0, 0}, {1, 0}), SmoothCurve::Line({1, 0}, {1, 3})});
  const auto parts = MakePartition(path, {UniformArcLength{4}});
  ASSERT_EQ(parts.size(), 2u);
  EXPECT_EQ(parts[0].size(), 5u);
  EXPECT_EQ(parts[1].size(), 5u);
}

TEST(Partition, RulesAreAClosedSetOneRulePerPieceOrOneForAll) {
  const Path path({SmoothCurve::Line({0, 0}, {1, 0}), SmoothCurve::Line({1, 0}, {1, 3})});
  EXPECT_EQ(ToString(PartitionRule{UniformParameter{}}), "uniform_parameter");
  EXPECT_EQ(ToString(PartitionRule{UniformArcLength{}}), "uniform_arc_length");
  EXPECT_EQ(ToString(PartitionRule{ExplicitTaus{}}), "explicit");
  const auto mixed = MakePartition(path, {UniformParameter{2}, ExplicitTaus{{0.0, 0.25, 1.0}}});
  ASSERT_EQ(mixed.size(), 2u);
  EXPECT_EQ(mixed[0], (std::vector<double>{0.0, 0.5, 1.0}));
  EXPECT_EQ(mixed[1], (std::vector<double>{0.0, 0.25, 1.0}));
  const std::string e = ErrorOf([&] {
    MakePartition(path, {UniformParameter{2}, UniformParameter{2}, UniformParameter{2}});
  });
  EXPECT_NE(e.find("rule count"), std::string::npos) << e;
  EXPECT_NE(ErrorOf([&] {
              MakePartition(path, {UniformParameter{2}, ExplicitTaus{{0.0, 2.0}}});
            }).find("partition[1].taus"),
            std::string::npos);
}
