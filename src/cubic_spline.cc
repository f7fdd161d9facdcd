#include "plateball/cubic_spline.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "check.h"

namespace plateball {
namespace {
std::vector<double> ChordKnots(const std::vector<Eigen::Vector2d>& p) {
  std::vector<double> s(p.size(), 0.0);
  for (std::size_t i = 1; i < p.size(); ++i) s[i] = s[i - 1] + (p[i] - p[i - 1]).norm();
  return s;
}
std::string SamplePointText(const Eigen::Vector2d& p) {
  return "(" + internal::FormatNumber(p.x()) + ", " + internal::FormatNumber(p.y()) + ")";
}
void CheckPoints(const std::vector<Eigen::Vector2d>& p) {
  if (p.size() < 2)
    internal::ThrowInvalid("points (count)", static_cast<double>(p.size()), "a path needs at least 2 samples");
  double length = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    internal::RequireFinite("points[" + std::to_string(i) + "]", p[i]);
    if (i == 0) continue;
    const double step = (p[i] - p[i - 1]).norm();
    if (p[i] == p[i - 1])
      internal::ThrowInvalid(
          "points[" + std::to_string(i) + "]", SamplePointText(p[i]), "repeats the previous sample point");
    if (!std::isfinite(step)) {  // the chord lengths are the spline's knots: name the larger point
      const std::size_t far = p[i - 1].cwiseAbs().maxCoeff() > p[i].cwiseAbs().maxCoeff() ? i - 1 : i;
      internal::ThrowInvalid(
          "points[" + std::to_string(far) + "]",
          SamplePointText(p[far]),
          "too far from sample point " + std::to_string(far == i ? i - 1 : i) + " (the distance overflows a double)");
    }
    if (!(step > 0.0))  // distinct, but the distance underflows
      internal::ThrowInvalid("points[" + std::to_string(i) + "]",
                             SamplePointText(p[i]),
                             "distinct from the previous sample point but closer than double precision resolves");
    length += step;
  }
  if (!std::isfinite(length))
    internal::ThrowInvalid(
        "points", "[array of " + std::to_string(p.size()) + "]", "the path length overflows a double");
}
}  // namespace

CubicSpline2d::CubicSpline2d(const std::vector<Eigen::Vector2d>& points) : p_(points) {
  CheckPoints(points);
  s_ = ChordKnots(points);
  Build();
}

CubicSpline2d::CubicSpline2d(const std::vector<double>& knots, const std::vector<Eigen::Vector2d>& points)
    : s_(knots), p_(points) {
  CheckPoints(points);
  if (knots.size() != points.size())
    internal::ThrowInvalid("knots (count)", static_cast<double>(knots.size()), "must equal the number of samples");
  for (std::size_t i = 0; i < knots.size(); ++i) {
    internal::RequireFinite("knots[" + std::to_string(i) + "]", knots[i]);
    if (i > 0 && !(knots[i] > knots[i - 1]))
      internal::ThrowInvalid("knots[" + std::to_string(i) + "]", knots[i], "knots must increase strictly");
  }
  Build();
}

void CubicSpline2d::Build() {
  const std::size_t n = s_.size();
  m_.assign(n, Eigen::Vector2d::Zero());
  if (n < 3) return;
  // Tridiagonal system for the interior second derivatives (natural end conditions).
  std::vector<double> diag(n, 0.0), upper(n, 0.0);
  std::vector<Eigen::Vector2d> rhs(n, Eigen::Vector2d::Zero());
  for (std::size_t i = 1; i + 1 < n; ++i) {
    const double h0 = s_[i] - s_[i - 1], h1 = s_[i + 1] - s_[i];
    diag[i] = 2.0 * (h0 + h1);
    upper[i] = h1;
    rhs[i] = 6.0 * ((p_[i + 1] - p_[i]) / h1 - (p_[i] - p_[i - 1]) / h0);
  }
  // Thomas algorithm on rows 1..n-2 (lower[i] = h0 = s_i - s_{i-1}).
  for (std::size_t i = 2; i + 1 < n; ++i) {
    const double lower = s_[i] - s_[i - 1];
    const double f = lower / diag[i - 1];
    diag[i] -= f * upper[i - 1];
    rhs[i] -= f * rhs[i - 1];
  }
  for (std::size_t i = n - 2; i >= 1; --i) {
    m_[i] = (rhs[i] - upper[i] * m_[i + 1]) / diag[i];
    if (i == 1) break;
  }
}

std::size_t CubicSpline2d::Segment(double s) const {
  auto it = std::upper_bound(s_.begin(), s_.end(), s);
  std::size_t i = it == s_.begin() ? 0 : static_cast<std::size_t>(it - s_.begin()) - 1;
  return std::min(i, s_.size() - 2);
}

Eigen::Vector2d CubicSpline2d::Value(double s) const {
  const std::size_t i = Segment(s);
  const double h = s_[i + 1] - s_[i], a = (s_[i + 1] - s) / h, b = (s - s_[i]) / h;
  return a * p_[i] + b * p_[i + 1] + ((a * a * a - a) * m_[i] + (b * b * b - b) * m_[i + 1]) * (h * h / 6.0);
}

Eigen::Vector2d CubicSpline2d::Derivative(double s) const {
  const std::size_t i = Segment(s);
  const double h = s_[i + 1] - s_[i], a = (s_[i + 1] - s) / h, b = (s - s_[i]) / h;
  return (p_[i + 1] - p_[i]) / h + (-(3 * a * a - 1) * m_[i] + (3 * b * b - 1) * m_[i + 1]) * (h / 6.0);
}

Eigen::Vector2d CubicSpline2d::SecondDerivative(double s) const {
  const std::size_t i = Segment(s);
  const double h = s_[i + 1] - s_[i], a = (s_[i + 1] - s) / h, b = (s - s_[i]) / h;
  return a * m_[i] + b * m_[i + 1];
}

}  // namespace plateball
