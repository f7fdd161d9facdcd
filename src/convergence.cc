#include "plateball/convergence.h"

#include <chrono>
#include <cmath>
#include <set>
#include <sstream>
#include <stdexcept>
#include <variant>

#include "check.h"

namespace plateball {
namespace {

constexpr int kMaxPartitionSize = internal::kMaxPartitionSteps;  // README, "Limits"

// The plan problem with every uniform rule set to n steps per piece.
PlanProblem WithPartitionSize(const PlanProblem& plan, int n) {
  PlanProblem p = plan;
  for (std::size_t i = 0; i < p.partition.size(); ++i) {
    PartitionRule& rule = p.partition[i];
    if (auto* u = std::get_if<UniformParameter>(&rule))
      u->n = n;
    else if (auto* a = std::get_if<UniformArcLength>(&rule))
      a->n = n;
    else
      internal::ThrowInvalid("plan.partition[" + std::to_string(i) + "]",
                             "explicit",
                             "a convergence study needs uniform partitions (n varies)");
  }
  return p;
}

ConvergenceRow RowOf(int n, const PlanSummary& plan, double seconds) {
  ConvergenceRow r;
  r.n = n;
  r.segments = plan.segments;
  r.plan_seconds = seconds;
  r.measured_error = plan.measured_error;
  r.polyline_error = plan.polyline_error;
  r.bound = plan.bounds.a_posteriori;
  r.theorem_2_6 = plan.bounds.theorem_2_6;
  r.corollary_3 = plan.bounds.corollary_3;
  r.max_pass_miss = plan.max_pass_miss;
  r.status = plan.status;
  r.message = plan.message;
  return r;
}

void AppendSlope(std::ostream& os, const char* name, const std::optional<double>& slope) {
  os << ", " << name << " slope ";
  if (slope)
    os << *slope;
  else
    os << "none";
}

}  // namespace

std::optional<double> LogLogSlope(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int m = 0;
  for (std::size_t i = 0; i < x.size() && i < y.size(); ++i) {
    if (!(x[i] > 0 && y[i] > 0 && std::isfinite(x[i]) && std::isfinite(y[i]))) continue;
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
    ++m;
  }
  const double den = m * sxx - sx * sx;
  if (m < 2 || !(den > 0)) return std::nullopt;
  return (m * sxy - sx * sy) / den;
}

void ValidatePartitionSizes(const std::vector<int>& ns, const std::string& field) {
  if (ns.empty()) internal::ThrowInvalid(field + " (count)", 0, "give at least one partition size");
  std::set<int> seen;
  for (std::size_t i = 0; i < ns.size(); ++i) {
    const std::string f = field + "[" + std::to_string(i) + "]";
    if (ns[i] < 1 || ns[i] > kMaxPartitionSize)
      internal::ThrowInvalid(f, ns[i], "must be in [1, " + std::to_string(kMaxPartitionSize) + "]");
    if (!seen.insert(ns[i]).second) internal::ThrowInvalid(f, ns[i], "repeated: give each partition size once");
  }
}

std::string ToString(ConvergenceStatus status) {
  switch (status) {
    case ConvergenceStatus::kNotRun:
      return "not_run";
    case ConvergenceStatus::kCompleted:
      return "completed";
    case ConvergenceStatus::kNoSlope:
      return "no_slope";
  }
  return "unknown";
}

std::string ConvergenceStudy::BriefReport() const {
  std::ostringstream os;
  os.precision(4);
  os << "Convergence: " << ToString(status) << ", " << rows.size() << " partitions";
  AppendSlope(os, "error", error_slope);
  AppendSlope(os, "bound", bound_slope);
  if (time_slope) AppendSlope(os, "time", time_slope);
  os << ", bound " << (bound_holds ? "holds" : "VIOLATED") << " on every n";
  if (failed_rows > 0) os << ", " << failed_rows << " plans failed";
  if (!message.empty()) os << " (" << message << ")";
  return os.str();
}

ConvergenceStudy RunConvergenceStudy(const ConvergenceProblem& problem, const ConvergenceOptions& options) {
  ValidatePartitionSizes(problem.ns, "ns");
  internal::ThrowIfInvalid(options.Validate());
  std::vector<PlanProblem> plans;
  for (int n : problem.ns) plans.push_back(WithPartitionSize(problem.plan, n));
  ConvergenceStudy out;
  std::vector<double> xn, err_y, bound_y, secs;
  for (std::size_t i = 0; i < plans.size(); ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    const PlanSummary plan = PlanImpulses(plans[i], options.plan);
    const double dt =
        options.timings ? std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() : 0.0;
    const ConvergenceRow r = RowOf(problem.ns[i], plan, dt);
    if (plan.IsSolutionUsable()) {
      xn.push_back(r.n);
      err_y.push_back(r.measured_error);
      bound_y.push_back(r.bound);
      secs.push_back(dt);
      if (!(r.measured_error <= r.bound)) out.bound_holds = false;
    } else {
      ++out.failed_rows;
    }
    out.rows.push_back(r);
    if (options.progress) options.progress(static_cast<int>(i + 1), static_cast<int>(plans.size()));
  }
  out.error_slope = LogLogSlope(xn, err_y);
  out.bound_slope = LogLogSlope(xn, bound_y);
  if (options.timings) out.time_slope = LogLogSlope(xn, secs);
  out.status = out.error_slope ? ConvergenceStatus::kCompleted : ConvergenceStatus::kNoSlope;
  out.message = out.error_slope ? "" : "no slope: needs at least 2 successful partition sizes";
  return out;
}

}  // namespace plateball
