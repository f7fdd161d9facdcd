#include "plateball/convergence.h"

#include <chrono>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "check.h"

namespace plateball {

double LogLogSlope(const std::vector<double>& x, const std::vector<double>& y) {
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
  if (m < 2 || den <= 0) return std::numeric_limits<double>::quiet_NaN();
  return (m * sxy - sx * sy) / den;
}

std::string ConvergenceStudy::BriefReport() const {
  std::ostringstream os;
  os.precision(4);
  os << "Convergence: " << rows.size() << " partitions, error slope " << error_slope << ", bound slope "
     << bound_slope << ", time slope " << time_slope << ", bound " << (bound_holds ? "holds" : "VIOLATED")
     << " on every n";
  if (failed_rows > 0) os << ", " << failed_rows << " plans failed";
  return os.str();
}

ConvergenceStudy RunConvergenceStudy(const Problem& problem, std::vector<int> ns, const PlanOptions& options) {
  if (!problem.plan) internal::ThrowInvalid("plan", "(missing)", "the problem has no plan task");
  if (ns.empty()) ns = problem.plan->converge_n;
  if (ns.empty()) ns = {16, 32, 64, 128, 256, 512, 1024};
  for (std::size_t i = 0; i < ns.size(); ++i)
    if (ns[i] < 1) internal::ThrowInvalid("converge_n[" + std::to_string(i) + "]", ns[i], "must be >= 1");
  ConvergenceStudy out;
  std::vector<double> xn, err, bound, secs;
  for (int n : ns) {
    const auto t0 = std::chrono::steady_clock::now();
    const PlanSummary plan = PlanImpulses(problem, options, n);
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    ConvergenceRow r;
    r.n = n;
    r.segments = plan.segments;
    r.plan_seconds = dt;
    r.measured_error = plan.measured_error;
    r.polyline_error = plan.polyline_error;
    r.bound = plan.bounds.a_posteriori;
    r.theorem_2_6 = plan.bounds.theorem_2_6;
    r.corollary_3 = plan.bounds.corollary_3;
    r.max_pass_miss = plan.max_pass_miss;
    r.status = plan.status;
    r.message = plan.message;
    if (plan.IsSolutionUsable()) {
      xn.push_back(n);
      err.push_back(r.measured_error);
      bound.push_back(r.bound);
      secs.push_back(dt);
      if (!(r.measured_error <= r.bound)) out.bound_holds = false;
    } else {
      ++out.failed_rows;
    }
    out.rows.push_back(r);
  }
  out.error_slope = LogLogSlope(xn, err);
  out.bound_slope = LogLogSlope(xn, bound);
  out.time_slope = LogLogSlope(xn, secs);
  return out;
}

}  // namespace plateball
