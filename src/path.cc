#include "plateball/path.h"

#include <algorithm>
#include <array>
#include <boost/math/quadrature/gauss.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "check.h"
#include "plateball/cubic_spline.h"

namespace plateball {
namespace {

using internal::RequireFinite;
using internal::ThrowInvalid;

Eigen::Matrix2d Rot(double a) {
  Eigen::Matrix2d r;
  r << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  return r;
}

// Largest |tau_begin|, |tau_end| of a circle, ellipse or lemniscate (cos and sin of tau): doubles
// near 10^6 are 1.2e-10 apart, so a larger parameter places the points only to worse than 1e-10 of
// the curve's size (and merges partition points); 10^6 is already 1.6 x 10^5 laps.
constexpr double kMaxCurveParameter = 1e6;

void RequireRange(double tau_begin, double tau_end) {
  RequireFinite("tau_begin", tau_begin);
  RequireFinite("tau_end", tau_end);
  for (const auto& [name, tau] : {std::pair<const char*, double>{"tau_begin", tau_begin}, {"tau_end", tau_end}})
    if (!(std::abs(tau) <= kMaxCurveParameter))
      ThrowInvalid(name, tau, "must be in [-1e6, 1e6] (cos and sin of a larger parameter lose their accuracy)");
  if (tau_end == tau_begin) ThrowInvalid("tau_end", tau_end, "must differ from tau_begin (an empty curve)");
}

// ArcLength on one smooth panel: Gauss-Kronrod G15/K31 (Boost.Math's nodes and weights), the
// panel halved until the error estimate |K31 - G15| (which bounds the error of the far more
// accurate K31 generously) is below kArcLengthTolerance of the panel's own length or below the
// round-off floor, at most kArcLengthMaxDepth times.
constexpr double kArcLengthTolerance = 1e-12;
constexpr unsigned kArcLengthMaxDepth = 8;

struct PanelQuadrature {
  double length = 0.0;  // K31
  double error = 0.0;   // |K31 - G15|
  double floor = 0.0;   // round-off in both: below it halving cannot help
};

// The round-off floor: a node lo + h x is rounded by up to eps max(|lo|, |hi|), which moves the
// speed by |speed'| times that (|speed'| estimated from neighbouring nodes); each speed and the sum
// carry a few eps relative more. Far from tau = 0 (e.g. tau = 200 on a sine of wavelength 0.1) this
// floor is above 1e-12 of a short panel's length, and halving such a panel only makes it worse.
template <class Speed>
PanelQuadrature GaussKronrod31(const Speed& speed, double lo, double hi) {
  using Kronrod = boost::math::quadrature::gauss_kronrod<double, 31>;
  using Gauss = boost::math::quadrature::gauss<double, 15>;
  const auto& x = Kronrod::abscissa();  // x[0] = 0 < x[1] < ... < x[15]; even i: the Gauss nodes
  const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
  std::array<double, 31> f{};  // speeds at mid + half * t[j], t ascending
  f[15] = speed(mid);
  double kronrod = f[15] * Kronrod::weights()[0], gauss = f[15] * Gauss::weights()[0];
  for (std::size_t i = 1; i < x.size(); ++i) {
    f[15 + i] = speed(mid + half * x[i]);
    f[15 - i] = speed(mid - half * x[i]);
    kronrod += (f[15 + i] + f[15 - i]) * Kronrod::weights()[i];
    if (i % 2 == 0) gauss += (f[15 + i] + f[15 - i]) * Gauss::weights()[i / 2];
  }
  double slope = 0.0;  // max |d speed / d x| over [-1, 1]
  for (std::size_t j = 0; j + 1 < f.size(); ++j) {
    const double t0 = j < 15 ? -x[15 - j] : x[j - 15], t1 = j + 1 < 15 ? -x[14 - j] : x[j - 14];
    slope = std::max(slope, std::abs(f[j + 1] - f[j]) / (t1 - t0));
  }
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  const double length = half * kronrod;
  const double floor = 8.0 * kEps * (2.0 * std::max(std::abs(lo), std::abs(hi)) * slope + 8.0 * length);
  return {length, half * std::abs(kronrod - gauss), floor};
}

template <class Speed>
double PanelLength(const Speed& speed, double lo, double hi, unsigned depth) {
  const PanelQuadrature q = GaussKronrod31(speed, lo, hi);
  if (depth == 0 || q.error <= std::max(kArcLengthTolerance * q.length, q.floor)) return q.length;
  const double mid = 0.5 * (lo + hi);
  return PanelLength(speed, lo, mid, depth - 1) + PanelLength(speed, mid, hi, depth - 1);
}

// A regular curve: |p'| > 0, checked on a fine grid against the curve's mean speed. `field` is the
// parameter that sets the speed (a radius, a scale), named with its value in the message.
void RequireRegular(const SmoothCurve& c, const std::string& field, const std::string& value_text) {
  constexpr int kGrid = 1024;
  double mean = 0.0, least = INFINITY, at = c.Begin();
  for (int i = 0; i <= kGrid; ++i) {
    const double tau = c.Begin() + (c.End() - c.Begin()) * i / kGrid;
    const double v = c.Derivative(tau).norm();
    if (!std::isfinite(v))
      ThrowInvalid(field,
                   value_text,
                   "the path's speed |p'| at tau = " + internal::FormatNumber(tau) + " is " +
                       internal::FormatNumber(v) + ": must be finite");
    mean += v / (kGrid + 1);
    if (v < least) least = v, at = tau;
  }
  if (!(least > 1e-9 * mean && least > 0.0))
    ThrowInvalid(field,
                 value_text,
                 "the path's speed |p'| at tau = " + internal::FormatNumber(at) + " is " +
                     internal::FormatNumber(least) + ": must be nonzero everywhere");
}

}  // namespace

std::string ToString(CurveKind kind) {
  switch (kind) {
    case CurveKind::kLine:
      return "line";
    case CurveKind::kCircle:
      return "circle";
    case CurveKind::kEllipse:
      return "ellipse";
    case CurveKind::kLemniscate:
      return "lemniscate";
    case CurveKind::kSine:
      return "sine";
    case CurveKind::kSamples:
      return "samples";
    case CurveKind::kCustom:
      return "custom";
  }
  return "unknown";
}

SmoothCurve SmoothCurve::Line(const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
  RequireFinite("from", from);
  RequireFinite("to", to);
  if ((to - from).norm() == 0.0)
    ThrowInvalid("to", to.x(), "equals 'from': a line needs two distinct points (zero speed)");
  SmoothCurve c;
  c.kind_ = CurveKind::kLine;
  c.origin_ = from;
  c.vec_ = to - from;
  c.tau_begin_ = 0.0;
  c.tau_end_ = 1.0;
  return c;
}

SmoothCurve SmoothCurve::Circle(const Eigen::Vector2d& center, double radius, double tau_begin, double tau_end) {
  RequireFinite("center", center);
  internal::RequirePositive("radius", radius);
  RequireRange(tau_begin, tau_end);
  SmoothCurve c;
  c.kind_ = CurveKind::kCircle;
  c.origin_ = center;
  c.scale_ = radius;
  c.SetRange(tau_begin, tau_end);
  RequireRegular(c, "radius", internal::FormatNumber(radius));
  return c;
}

SmoothCurve SmoothCurve::Ellipse(const Eigen::Vector2d& center,
                                 const Eigen::Vector2d& semi_axes,
                                 double rotation,
                                 double tau_begin,
                                 double tau_end) {
  RequireFinite("center", center);
  internal::RequirePositive("semi_axes[0]", semi_axes.x());
  internal::RequirePositive("semi_axes[1]", semi_axes.y());
  RequireFinite("rotation", rotation);
  RequireRange(tau_begin, tau_end);
  SmoothCurve c;
  c.kind_ = CurveKind::kEllipse;
  c.origin_ = center;
  c.vec_ = semi_axes;
  c.rot_ = Rot(rotation);
  c.SetRange(tau_begin, tau_end);
  const int smaller = semi_axes.y() < semi_axes.x() ? 1 : 0;
  RequireRegular(c, "semi_axes[" + std::to_string(smaller) + "]", internal::FormatNumber(semi_axes[smaller]));
  return c;
}

SmoothCurve SmoothCurve::Lemniscate(
    const Eigen::Vector2d& center, double scale, double rotation, double tau_begin, double tau_end) {
  RequireFinite("center", center);
  internal::RequirePositive("scale", scale);
  RequireFinite("rotation", rotation);
  RequireRange(tau_begin, tau_end);
  SmoothCurve c;
  c.kind_ = CurveKind::kLemniscate;
  c.origin_ = center;
  c.scale_ = scale;
  c.rot_ = Rot(rotation);
  c.SetRange(tau_begin, tau_end);
  RequireRegular(c, "scale", internal::FormatNumber(scale));
  return c;
}

SmoothCurve SmoothCurve::Sine(
    const Eigen::Vector2d& from, double rotation, double length, double amplitude, double wavelength) {
  RequireFinite("from", from);
  RequireFinite("rotation", rotation);
  internal::RequirePositive("length", length);
  RequireFinite("amplitude", amplitude);
  internal::RequirePositive("wavelength", wavelength);
  SmoothCurve c;
  c.kind_ = CurveKind::kSine;
  c.origin_ = from;
  c.rot_ = Rot(rotation);
  c.scale_ = amplitude;
  c.wavenumber_ = 2.0 * M_PI / wavelength;
  c.tau_begin_ = 0.0;
  c.tau_end_ = length;
  // |p'| = sqrt(1 + (2 pi amplitude / wavelength)^2 cos^2) >= 1: only an overflow of the ratio fails,
  // blamed on the wavelength when it is below 1, else on the amplitude.
  if (wavelength < 1.0)
    RequireRegular(c, "wavelength", internal::FormatNumber(wavelength));
  else
    RequireRegular(c, "amplitude", internal::FormatNumber(amplitude));
  return c;
}

SmoothCurve SmoothCurve::Samples(const std::vector<Eigen::Vector2d>& points) {
  SmoothCurve c;
  c.kind_ = CurveKind::kSamples;
  c.spline_ = std::make_shared<const CubicSpline2d>(points);
  c.tau_begin_ = c.spline_->ParameterBegin();
  c.tau_end_ = c.spline_->ParameterEnd();
  RequireRegular(c, "points", "(" + std::to_string(points.size()) + " points)");
  return c;
}

SmoothCurve SmoothCurve::Custom(
    CurveFunction value, CurveFunction derivative, CurveFunction second_derivative, double tau_begin, double tau_end) {
  RequireFinite("tau_begin", tau_begin);
  RequireFinite("tau_end", tau_end);
  if (!(tau_end > tau_begin)) ThrowInvalid("tau_end", tau_end, "must be > tau_begin");
  if (!value || !derivative || !second_derivative)
    ThrowInvalid("custom", "(empty function)", "value, derivative and second_derivative must all be given");
  SmoothCurve c;
  c.kind_ = CurveKind::kCustom;
  c.custom_ = std::make_shared<const CustomFunctions>(
      CustomFunctions{std::move(value), std::move(derivative), std::move(second_derivative)});
  c.tau_begin_ = tau_begin;
  c.tau_end_ = tau_end;
  c.CheckSpeed("custom");
  return c;
}

Eigen::Vector2d SmoothCurve::RawValue(double tau) const {
  switch (kind_) {
    case CurveKind::kLine:
      return origin_ + tau * vec_;
    case CurveKind::kCircle:
      return origin_ + scale_ * Eigen::Vector2d(std::cos(tau), std::sin(tau));
    case CurveKind::kEllipse:
      return origin_ + rot_ * Eigen::Vector2d(vec_.x() * std::cos(tau), vec_.y() * std::sin(tau));
    case CurveKind::kLemniscate: {
      const double s = std::sin(tau), c = std::cos(tau);
      return origin_ + rot_ * (scale_ / (1.0 + s * s) * Eigen::Vector2d(c, s * c));
    }
    case CurveKind::kSine:
      return origin_ + rot_ * Eigen::Vector2d(tau, scale_ * std::sin(wavenumber_ * tau));
    case CurveKind::kSamples:
      return spline_->Value(tau);
    case CurveKind::kCustom:
      return custom_->value(tau);
  }
  return origin_;
}

Eigen::Vector2d SmoothCurve::RawDerivative(double tau) const {
  switch (kind_) {
    case CurveKind::kLine:
      return vec_;
    case CurveKind::kCircle:
      return scale_ * Eigen::Vector2d(-std::sin(tau), std::cos(tau));
    case CurveKind::kEllipse:
      return rot_ * Eigen::Vector2d(-vec_.x() * std::sin(tau), vec_.y() * std::cos(tau));
    case CurveKind::kLemniscate: {
      // p = f / g, f = (cos, sin cos), g = 1 + sin^2: p' = f'/g - f g'/g^2.
      const double s = std::sin(tau), c = std::cos(tau);
      const double g = 1.0 + s * s, gp = 2.0 * s * c;
      const Eigen::Vector2d f(c, s * c), fp(-s, c * c - s * s);
      return rot_ * (scale_ * (fp / g - f * gp / (g * g)));
    }
    case CurveKind::kSine:
      return rot_ * Eigen::Vector2d(1.0, scale_ * wavenumber_ * std::cos(wavenumber_ * tau));
    case CurveKind::kSamples:
      return spline_->Derivative(tau);
    case CurveKind::kCustom:
      return custom_->derivative(tau);
  }
  return vec_;
}

Eigen::Vector2d SmoothCurve::RawSecondDerivative(double tau) const {
  switch (kind_) {
    case CurveKind::kLine:
      return Eigen::Vector2d::Zero();
    case CurveKind::kCircle:
      return -scale_ * Eigen::Vector2d(std::cos(tau), std::sin(tau));
    case CurveKind::kEllipse:
      return rot_ * Eigen::Vector2d(-vec_.x() * std::cos(tau), -vec_.y() * std::sin(tau));
    case CurveKind::kLemniscate: {
      // p'' = f''/g - 2 f' g'/g^2 - f g''/g^2 + 2 f g'^2/g^3.
      const double s = std::sin(tau), c = std::cos(tau);
      const double g = 1.0 + s * s, gp = 2.0 * s * c, gpp = 2.0 * (c * c - s * s);
      const Eigen::Vector2d f(c, s * c), fp(-s, c * c - s * s), fpp(-c, -4.0 * s * c);
      return rot_ *
             (scale_ * (fpp / g - 2.0 * fp * gp / (g * g) - f * gpp / (g * g) + 2.0 * f * gp * gp / (g * g * g)));
    }
    case CurveKind::kSine:
      return rot_ * Eigen::Vector2d(0.0, -scale_ * wavenumber_ * wavenumber_ * std::sin(wavenumber_ * tau));
    case CurveKind::kSamples:
      return spline_->SecondDerivative(tau);
    case CurveKind::kCustom:
      return custom_->second_derivative(tau);
  }
  return Eigen::Vector2d::Zero();
}

void SmoothCurve::SetRange(double tau_begin, double tau_end) {
  reversed_ = tau_end < tau_begin;
  tau_begin_ = reversed_ ? -tau_begin : tau_begin;
  tau_end_ = reversed_ ? -tau_end : tau_end;
}

Eigen::Vector2d SmoothCurve::Value(double s) const { return RawValue(reversed_ ? -s : s); }
Eigen::Vector2d SmoothCurve::Derivative(double s) const {
  return reversed_ ? Eigen::Vector2d(-RawDerivative(-s)) : RawDerivative(s);
}
Eigen::Vector2d SmoothCurve::SecondDerivative(double s) const { return RawSecondDerivative(reversed_ ? -s : s); }

std::array<double, 2> SmoothCurve::DerivativeNorms(double s) const {
  const double tau = reversed_ ? -s : s;  // reversal flips p' only: the norms are those at tau
  if (kind_ != CurveKind::kCircle && kind_ != CurveKind::kEllipse)
    return {RawDerivative(tau).norm(), RawSecondDerivative(tau).norm()};
  const double sn = std::sin(tau), cs = std::cos(tau);  // RawDerivative's and RawSecondDerivative's formulas
  if (kind_ == CurveKind::kCircle)
    return {(scale_ * Eigen::Vector2d(-sn, cs)).norm(), (-scale_ * Eigen::Vector2d(cs, sn)).norm()};
  return {(rot_ * Eigen::Vector2d(-vec_.x() * sn, vec_.y() * cs)).norm(),
          (rot_ * Eigen::Vector2d(-vec_.x() * cs, -vec_.y() * sn)).norm()};
}

double SmoothCurve::ArcLength(double a, double b) const {
  RequireFinite("a", a);
  RequireFinite("b", b);
  if (b < a) return -ArcLength(b, a);
  const auto speed = [this](double tau) { return Derivative(tau).norm(); };
  const std::vector<double> breaks = PanelBreaks(a, b);
  const std::size_t last = breaks.size() - 1;
  // The whole quarter turns of a circle, ellipse or lemniscate and the whole quarter wavelengths of
  // a sine all have one length (|p'| is periodic and even about every break): measured once, on
  // [0, width], where the nodes carry no round-off from a large tau.
  const bool equal_panels = kind_ != CurveKind::kSamples && kind_ != CurveKind::kCustom && last >= 3;
  if (equal_panels) {
    const double whole = PanelLength(speed, 0.0, PanelWidth(), kArcLengthMaxDepth);
    return PanelLength(speed, breaks[0], breaks[1], kArcLengthMaxDepth) + static_cast<double>(last - 2) * whole +
           PanelLength(speed, breaks[last - 1], breaks[last], kArcLengthMaxDepth);
  }
  double length = 0.0;
  for (std::size_t i = 1; i <= last; ++i) length += PanelLength(speed, breaks[i - 1], breaks[i], kArcLengthMaxDepth);
  return length;
}

double SmoothCurve::PanelWidth() const {
  // A quarter turn of the angle of a circle, ellipse or lemniscate; a quarter wavelength of a sine
  // (|p'| has period half a wavelength); 1/64 of the parameter range of a custom curve; none
  // (infinite) for a line and a spline (whose panels are its knot intervals).
  switch (kind_) {
    case CurveKind::kCircle:
    case CurveKind::kEllipse:
    case CurveKind::kLemniscate:
      return 0.5 * M_PI;
    case CurveKind::kSine:
      return wavenumber_ > 0.0 ? 0.5 * M_PI / wavenumber_ : INFINITY;
    case CurveKind::kCustom:
      return (tau_end_ - tau_begin_) / 64.0;
    case CurveKind::kLine:
    case CurveKind::kSamples:
      break;
  }
  return INFINITY;
}

std::vector<double> SmoothCurve::PanelBreaks(double a, double b) const {
  // Panels on which the speed |p'| is smooth and monotone or nearly so, so that each needs few
  // halvings: the knot intervals of a spline (|p'| is only C^1 at the knots); the multiples of
  // PanelWidth() otherwise (from tau_begin for a custom curve, from 0 else: for a sine that is where
  // cos(k tau) is 0 or +-1, and |p'|, near-singular at its minima, has them at panel ends, where
  // the Gauss nodes cluster).
  std::vector<double> breaks{a};
  if (kind_ == CurveKind::kSamples) {
    for (const double knot : spline_->knots()) {
      const double s = reversed_ ? -knot : knot;
      if (s > a && s < b) breaks.push_back(s);
    }
    std::sort(breaks.begin(), breaks.end());
  }
  const double width = PanelWidth(), anchor = kind_ == CurveKind::kCustom ? tau_begin_ : 0.0;
  const double first = std::floor((a - anchor) / width) + 1.0, last = std::ceil((b - anchor) / width) - 1.0;
  if (std::isfinite(width) && last - first < 1e6)  // at most a million panels
    for (double j = first; j <= last; ++j)
      if (anchor + j * width > breaks.back() && anchor + j * width < b) breaks.push_back(anchor + j * width);
  breaks.push_back(b);
  return breaks;
}

void SmoothCurve::CheckSpeed(const std::string& field) const { RequireRegular(*this, field, "(" + field + ")"); }

Path::Path(std::vector<SmoothCurve> pieces) : pieces_(std::move(pieces)) {
  if (pieces_.empty()) ThrowInvalid("pieces (count)", 0, "a path needs at least one piece");
  double size = 0.0;
  for (const auto& p : pieces_) size = std::max({size, p.StartPoint().norm(), p.EndPoint().norm(), p.Length()});
  for (std::size_t i = 1; i < pieces_.size(); ++i) {
    const double gap = (pieces_[i].StartPoint() - pieces_[i - 1].EndPoint()).norm();
    if (gap > 1e-9 * std::max(1.0, size))
      ThrowInvalid("pieces[" + std::to_string(i) + "] (gap to the end of the previous piece)",
                   gap,
                   "consecutive pieces must share their end points");
  }
}

double Path::Length() const {
  double l = 0.0;
  for (const auto& p : pieces_) l += p.Length();
  return l;
}

}  // namespace plateball
