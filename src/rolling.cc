#include "plateball/rolling.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <stdexcept>

#include "check.h"
#include "dynamics.h"
#include "plateball/cubic_spline.h"
#include "plateball/so3.h"

namespace plateball {
Eigen::Matrix3d RollingReorientation(const PlanarVelocity& velocity,
                                     double a,
                                     double b,
                                     const std::vector<double>& breakpoints,
                                     const IntegrationOptions& options) {
  internal::RequireFinite("a", a);
  internal::RequireFinite("b", b);
  internal::ThrowIfInvalid(options.Validate());
  if (!velocity) internal::ThrowInvalid("velocity", "(empty function)", "a velocity function must be given");
  std::vector<double> knots{a};
  for (double t : breakpoints) {
    internal::RequireFinite("breakpoints", t);
    if ((t - a) * (t - b) < 0) knots.push_back(t);
  }
  std::sort(knots.begin() + 1, knots.end());
  if (b < a) std::reverse(knots.begin() + 1, knots.end());
  knots.push_back(b);
  internal::RowMajor3x3 y{1, 0, 0, 0, 1, 0, 0, 0, 1};
  const internal::RollingRhs rhs{[&velocity](double tau) { return velocity(tau); }};
  for (std::size_t i = 0; i + 1 < knots.size(); ++i) {
    const double h = knots[i + 1] - knots[i];
    if (h == 0) continue;
    internal::IntegrateAdaptive(rhs, y, knots[i], knots[i + 1], h / 16.0, options);
  }
  return ProjectToSO3(internal::MatrixFromRowMajor(y.data()));
}

Eigen::Matrix3d RollAlongSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& q) {
  const Eigen::Vector2d d = q - p;
  return ExpSO3(RollingAngularVelocity(d));
}

Eigen::Matrix3d RollAlongPolyline(const std::vector<Eigen::Vector2d>& points) {
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  for (std::size_t i = 0; i < points.size(); ++i) {
    internal::RequireFinite("points[" + std::to_string(i) + "]", points[i]);
    if (i > 0) r = RollAlongSegment(points[i - 1], points[i]) * r;
  }
  return r;
}

Eigen::Matrix3d RollAlongSamples(const std::vector<Eigen::Vector2d>& points, const IntegrationOptions& options) {
  const CubicSpline2d spline(points);
  const PlanarVelocity v = [&spline](double s) { return spline.Derivative(s); };
  return RollingReorientation(v, spline.ParameterBegin(), spline.ParameterEnd(), spline.knots(), options);
}

}  // namespace plateball
