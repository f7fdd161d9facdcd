#include "circle_crossings.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace plateball::internal {
namespace {

struct Sample {
  double s, f, df, norm;  // arc length, f = |x|^2 - r^2, f' = 2 x.t, |x|
};

struct Counter {
  const Elastica& e;
  double r2;
  double kappa_max;

  Sample At(double s) const {
    const Eigen::Vector2d x = e.Position(s);
    return {s, x.squaredNorm() - r2, 2.0 * x.dot(e.Tangent(s)), x.norm()};
  }

  // The interval of t >= 0 over which f0 + d0 t - m t^2 / 2 keeps f0's sign (f0 != 0): its length.
  static double KeepsSign(double f0, double d0, double m) {
    const double sign = f0 > 0 ? 1.0 : -1.0;
    const double f = sign * f0, d = sign * d0;
    return (d + std::sqrt(d * d + 2.0 * m * f)) / m;
  }

  int Count(const Sample& a, const Sample& b) const {
    const double width = b.s - a.s;
    const int change = (a.f > 0) != (b.f > 0) ? 1 : 0;
    const double m = 2.0 * (1.0 + kappa_max * (0.5 * (a.norm + b.norm + width)));
    if ((a.df > 0) == (b.df > 0) && std::abs(a.df) + std::abs(b.df) > m * width) return change;
    if (!change && a.f != 0.0 && b.f != 0.0 && KeepsSign(a.f, a.df, m) + KeepsSign(b.f, -b.df, m) > width) return 0;
    if (width <= 1e-13 * (1.0 + b.s)) return change;
    const Sample mid = At(a.s + 0.5 * width);
    return Count(a, mid) + Count(mid, b);
  }
};

}  // namespace

int CountCircleCrossings(const Elastica& e, double radius, double s_end) {
  if (!(s_end > 0.0)) return 0;
  const double kappa_max = std::sqrt(std::max(0.0, 2.0 * (e.Energy() + e.G())));
  const Counter counter{e, radius * radius, kappa_max};
  return counter.Count({0.0, -radius * radius, 0.0, 0.0}, counter.At(s_end));
}

}  // namespace plateball::internal
