#include "plateball/partition.h"

#include <algorithm>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <stdexcept>

#include "check.h"

namespace plateball {
namespace {
using internal::ThrowInvalid;

void RequireCount(int n, const std::string& field) {
  if (n < 1) ThrowInvalid(field, n, "a partition needs n >= 1 steps (at least 2 points)");
  if (n > internal::kMaxPartitionSteps)  // README, "Limits": a plan's work and memory grow with n
    ThrowInvalid(field, n, "must be <= " + std::to_string(internal::kMaxPartitionSteps));
}
// The length of a short cell [a, b] (at most 1/256 of the curve's parameter range) by one
// 15-point Gauss-Kronrod rule, accepted when |K15 - G7| <= 1e-13 of max(length, scale) (the K15
// value is then far more accurate; `scale` is the length of the grid cell that holds [a, b], so a
// Newton iterate next to the cell's start is not held to a relative accuracy below round-off), else
// the adaptive SmoothCurve::ArcLength (which also knows the round-off floor of cells far from
// tau = 0). On smooth cells 15 speed evaluations instead of ArcLength's 31 and more.
double CellLength(const SmoothCurve& curve, double a, double b, double scale) {
  using Kronrod = boost::math::quadrature::gauss_kronrod<double, 15>;
  double error = 0.0;
  const double length =
      Kronrod::integrate([&curve](double tau) { return curve.Derivative(tau).norm(); }, a, b, 0, 0.0, &error);
  return std::isfinite(length) && error <= 1e-13 * std::max(length, scale) ? length : curve.ArcLength(a, b);
}
}  // namespace

void ValidatePartition(const SmoothCurve& curve, const std::vector<double>& taus, const std::string& field) {
  if (taus.size() < 2)
    ThrowInvalid(field + " (point count)", static_cast<double>(taus.size()), "a partition needs at least 2 points");
  const double span = curve.End() - curve.Begin();
  // Element names are built only for a bad value (a plan validates every partition point).
  const auto element = [&field](std::size_t k) { return field + "[" + std::to_string(k) + "]"; };
  for (std::size_t k = 0; k < taus.size(); ++k) {
    if (!std::isfinite(taus[k])) internal::RequireFinite(element(k), taus[k]);
    if (k > 0 && !(taus[k] > taus[k - 1]))
      ThrowInvalid(element(k), taus[k], "partition values must increase strictly (previous " + internal::FormatNumber(taus[k - 1]) + ")");
  }
  if (std::abs(taus.front() - curve.Begin()) > 1e-12 * std::max(1.0, std::abs(span)))
    ThrowInvalid(field + "[0]", taus.front(), "must equal the start of the parameter interval " + internal::FormatNumber(curve.Begin()));
  if (std::abs(taus.back() - curve.End()) > 1e-12 * std::max(1.0, std::abs(span)))
    ThrowInvalid(field + "[" + std::to_string(taus.size() - 1) + "]", taus.back(),
                 "must equal the end of the parameter interval " + internal::FormatNumber(curve.End()));
  const double size = std::max(1.0, curve.Length());
  Eigen::Vector2d previous = curve.Value(taus.front());
  for (std::size_t k = 1; k < taus.size(); ++k) {
    const Eigen::Vector2d point = curve.Value(taus[k]);
    const double step = (point - previous).norm();
    previous = point;
    if (!(step > 1e-12 * size))
      ThrowInvalid(field + "[" + std::to_string(k) + "] (|p(tau_k) - p(tau_k-1)|)", step,
                   "consecutive partition points must be more than 1e-12 x the path length apart on the plate");
  }
}

std::vector<double> UniformParameterPartition(const SmoothCurve& curve, int n) {
  RequireCount(n, "partition.n");
  std::vector<double> t(static_cast<std::size_t>(n) + 1);
  for (int k = 0; k <= n; ++k) t[k] = curve.Begin() + (curve.End() - curve.Begin()) * k / n;
  t.back() = curve.End();
  ValidatePartition(curve, t, "partition (uniform_parameter, n = " + std::to_string(n) + ")");
  return t;
}

std::vector<double> UniformArcLengthPartition(const SmoothCurve& curve, int n) {
  RequireCount(n, "partition.n");
  // Cumulative length on a grid, then Newton on L(tau) = target inside the bracketing cell.
  constexpr int kGrid = 256;
  std::vector<double> grid(kGrid + 1), cum(kGrid + 1, 0.0);
  for (int i = 0; i <= kGrid; ++i) grid[i] = curve.Begin() + (curve.End() - curve.Begin()) * i / kGrid;
  for (int i = 1; i <= kGrid; ++i) cum[i] = cum[i - 1] + CellLength(curve, grid[i - 1], grid[i], 0.0);
  const double total = cum.back();
  std::vector<double> t(static_cast<std::size_t>(n) + 1);
  t.front() = curve.Begin();
  t.back() = curve.End();
  for (int k = 1; k < n; ++k) {
    const double target = total * k / n;
    const int i = static_cast<int>(std::upper_bound(cum.begin(), cum.end(), target) - cum.begin()) - 1;
    const int cell = std::clamp(i, 0, kGrid - 1);
    double lo = grid[cell], hi = grid[cell + 1];
    double tau = lo + (hi - lo) * (target - cum[cell]) / (cum[cell + 1] - cum[cell]);
    for (int it = 0; it < 50; ++it) {  // safeguarded Newton: L'(tau) = |p'(tau)| > 0
      const double f = cum[cell] + CellLength(curve, grid[cell], tau, cum[cell + 1] - cum[cell]) - target;
      if (std::abs(f) <= 1e-14 * std::max(1.0, total)) break;
      if (f > 0) hi = tau; else lo = tau;
      double next = tau - f / curve.Derivative(tau).norm();
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      tau = next;
    }
    t[k] = tau;
  }
  ValidatePartition(curve, t, "partition (uniform_arc_length, n = " + std::to_string(n) + ")");
  return t;
}

std::vector<double> ExplicitPartition(const SmoothCurve& curve, const std::vector<double>& taus) {
  ValidatePartition(curve, taus, "partition.taus");
  std::vector<double> t = taus;
  t.front() = curve.Begin();
  t.back() = curve.End();
  return t;
}

std::string ToString(const PartitionRule& rule) {
  struct Name {
    std::string operator()(const UniformParameter&) const { return "uniform_parameter"; }
    std::string operator()(const UniformArcLength&) const { return "uniform_arc_length"; }
    std::string operator()(const ExplicitTaus&) const { return "explicit"; }
  };
  return std::visit(Name{}, rule);
}

std::vector<std::vector<double>> MakePartition(const Path& path, const std::vector<PartitionRule>& rules,
                                               const std::string& field) {
  const std::size_t pieces = static_cast<std::size_t>(path.PieceCount());
  if (rules.size() != 1 && rules.size() != pieces)
    ThrowInvalid(field + " (rule count)", static_cast<double>(rules.size()),
                 "must be 1 or the number of path pieces " + std::to_string(pieces));
  std::vector<std::vector<double>> out;
  long long steps = 0;  // every piece gets its rule's steps (README, "Limits")
  for (std::size_t i = 0; i < pieces; ++i) {
    const PartitionRule& rule = rules.size() == 1 ? rules.front() : rules[i];
    if (const auto* u = std::get_if<UniformParameter>(&rule)) steps += u->n;
    else if (const auto* a = std::get_if<UniformArcLength>(&rule)) steps += a->n;
    else steps += static_cast<long long>(std::get<ExplicitTaus>(rule).taus.size()) - 1;
  }
  if (steps > internal::kMaxPartitionSteps)
    ThrowInvalid(rules.size() == 1 ? field + " (n x " + std::to_string(pieces) + " pieces)" : field + " (steps)", steps,
                 "steps over all pieces must be <= " + std::to_string(internal::kMaxPartitionSteps));
  for (std::size_t i = 0; i < pieces; ++i) {
    const PartitionRule& rule = rules.size() == 1 ? rules.front() : rules[i];
    const SmoothCurve& curve = path.pieces()[i];
    const std::string f = rules.size() == 1 ? field : field + "[" + std::to_string(i) + "]";
    if (const auto* u = std::get_if<UniformParameter>(&rule)) {
      RequireCount(u->n, f + ".n");
      out.push_back(UniformParameterPartition(curve, u->n));
    } else if (const auto* a = std::get_if<UniformArcLength>(&rule)) {
      RequireCount(a->n, f + ".n");
      out.push_back(UniformArcLengthPartition(curve, a->n));
    } else {
      const std::vector<double>& taus = std::get<ExplicitTaus>(rule).taus;
      ValidatePartition(curve, taus, f + ".taus");
      out.push_back(ExplicitPartition(curve, taus));
    }
  }
  return out;
}

double PointNorm(const SmoothCurve& curve, const std::vector<double>& taus) {
  double m = 0.0;
  for (std::size_t k = 1; k < taus.size(); ++k) m = std::max(m, (curve.Value(taus[k]) - curve.Value(taus[k - 1])).norm());
  return m;
}

double ParameterNorm(const std::vector<double>& taus) {
  double m = 0.0;
  for (std::size_t k = 1; k < taus.size(); ++k) m = std::max(m, taus[k] - taus[k - 1]);
  return m;
}

}  // namespace plateball
