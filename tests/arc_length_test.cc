// SmoothCurve::ArcLength (adaptive Gauss-Kronrod) against closed forms on long and oscillating
// paths, and against a second method (Richardson-extrapolated chord sums) on splines.
#include <gtest/gtest.h>

#include <boost/math/special_functions/ellint_2.hpp>
#include <cmath>
#include <vector>

#include "plateball/partition.h"
#include "plateball/path.h"

using namespace plateball;

namespace {
// The quadrature's target (path.h): about 1e-13 relative. The closed forms (Boost.Math) are
// accurate to a few ulps.
constexpr double kRelativeTolerance = 1e-12;

// p(tau) = (tau, A sin(k tau)), k = 2 pi / wavelength: |p'| = sqrt(1 + m cos^2(k tau)), m = (A k)^2.
// With u = k tau, 1 + m cos^2 u = (1 + m) (1 - kappa^2 sin^2 u), kappa^2 = m / (1 + m), so
//   L(a, b) = sqrt(1 + m) / k [E(kappa, k b) - E(kappa, k a)]
// (E the incomplete elliptic integral of the second kind); over n whole wavelengths
//   L = n 4 sqrt(1 + m) E(kappa) / k.
double SineArcLength(double amplitude, double wavelength, double a, double b) {
  const double k = 2.0 * M_PI / wavelength, m = amplitude * amplitude * k * k;
  const double kappa = std::sqrt(m / (1.0 + m));
  return std::sqrt(1.0 + m) / k * (boost::math::ellint_2(kappa, k * b) - boost::math::ellint_2(kappa, k * a));
}

// Second method for a spline: chord sums with `per_knot` chords per knot interval (error
// c h^2 + O(h^4)), Richardson-extrapolated from per_knot and 2 per_knot.
double ChordLength(const SmoothCurve& c, const std::vector<double>& knots, int per_knot) {
  double sum = 0.0;
  for (std::size_t i = 1; i < knots.size(); ++i)
    for (int j = 0; j < per_knot; ++j) {
      const double t0 = knots[i - 1] + (knots[i] - knots[i - 1]) * j / per_knot;
      const double t1 = knots[i - 1] + (knots[i] - knots[i - 1]) * (j + 1) / per_knot;
      sum += (c.Value(t1) - c.Value(t0)).norm();
    }
  return sum;
}

std::vector<Eigen::Vector2d> CircleSamples(double radius, int n) {
  std::vector<Eigen::Vector2d> pts;
  for (int i = 0; i <= n; ++i)
    pts.emplace_back(radius * std::cos(2 * M_PI * i / n), radius * std::sin(2 * M_PI * i / n));
  return pts;
}

std::vector<double> ChordKnots(const std::vector<Eigen::Vector2d>& pts) {
  std::vector<double> knots{0.0};
  for (std::size_t i = 1; i < pts.size(); ++i) knots.push_back(knots.back() + (pts[i] - pts[i - 1]).norm());
  return knots;
}
}  // namespace

// A hard case: a sine of length 200, amplitude 1 and wavelength 0.5 (400 wavelengths). The fixed 64
// Gauss-Legendre panels gave 1607.54 instead of 1622.366 (0.9% short).
TEST(ArcLength, LongShortWavelengthSineMatchesTheEllipticIntegral) {
  const double amplitude = 1.0, wavelength = 0.5;
  const SmoothCurve c = SmoothCurve::Sine({0, 0}, 0.0, 200.0, amplitude, wavelength);
  const double k = 2.0 * M_PI / wavelength, m = amplitude * amplitude * k * k;
  const double whole = 400.0 * 4.0 * std::sqrt(1.0 + m) * boost::math::ellint_2(std::sqrt(m / (1.0 + m))) / k;
  EXPECT_NEAR(whole, SineArcLength(amplitude, wavelength, 0.0, 200.0), 1e-12 * whole);  // the two forms agree
  EXPECT_NEAR(whole, 1622.36572376791, 1e-10);                                          // mpmath.ellipe, 15 digits
  EXPECT_NEAR(c.Length(), whole, kRelativeTolerance * whole);
  // Arbitrary sub-ranges (not whole wavelengths), and the reverse direction.
  for (const auto& [a, b] : {std::pair{0.1, 37.3}, std::pair{12.345, 12.4}, std::pair{3.0, 199.9}}) {
    const double expected = SineArcLength(amplitude, wavelength, a, b);
    EXPECT_NEAR(c.ArcLength(a, b), expected, kRelativeTolerance * expected) << a << " " << b;
    EXPECT_NEAR(c.ArcLength(b, a), -expected, kRelativeTolerance * expected) << a << " " << b;
  }
}

TEST(ArcLength, SinesOfManyShapesMatchTheEllipticIntegral) {
  for (const double amplitude : {0.01, 0.5, 3.0})
    for (const double wavelength : {0.1, 1.0, 7.0}) {
      const SmoothCurve c = SmoothCurve::Sine({1, -2}, 0.4, 50.0, amplitude, wavelength);
      const double expected = SineArcLength(amplitude, wavelength, 0.0, 50.0);
      EXPECT_NEAR(c.Length(), expected, kRelativeTolerance * expected) << amplitude << " " << wavelength;
    }
}

TEST(ArcLength, CirclesAndLinesAreExact) {
  // Ten turns of a circle: radius * angle; any sub-arc too.
  const SmoothCurve circle = SmoothCurve::Circle({3, 4}, 0.7, -1.0, -1.0 + 20 * M_PI);
  EXPECT_NEAR(circle.Length(), 0.7 * 20 * M_PI, kRelativeTolerance * 0.7 * 20 * M_PI);
  EXPECT_NEAR(circle.ArcLength(0.25, 33.0), 0.7 * 32.75, kRelativeTolerance * 0.7 * 32.75);
  const SmoothCurve line = SmoothCurve::Line({1, 2}, {1001, -749});
  EXPECT_NEAR(line.Length(), std::hypot(1000.0, 751.0), kRelativeTolerance * 1250.0);
  EXPECT_NEAR(line.ArcLength(0.2, 0.3), 0.1 * std::hypot(1000.0, 751.0), kRelativeTolerance * 125.0);
}

// The fixed panels were 1.6e-4 to 1.7e-3 off on splines of 100 to 1000 samples: the quadrature
// must give the spline's own length (second method: extrapolated chord sums).
TEST(ArcLength, SplinesMatchExtrapolatedChordSums) {
  for (const int n : {100, 400, 1000}) {
    std::vector<Eigen::Vector2d> pts;
    for (int i = 0; i <= n; ++i) {
      const double t = 10.0 * i / n;
      pts.emplace_back(t, 0.5 * std::sin(3.0 * t) + 0.2 * std::cos(11.0 * t));
    }
    const SmoothCurve c = SmoothCurve::Samples(pts);
    const std::vector<double> knots = ChordKnots(pts);
    const double coarse = ChordLength(c, knots, 256), fine = ChordLength(c, knots, 512);
    const double reference = (4.0 * fine - coarse) / 3.0;
    EXPECT_NEAR(c.Length(), reference, 1e-11 * reference) << n << " samples";
  }
}

TEST(ArcLength, SplinesThroughCircleSamplesConvergeTo2PiR) {
  // A natural spline through N + 1 samples of a full circle of radius r: the length tends to
  // 2 pi r (the error, from the natural end conditions, shrinks with N).
  const double r = 2.5;
  double previous_error = INFINITY;
  for (const int n : {16, 64, 256, 1024}) {
    const double error = std::abs(SmoothCurve::Samples(CircleSamples(r, n)).Length() - 2 * M_PI * r);
    EXPECT_LT(error, previous_error) << n << " samples";
    previous_error = error;
  }
  EXPECT_LT(previous_error, 1e-6 * 2 * M_PI * r);
}

TEST(ArcLength, UniformArcLengthPartitionOfALongSineHasEqualLengths) {
  // Equal pieces of the closed-form length (was up to 0.9% off with the fixed panels).
  const double amplitude = 1.0, wavelength = 0.5;
  const SmoothCurve c = SmoothCurve::Sine({0, 0}, 0.0, 200.0, amplitude, wavelength);
  const int n = 37;
  const std::vector<double> t = UniformArcLengthPartition(c, n);
  const double piece = SineArcLength(amplitude, wavelength, 0.0, 200.0) / n;
  for (int k = 1; k <= n; ++k)
    EXPECT_NEAR(SineArcLength(amplitude, wavelength, t[k - 1], t[k]), piece, 1e-10 * piece) << "piece " << k;
}
