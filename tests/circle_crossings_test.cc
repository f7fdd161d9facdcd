// The crossings of a circle about the elastica's start, counted with a proof (circle_crossings.h),
// against sign changes on a fine grid of the closed form, against roots bracketed by hand around a
// near-tangency, and against the search table's node count, which misses such a pair.
#include "circle_crossings.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

#include "elastica_rolling.h"
#include "plateball/elastica.h"

using namespace plateball;
using internal::CountCircleCrossings;

namespace {

std::vector<Elastica> Paths() {
  return {Elastica::FromInitialState(0.6, 0.2, 0.9, 0.4),    // oscillating
          Elastica::FromInitialState(0.6, 0.2, 0.9, 1.9),    // rotating
          Elastica::FromInitialState(2.5, -1.0, 0.3, 0.05),  // oscillating, small amplitude
          Elastica::FromInitialState(0.0, 0.0, 0.0, 0.7)};   // circle of radius 1/0.7
}

// Sign changes of |x(s)| - radius on the grid s = i h, i = 1 .. s_end / h.
int GridCount(const Elastica& e, double radius, double s_end, double h) {
  int changes = 0;
  double prev = -radius;
  for (long i = 1; i * h <= s_end; ++i) {
    const double f = e.Position(i * h).norm() - radius;
    if ((f > 0) != (prev > 0)) ++changes;
    prev = f;
  }
  return changes;
}

// A root of x.t (an extremum of |x|) in [a, b] where it changes sign, by bisection.
double ExtremumOfChord(const Elastica& e, double a, double b) {
  const auto g = [&e](double s) { return e.Position(s).dot(e.Tangent(s)); };
  for (int i = 0; i < 200 && b - a > 1e-15; ++i) {
    const double m = 0.5 * (a + b);
    ((g(m) > 0) == (g(a) > 0) ? a : b) = m;
  }
  return 0.5 * (a + b);
}

}  // namespace

// The bound the count rests on: kappa^2 = theta'^2 = 2 (E + G cos theta) <= 2 (E + G), reached
// where the pendulum passes theta = 0 (sampled over two periods).
TEST(CircleCrossings, CurvatureBoundHoldsAndIsReached) {
  for (const Elastica& e : Paths()) {
    const double bound = std::sqrt(2.0 * (e.Energy() + e.G()));
    const double span = std::isfinite(e.Period()) ? 2.0 * e.Period() : 10.0;
    double largest = 0.0;
    for (int i = 0; i <= 20000; ++i) largest = std::max(largest, std::abs(e.Curvature(span * i / 20000)));
    EXPECT_LE(largest, bound * (1 + 1e-12)) << e.Energy();
    EXPECT_GT(largest, bound * (1 - 1e-6)) << e.Energy();
  }
}

// Away from tangencies a grid of 1e-4 sees every crossing: the counts agree, over many radii.
TEST(CircleCrossings, AgreeWithAFineGridAwayFromTangencies) {
  int checked = 0, total = 0;
  for (const Elastica& e : Paths()) {
    for (double radius : {0.3, 0.9, 1.7, 2.5, 4.0}) {
      const double s_end = 15.0;
      const int grid = GridCount(e, radius, s_end, 1e-4);
      // Skip a radius whose grid count changes with the grid (a crossing pair near a tangency).
      if (grid != GridCount(e, radius, s_end, 3e-4)) continue;
      EXPECT_EQ(CountCircleCrossings(e, radius, s_end), grid) << e.Energy() << " " << radius;
      ++checked;
      total += grid;
    }
  }
  EXPECT_GE(checked, 15);
  EXPECT_GE(total, 30) << "the paths must cross their circles";
}

// The end belongs to the interval (0, s_end]: a path ending just past its first crossing has one,
// just before it none; a straight line crosses once.
TEST(CircleCrossings, CountTheEndOfTheInterval) {
  const Elastica e = Paths()[0];
  const internal::ElasticaRollingTable table(e, 15.0, 12, 0.5, 200000, true);
  const std::vector<double> roots = table.Crossings(1.7, 10);
  ASSERT_GE(roots.size(), 2u);
  EXPECT_EQ(CountCircleCrossings(e, 1.7, roots[0] + 1e-9), 1);
  EXPECT_EQ(CountCircleCrossings(e, 1.7, roots[0] - 1e-9), 0);
  EXPECT_EQ(CountCircleCrossings(e, 1.7, roots[1] + 1e-9), 2);
  ElasticaParameters straight;
  straight.heading_w = 0.4;
  EXPECT_EQ(CountCircleCrossings(Elastica(straight), 2.0, 3.0), 1);
  EXPECT_EQ(CountCircleCrossings(Elastica(straight), 2.0, 1.5), 0);
  EXPECT_EQ(CountCircleCrossings(e, 1.7, 0.0), 0);
}

// Just below a local maximum of |x| the circle is crossed twice within ~1e-5: the pair is
// bracketed here by hand (|x| above the radius at the maximum, below it 1e-3 to either side);
// the count sees it, 2 more than just above the maximum, where the search table's nodes (which
// cannot tell) give the same count for both radii.
TEST(CircleCrossings, CountAPairOfCrossingsBetweenTwoNodes) {
  const Elastica e = Paths()[0];
  const double s_end = 15.0;
  // The first local maximum of |x| past s = 1 (a sign change of x.t from + to -).
  double peak = 0.0;
  for (double s = 1.0; s < s_end && peak == 0.0; s += 1e-3)
    if (e.Position(s).dot(e.Tangent(s)) > 0 && e.Position(s + 1e-3).dot(e.Tangent(s + 1e-3)) <= 0)
      peak = ExtremumOfChord(e, s, s + 1e-3);
  ASSERT_GT(peak, 0.0);
  const double top = e.Position(peak).norm();
  const double below = top - 1e-10, above = top + 1e-10;
  ASSERT_GT(e.Position(peak).norm(), below);
  ASSERT_LT(e.Position(peak - 1e-3).norm(), below);
  ASSERT_LT(e.Position(peak + 1e-3).norm(), below);
  EXPECT_EQ(CountCircleCrossings(e, below, s_end), CountCircleCrossings(e, above, s_end) + 2);
  EXPECT_EQ(CountCircleCrossings(e, above, s_end), GridCount(e, above, s_end, 1e-4));
  const internal::ElasticaRollingTable table(e, s_end, 12, 0.5, 200000, true);
  EXPECT_EQ(table.Crossings(below, 100).size(), table.Crossings(above, 100).size()) << "the nodes cannot see the pair";
  // Ending between the two crossings of the pair: one of them.
  EXPECT_EQ(CountCircleCrossings(e, below, peak), CountCircleCrossings(e, above, peak) + 1);
}
