#include "plateball/path.h"

#include <gtest/gtest.h>

#include <boost/math/special_functions/ellint_2.hpp>
#include <cmath>
#include <stdexcept>
#include <string>

#include "plateball/partition.h"
#include "support/test_support.h"

using namespace plateball;

namespace {
// Central differences with step 1e-5 on O(1) curves: truncation ~1e-10, round-off ~1e-11.
constexpr double kFiniteDifferenceTolerance = 1e-7;
// Gauss-Legendre with 64 panels of 8 points on analytic curves.
constexpr double kLengthTolerance = 1e-11;

std::vector<SmoothCurve> AllKinds() {
  return {SmoothCurve::Line({1, 2}, {-3, 0.5}),
          SmoothCurve::Circle({1, -1}, 2.5, 0.3, 4.0),
          SmoothCurve::Ellipse({0.5, 0}, {2, 1}, 0.7, 0, 2 * M_PI),
          SmoothCurve::Lemniscate({0, 1}, 1.5, -0.4, 0, 2 * M_PI),
          SmoothCurve::Sine({0, 0}, 0.2, 5.0, 0.4, 2.0),
          SmoothCurve::Samples({{0, 0}, {1, 0.5}, {2, 0.2}, {3, 1.0}, {4, 0.0}})};
}
}  // namespace

TEST(Path, DerivativesAgreeWithFiniteDifferences) {
  const double h = 1e-5;
  for (const SmoothCurve& c : AllKinds()) {
    for (int i = 1; i < 10; ++i) {
      const double tau = c.Begin() + (c.End() - c.Begin()) * i / 10.0;
      const Eigen::Vector2d d1 = (c.Value(tau + h) - c.Value(tau - h)) / (2 * h);
      const Eigen::Vector2d d2 = (c.Derivative(tau + h) - c.Derivative(tau - h)) / (2 * h);
      EXPECT_LT((d1 - c.Derivative(tau)).norm(), kFiniteDifferenceTolerance) << ToString(c.kind()) << " tau " << tau;
      EXPECT_LT((d2 - c.SecondDerivative(tau)).norm(), kFiniteDifferenceTolerance)
          << ToString(c.kind()) << " tau " << tau;
    }
  }
}

TEST(Path, DerivativeNormsEqualTheNormsOfTheDerivatives) {
  // DerivativeNorms shares one sine and cosine on circles and ellipses (the plan's bound samples);
  // it must give Derivative(tau).norm() and SecondDerivative(tau).norm() on every kind, reversed too.
  std::vector<SmoothCurve> curves = AllKinds();
  curves.push_back(SmoothCurve::Circle({1, -1}, 2.5, 4.0, 0.3));
  curves.push_back(SmoothCurve::Ellipse({0.5, 0}, {2, 1}, 0.7, 2 * M_PI, 0));
  for (const SmoothCurve& c : curves) {
    for (int i = 0; i <= 10; ++i) {
      const double tau = c.Begin() + (c.End() - c.Begin()) * i / 10.0;
      const std::array<double, 2> norms = c.DerivativeNorms(tau);
      EXPECT_DOUBLE_EQ(norms[0], c.Derivative(tau).norm()) << ToString(c.kind()) << " tau " << tau;
      EXPECT_DOUBLE_EQ(norms[1], c.SecondDerivative(tau).norm()) << ToString(c.kind()) << " tau " << tau;
    }
  }
}

TEST(Path, LengthsMatchClosedForms) {
  // Circle arc: radius * angle. Ellipse: 4 a E(e) (complete elliptic integral, Boost.Math).
  // Lemniscate of Bernoulli of half-width s: 2 varpi s, varpi = 2.622057554292119810464839589891.
  EXPECT_NEAR(SmoothCurve::Circle({0, 0}, 2.5, 0.3, 4.0).Length(), 2.5 * 3.7, kLengthTolerance);
  const double e = std::sqrt(1.0 - 0.25);
  EXPECT_NEAR(SmoothCurve::Ellipse({0, 0}, {2, 1}, 0.7, 0, 2 * M_PI).Length(),
              8.0 * boost::math::ellint_2(e),
              kLengthTolerance);
  EXPECT_NEAR(SmoothCurve::Lemniscate({0, 0}, 1.5, 0.0, 0, 2 * M_PI).Length(),
              2.0 * 2.622057554292119810464839589891 * 1.5,
              kLengthTolerance);
  EXPECT_NEAR(SmoothCurve::Line({1, 2}, {4, 6}).Length(), 5.0, kLengthTolerance);
}

TEST(Path, LemniscatePassesThroughItsCentreAndVertices) {
  const SmoothCurve c = SmoothCurve::Lemniscate({1, 1}, 2.0, 0.0, 0, 2 * M_PI);
  EXPECT_LT((c.Value(0) - Eigen::Vector2d(3, 1)).norm(), 1e-15);
  EXPECT_LT((c.Value(M_PI / 2) - Eigen::Vector2d(1, 1)).norm(), 1e-15);
  EXPECT_LT((c.Value(M_PI) - Eigen::Vector2d(-1, 1)).norm(), 1e-15);
  // (x^2 + y^2)^2 = a^2 (x^2 - y^2) about the centre.
  for (double tau : {0.3, 1.1, 2.5, 4.0}) {
    const Eigen::Vector2d q = c.Value(tau) - Eigen::Vector2d(1, 1);
    EXPECT_NEAR(std::pow(q.squaredNorm(), 2), 4.0 * (q.x() * q.x() - q.y() * q.y()), 1e-13);
  }
}

TEST(Path, SamplesOnACircleApproximateItsLength) {
  std::vector<Eigen::Vector2d> pts;
  for (int i = 0; i <= 64; ++i) pts.emplace_back(std::cos(i * M_PI / 64), std::sin(i * M_PI / 64));
  const SmoothCurve c = SmoothCurve::Samples(pts);
  EXPECT_NEAR(c.Length(), M_PI, 1e-4);  // spline vs circle: O(h^2) at the natural ends
  EXPECT_LT((c.StartPoint() - pts.front()).norm(), 1e-15);
  EXPECT_LT((c.EndPoint() - pts.back()).norm(), 1e-15);
}

TEST(Path, ReversedRangeTraversesTheCurveBackwards) {
  // Clockwise unit circle from angle 0 to -pi/2: parameter s = -tau in [0, pi/2].
  const SmoothCurve c = SmoothCurve::Circle({0, 0}, 1, 0.0, -M_PI / 2);
  EXPECT_TRUE(c.reversed());
  EXPECT_EQ(c.Begin(), 0.0);
  EXPECT_NEAR(c.End(), M_PI / 2, 1e-15);
  EXPECT_LT((c.EndPoint() - Eigen::Vector2d(0, -1)).norm(), 1e-15);
  EXPECT_LT((c.Derivative(0.0) - Eigen::Vector2d(0, -1)).norm(), 1e-15);  // moving clockwise
  EXPECT_NEAR(c.Length(), M_PI / 2, 1e-12);
  const double h = 1e-5, s = 0.7;
  EXPECT_LT(((c.Value(s + h) - c.Value(s - h)) / (2 * h) - c.Derivative(s)).norm(), kFiniteDifferenceTolerance);
  EXPECT_LT(((c.Derivative(s + h) - c.Derivative(s - h)) / (2 * h) - c.SecondDerivative(s)).norm(),
            kFiniteDifferenceTolerance);
}
