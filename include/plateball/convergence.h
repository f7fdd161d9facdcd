// Convergence study of the impulsive approximation (Corollaries 2 and 3): plan one problem for a
// sequence of partition sizes n and fit the log-log slope of the error against n (about -2).
#pragma once

#include <string>
#include <vector>

#include "plateball/export.h"
#include "plateball/impulse_planner.h"
#include "plateball/problem.h"

namespace plateball PLATEBALL_EXPORT {

struct ConvergenceRow {
  int n = 0;                    ///< segments per piece
  int segments = 0;             ///< over all pieces
  double plan_seconds = 0.0;    ///< wall time of the whole plan
  double measured_error = 0.0;  ///< ||A(T) - Atilde_n||
  double polyline_error = 0.0;  ///< ||A(T) - Abar_n||
  double bound = 0.0;           ///< the plan's a-posteriori bound
  double theorem_2_6 = 0.0;     ///< (Kbar_p + Ktilde_p) sum dtau^3
  double corollary_3 = 0.0;     ///< (Kbar_p + Ktilde_p) n ||P||^3
  double max_pass_miss = 0.0;
  PlanStatus status = PlanStatus::kSuccess;
  std::string message;
};

struct ConvergenceStudy {
  std::vector<ConvergenceRow> rows;
  double error_slope = 0.0;     ///< least-squares slope of log(error) against log(n) (successful rows)
  double bound_slope = 0.0;     ///< same for the bound
  double time_slope = 0.0;      ///< same for the plan time
  bool bound_holds = true;      ///< measured error <= bound on every successful row
  int failed_rows = 0;
  std::string BriefReport() const;
};

/// Least-squares slope of log(y) against log(x) over the pairs with x, y > 0 (NaN with fewer than 2).
double LogLogSlope(const std::vector<double>& x, const std::vector<double>& y);

/// Plans problem.plan for every n in `ns` (each >= 1; default: plan.converge_n, else
/// 16, 32, ..., 1024). Throws std::invalid_argument naming the field for bad input.
ConvergenceStudy RunConvergenceStudy(const Problem& problem, std::vector<int> ns = {},
                                     const PlanOptions& options = {});

}  // namespace plateball
