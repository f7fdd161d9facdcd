#include "plateball/partition.h"

#include <algorithm>
#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <cmath>
#include <stdexcept>

#include "check.h"
#include "partition_internal.h"

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

namespace {

// The first k > 0 whose point p(tau_k) lies within 1e-12 x the path length of p(tau_{k-1}) (0: none);
// `step` gets that distance.
std::size_t CoincidentPoint(const SmoothCurve& curve, const std::vector<double>& taus, double* step) {
  const double size = std::max(1.0, curve.Length());
  Eigen::Vector2d previous = curve.Value(taus.front());
  for (std::size_t k = 1; k < taus.size(); ++k) {
    const Eigen::Vector2d point = curve.Value(taus[k]);
    *step = (point - previous).norm();
    previous = point;
    if (!(*step > 1e-12 * size)) return k;
  }
  return 0;
}

std::string CoincidentText(std::size_t k, double step) {
  return "partition points " + std::to_string(k - 1) + " and " + std::to_string(k) + " are " +
         internal::FormatNumber(step) +
         " apart on the plate: consecutive partition points must be more than 1e-12 x the path length apart";
}

// The points of a uniform partition follow from n alone: a fault is named by `n_field` and n.
void ValidateUniform(const SmoothCurve& curve, const std::vector<double>& taus, int n, const std::string& n_field) {
  for (std::size_t k = 1; k < taus.size(); ++k)
    if (!(taus[k] > taus[k - 1]))
      ThrowInvalid(n_field,
                   n,
                   "the parameter interval [" + internal::FormatNumber(curve.Begin()) + ", " +
                       internal::FormatNumber(curve.End()) + "] is too short for n steps in double precision");
  double step = 0.0;
  if (const std::size_t k = CoincidentPoint(curve, taus, &step); k > 0)
    ThrowInvalid(n_field, n, CoincidentText(k, step));
}

std::vector<double> UniformParameterNamed(const SmoothCurve& curve, int n, const std::string& n_field) {
  RequireCount(n, n_field);
  std::vector<double> t(static_cast<std::size_t>(n) + 1);
  for (int k = 0; k <= n; ++k) t[k] = curve.Begin() + (curve.End() - curve.Begin()) * k / n;
  t.back() = curve.End();
  ValidateUniform(curve, t, n, n_field);
  return t;
}

std::vector<double> UniformArcLengthNamed(const SmoothCurve& curve, int n, const std::string& n_field) {
  RequireCount(n, n_field);
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
      if (f > 0)
        hi = tau;
      else
        lo = tau;
      double next = tau - f / curve.Derivative(tau).norm();
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
      tau = next;
    }
    t[k] = tau;
  }
  ValidateUniform(curve, t, n, n_field);
  return t;
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
      ThrowInvalid(element(k),
                   taus[k],
                   "partition values must increase strictly (previous " + internal::FormatNumber(taus[k - 1]) + ")");
  }
  if (std::abs(taus.front() - curve.Begin()) > 1e-12 * std::max(1.0, std::abs(span)))
    ThrowInvalid(field + "[0]",
                 taus.front(),
                 "must equal the start of the parameter interval " + internal::FormatNumber(curve.Begin()));
  if (std::abs(taus.back() - curve.End()) > 1e-12 * std::max(1.0, std::abs(span)))
    ThrowInvalid(field + "[" + std::to_string(taus.size() - 1) + "]",
                 taus.back(),
                 "must equal the end of the parameter interval " + internal::FormatNumber(curve.End()));
  double step = 0.0;
  if (const std::size_t k = CoincidentPoint(curve, taus, &step); k > 0)
    ThrowInvalid(element(k), taus[k], CoincidentText(k, step));
}

std::vector<double> UniformParameterPartition(const SmoothCurve& curve, int n) {
  return UniformParameterNamed(curve, n, "partition.n");
}

std::vector<double> UniformArcLengthPartition(const SmoothCurve& curve, int n) {
  return UniformArcLengthNamed(curve, n, "partition.n");
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

std::vector<std::vector<double>> MakePartition(const Path& path,
                                               const std::vector<PartitionRule>& rules,
                                               const std::string& field) {
  return internal::MakePartition(path, rules, field, "");
}

namespace internal {

std::vector<std::vector<double>> MakePartition(const Path& path,
                                               const std::vector<PartitionRule>& rules,
                                               const std::string& field,
                                               const std::string& n_field) {
  const std::size_t pieces = static_cast<std::size_t>(path.PieceCount());
  if (rules.size() != 1 && rules.size() != pieces)
    ThrowInvalid(field + " (rule count)",
                 static_cast<double>(rules.size()),
                 "must be 1 or the number of path pieces " + std::to_string(pieces));
  std::vector<std::vector<double>> out;
  long long steps = 0;  // every piece gets its rule's steps (README, "Limits")
  for (std::size_t i = 0; i < pieces; ++i) {
    const PartitionRule& rule = rules.size() == 1 ? rules.front() : rules[i];
    if (const auto* u = std::get_if<UniformParameter>(&rule))
      steps += u->n;
    else if (const auto* a = std::get_if<UniformArcLength>(&rule))
      steps += a->n;
    else
      steps += static_cast<long long>(std::get<ExplicitTaus>(rule).taus.size()) - 1;
  }
  if (steps > kMaxPartitionSteps)
    ThrowInvalid(rules.size() == 1 ? field + " (n x " + std::to_string(pieces) + " pieces)" : field + " (steps)",
                 steps,
                 "steps over all pieces must be <= " + std::to_string(kMaxPartitionSteps));
  for (std::size_t i = 0; i < pieces; ++i) {
    const PartitionRule& rule = rules.size() == 1 ? rules.front() : rules[i];
    const SmoothCurve& curve = path.pieces()[i];
    const std::string f = rules.size() == 1 ? field : field + "[" + std::to_string(i) + "]";
    const std::string nf = n_field.empty() || rules.size() != 1 ? f + ".n" : n_field;
    if (const auto* u = std::get_if<UniformParameter>(&rule)) {
      out.push_back(UniformParameterNamed(curve, u->n, nf));
    } else if (const auto* a = std::get_if<UniformArcLength>(&rule)) {
      out.push_back(UniformArcLengthNamed(curve, a->n, nf));
    } else {
      const std::vector<double>& taus = std::get<ExplicitTaus>(rule).taus;
      ValidatePartition(curve, taus, f + ".taus");
      out.push_back(ExplicitPartition(curve, taus));
    }
  }
  return out;
}

}  // namespace internal

double PointNorm(const SmoothCurve& curve, const std::vector<double>& taus) {
  double m = 0.0;
  for (std::size_t k = 1; k < taus.size(); ++k)
    m = std::max(m, (curve.Value(taus[k]) - curve.Value(taus[k - 1])).norm());
  return m;
}

double ParameterNorm(const std::vector<double>& taus) {
  double m = 0.0;
  for (std::size_t k = 1; k < taus.size(); ++k) m = std::max(m, taus[k] - taus[k - 1]);
  return m;
}

}  // namespace plateball
