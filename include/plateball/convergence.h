// Convergence study of the impulsive approximation (Corollaries 2 and 3): plan one problem for a
// sequence of partition sizes n and fit the log-log slope of the error against n (about -2).
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "plateball/export.h"
#include "plateball/impulse_planner.h"

namespace plateball PLATEBALL_EXPORT {

/// What is asked: the plan problem (its partition rules must be uniform; each n of `ns` replaces
/// their n) and the distinct partition sizes.
struct ConvergenceProblem {
  PlanProblem plan;
  std::vector<int> ns{16, 32, 64, 128, 256, 512, 1024};  ///< distinct, each >= 1
};

struct ConvergenceOptions {
  PlanOptions plan;
  /// Measure the wall time of every plan (ConvergenceRow::plan_seconds, time_slope). Off by
  /// default: a study is then a deterministic function of its problem (reproducible files).
  bool timings = false;
  /// Called after each partition size with (sizes done, sizes in all), for a tool's progress
  /// line. The library never prints.
  std::function<void(int, int)> progress;
  /// Empty when the options are valid; else a message naming the field and its value.
  std::string Validate() const { return plan.Validate(); }
};

struct ConvergenceRow {
  int n = 0;                    ///< segments per piece
  int segments = 0;             ///< over all pieces
  double plan_seconds = 0.0;    ///< wall time of the whole plan (0 unless options.timings)
  double measured_error = 0.0;  ///< ||A(T) - Atilde_n||
  double polyline_error = 0.0;  ///< ||A(T) - Abar_n||
  double bound = 0.0;           ///< the plan's a-posteriori bound
  double theorem_2_6 = 0.0;     ///< (Kbar_p + Ktilde_p) sum dtau^3
  double corollary_3 = 0.0;     ///< (Kbar_p + Ktilde_p) n ||P||^3
  double max_pass_miss = 0.0;
  PlanStatus status = PlanStatus::kNotRun;
  std::string message = "not run";
};

enum class ConvergenceStatus {
  kNotRun,     ///< default: nothing was planned
  kCompleted,  ///< every n was planned and the slopes are fitted (rows may still have failed)
  kNoSlope,    ///< fewer than 2 partition sizes planned successfully: no slope (message)
};
/// "not_run", "completed" or "no_slope", as in the JSON.
std::string ToString(ConvergenceStatus status);

/// A default-constructed study says "not run" (no rows, no slopes).
struct ConvergenceStudy {
  ConvergenceStatus status = ConvergenceStatus::kNotRun;
  std::vector<ConvergenceRow> rows;
  /// Least-squares slope of log(error) against log(n) over the successful rows; empty with
  /// fewer than 2 successful rows (a slope needs two distinct n).
  std::optional<double> error_slope;
  std::optional<double> bound_slope;  ///< same for the bound
  std::optional<double> time_slope;   ///< same for the plan time (only with options.timings)
  bool bound_holds = true;            ///< measured error <= bound on every successful row
  int failed_rows = 0;
  std::string message = "not run";  ///< empty once run, or why there is no slope

  /// True when the slopes were fitted (status kCompleted).
  bool IsSolutionUsable() const { return status == ConvergenceStatus::kCompleted; }
  /// One line: the status, the number of partitions, the slopes and whether the bound holds.
  std::string BriefReport() const;
};

/// Least-squares slope of log(y) against log(x) over the pairs with x, y > 0; empty with fewer
/// than 2 such pairs or all x equal.
std::optional<double> LogLogSlope(const std::vector<double>& x, const std::vector<double>& y);

/// Checks a list of partition sizes: each in [1, 1000000] and none repeated (a repeated n would
/// weigh one point twice in the fit). Throws std::invalid_argument naming `field`[i].
void ValidatePartitionSizes(const std::vector<int>& ns, const std::string& field);

/// Plans problem.plan for every n in problem.ns (ValidatePartitionSizes; the partition rules
/// must be uniform). Throws std::invalid_argument naming the field for bad input; a plan that
/// fails is a row status.
ConvergenceStudy RunConvergenceStudy(const ConvergenceProblem& problem, const ConvergenceOptions& options = {});

}  // namespace PLATEBALL_EXPORT
