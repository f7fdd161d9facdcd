// C^2 interpolation of planar samples (natural cubic spline), used for paths given as samples.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "plateball/export.h"

namespace plateball PLATEBALL_EXPORT {

/// Natural cubic spline through (s_i, p_i), s strictly increasing. By default the knots are the
/// cumulative chord lengths (a good approximation of arc length).
class CubicSpline2d {
 public:
  /// Throws std::invalid_argument (naming the sample index) for fewer than 2 points, non-finite
  /// points, repeated consecutive points or non-increasing knots.
  explicit CubicSpline2d(const std::vector<Eigen::Vector2d>& points);
  /// The natural spline through the points at the given knots (strictly increasing, one per point); throws as the
  /// constructor above.
  CubicSpline2d(const std::vector<double>& knots, const std::vector<Eigen::Vector2d>& points);

  /// The first knot.
  double ParameterBegin() const { return s_.front(); }
  /// The last knot.
  double ParameterEnd() const { return s_.back(); }
  /// The point of the spline at parameter s.
  Eigen::Vector2d Value(double s) const;
  /// The first derivative with respect to s.
  Eigen::Vector2d Derivative(double s) const;
  /// The second derivative with respect to s.
  Eigen::Vector2d SecondDerivative(double s) const;
  /// The knots (one per point).
  const std::vector<double>& knots() const { return s_; }

 private:
  void Build();
  std::size_t Segment(double s) const;
  std::vector<double> s_;
  std::vector<Eigen::Vector2d> p_;
  std::vector<Eigen::Vector2d> m_;  // second derivatives at the knots
};

}  // namespace PLATEBALL_EXPORT
