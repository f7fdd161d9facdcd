// Planned paths p(tau) on the lower plate (section 2.3): smooth curves given analytically or as
// samples, and piecewise-smooth chains of them (the paper's remark: each smooth piece is planned
// on its own).
#pragma once

#include <Eigen/Core>
#include <array>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "plateball/export.h"

namespace plateball PLATEBALL_EXPORT {

class CubicSpline2d;

enum class CurveKind { kLine, kCircle, kEllipse, kLemniscate, kSine, kSamples, kCustom };
/// The value's word as the tools write it in their JSON output and messages.
std::string ToString(CurveKind kind);

/// One smooth piece p(tau), tau in [Begin(), End()], with exact first and second derivatives.
/// A circle, ellipse or lemniscate with tau_end < tau_begin is traversed backwards; its curve
/// parameter is then s = -tau, increasing from -tau_begin to -tau_end (reversed() is true), and
/// Value, Derivative, partitions and bounds use s.
/// The factories validate every value (std::invalid_argument naming the field) and reject a
/// curve whose speed |p'| vanishes anywhere (checked on a fine grid).
class SmoothCurve {
 public:
  /// p = from + tau (to - from), tau in [0, 1].
  static SmoothCurve Line(const Eigen::Vector2d& from, const Eigen::Vector2d& to);
  /// p = center + radius (cos tau, sin tau).
  static SmoothCurve Circle(const Eigen::Vector2d& center, double radius, double tau_begin, double tau_end);
  /// p = center + Rot(rotation) (a cos tau, b sin tau) with (a, b) = semi_axes.
  static SmoothCurve Ellipse(const Eigen::Vector2d& center,
                             const Eigen::Vector2d& semi_axes,
                             double rotation,
                             double tau_begin,
                             double tau_end);
  /// Lemniscate of Bernoulli of half-width `scale`:
  /// p = center + Rot(rotation) scale (cos tau, sin tau cos tau) / (1 + sin^2 tau).
  static SmoothCurve Lemniscate(
      const Eigen::Vector2d& center, double scale, double rotation, double tau_begin, double tau_end);
  /// p = from + Rot(rotation) (tau, amplitude sin(2 pi tau / wavelength)), tau in [0, length].
  static SmoothCurve Sine(
      const Eigen::Vector2d& from, double rotation, double length, double amplitude, double wavelength);
  /// Natural C^2 cubic spline through the samples, tau = cumulative chord length.
  static SmoothCurve Samples(const std::vector<Eigen::Vector2d>& points);
  /// Any analytic curve given by its value and first and second derivatives on [tau_begin, tau_end]
  /// (e.g. an optimal path of the isoparallel problem, elastica.h). The functions must be finite
  /// there; the speed check applies.
  using CurveFunction = std::function<Eigen::Vector2d(double)>;
  /// A curve from its value and derivative functions (see CurveFunction).
  static SmoothCurve Custom(
      CurveFunction value, CurveFunction derivative, CurveFunction second_derivative, double tau_begin, double tau_end);

  /// Which kind of curve this is.
  CurveKind kind() const { return kind_; }
  /// True when the curve runs backwards (Reversed()).
  bool reversed() const { return reversed_; }
  /// The first parameter tau_begin.
  double Begin() const { return tau_begin_; }
  /// The last parameter tau_end.
  double End() const { return tau_end_; }
  /// The point p(tau).
  Eigen::Vector2d Value(double tau) const;
  /// p'(tau).
  Eigen::Vector2d Derivative(double tau) const;
  /// p''(tau).
  Eigen::Vector2d SecondDerivative(double tau) const;
  /// {|p'(tau)|, |p''(tau)|}, equal to Derivative(tau).norm() and SecondDerivative(tau).norm()
  /// but with one sine and cosine on a circle or an ellipse (the bounds sample them per segment).
  std::array<double, 2> DerivativeNorms(double tau) const;
  /// p(tau_begin).
  Eigen::Vector2d StartPoint() const { return Value(tau_begin_); }
  /// p(tau_end).
  Eigen::Vector2d EndPoint() const { return Value(tau_end_); }
  /// Arc length between parameters a and b (negative for b < a): adaptive Gauss-Kronrod (G15/K31)
  /// with an error estimate on panels where |p'| is smooth, accurate to about 1e-12 relative.
  double ArcLength(double a, double b) const;
  /// The arc length from tau_begin to tau_end.
  double Length() const { return ArcLength(tau_begin_, tau_end_); }

 private:
  SmoothCurve() = default;
  void CheckSpeed(const std::string& field) const;
  std::vector<double> PanelBreaks(double a, double b) const;  // ArcLength's panels, a to b
  double PanelWidth() const;                                  // their width (infinite: none)
  void SetRange(double tau_begin, double tau_end);
  Eigen::Vector2d RawValue(double tau) const;
  Eigen::Vector2d RawDerivative(double tau) const;
  Eigen::Vector2d RawSecondDerivative(double tau) const;
  bool reversed_ = false;
  CurveKind kind_ = CurveKind::kLine;
  Eigen::Vector2d origin_ = Eigen::Vector2d::Zero();  // from / center
  Eigen::Vector2d vec_ = Eigen::Vector2d::Zero();     // to - from, or semi-axes
  Eigen::Matrix2d rot_ = Eigen::Matrix2d::Identity();
  double scale_ = 1.0;       // radius, lemniscate scale, sine amplitude
  double wavenumber_ = 0.0;  // 2 pi / wavelength
  double tau_begin_ = 0.0;
  double tau_end_ = 1.0;
  std::shared_ptr<const CubicSpline2d> spline_;
  struct CustomFunctions {
    CurveFunction value, derivative, second_derivative;
  };
  std::shared_ptr<const CustomFunctions> custom_;
};

/// A piecewise-smooth planned path: consecutive pieces share their end points (to 1e-9 of the
/// path's size). A smooth path is a chain of one piece.
class Path {
 public:
  /// Throws std::invalid_argument (naming "pieces[i]") for an empty chain or a gap between pieces.
  explicit Path(std::vector<SmoothCurve> pieces);

  /// The pieces, in order.
  const std::vector<SmoothCurve>& pieces() const { return pieces_; }
  /// The number of pieces.
  int PieceCount() const { return static_cast<int>(pieces_.size()); }
  /// The first point of the path.
  Eigen::Vector2d StartPoint() const { return pieces_.front().StartPoint(); }
  /// The last point of the path.
  Eigen::Vector2d EndPoint() const { return pieces_.back().EndPoint(); }
  /// The total arc length.
  double Length() const;

 private:
  std::vector<SmoothCurve> pieces_;
};

}  // namespace PLATEBALL_EXPORT
