// Monte Carlo of plan execution under errors: N seeded trials per strategy
// (execution.h) and error scenario (error_model.h), the distributions of the final errors, the
// missed pass points and the total time, and the final error against the number of impulses n
// with its fitted log-log slope (the paper's conclusion: errors of a more realistic model may
// slow Theorem 2.6's O(1/n^2) to about O(1/n)).
//
// Trial i of a (n, scenario, strategy) cell draws its errors from (seed, i) alone (a
// counter-based stream), so every strategy meets the same realisations and the results do not
// depend on the number of threads or processes: MonteCarloWork splits the flat task list
// [0, TaskCount()) in any way (threads here, MPI ranks in `plateball montecarlo`) and
// Summarize() of the gathered records is the same for any split.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "plateball/error_model.h"
#include "plateball/execution.h"
#include "plateball/export.h"
#include "plateball/impulse_planner.h"

namespace plateball PLATEBALL_EXPORT {

struct MonteCarloScenario {
  std::string name;  ///< for reports (e.g. ToString(errors))
  ErrorModel errors;
};

/// What is asked.
struct MonteCarloProblem {
  PlanProblem plan;  ///< the planned path; its (single, uniform) partition gives the main n
  std::vector<ExecutionStrategy> strategies{ExecutionStrategy::kOpenLoop, ExecutionStrategy::kFeedback};
  std::vector<MonteCarloScenario> scenarios;  ///< at least one
  int trials = 100;                           ///< per cell at the main n, 1 ... kMaxTrials
  std::uint64_t seed = 1;
  /// Further n for the error-against-n study (uniform partitions, distinct, 3 ... 10^4); empty: none.
  std::vector<int> sweep_n;
  /// The main n's plan of `plan`, planned elsewhere (e.g. PlanImpulsesOnRig, rig_planner.h, on a
  /// refined partition slid onto a tick grid): executed as it is (MakeNominalPlan(plan, options,
  /// main_plan)) instead of planning plan.partition. Not with sweep_n (its n would not be the
  /// partition's). Empty: plan.partition is planned.
  std::optional<PlanSummary> main_plan;
};

struct MonteCarloOptions {
  static constexpr int kMaxTrials = 1'000'000;
  static constexpr long long kMaxTasks = 2'000'000;  ///< trials over all cells and n (memory: ~60 bytes each)
  /// Bound of the study's work, counted up front in impulse executions: every trial executes its n
  /// impulses, and a feedback_exact trial re-solves exactly while at most W = execution.exact_window
  /// impulses remain (about W^3 more): work = sum over cells of trials x (n + [feedback_exact] W^3).
  static constexpr long long kMaxWork = 100'000'000;
  PlanOptions plan;
  ExecutionOptions execution;
  int threads = 1;          ///< 1 ... 256; the results do not depend on it
  int sweep_trials = 0;     ///< trials per cell at the sweep's other n (0: `trials`), 0 ... kMaxTrials
  bool keep_trials = true;  ///< keep every trial's record in the summary
  /// Called after each task with (tasks done, tasks to do), on the thread that ran it (the calling
  /// thread among them); may throw to abandon the run: each thread stops at its next task and the
  /// exception propagates out of RunMonteCarlo.
  std::function<void(long long, long long)> progress;
  /// Empty when the options are valid; else a message naming the field and its value.
  std::string Validate() const;
};

/// One trial's result (what the per-trial CSV holds).
struct TrialRecord {
  int n = 0;
  int scenario = 0;  ///< index into MonteCarloProblem::scenarios
  ExecutionStrategy strategy = ExecutionStrategy::kFeedback;
  std::int64_t trial = 0;
  ExecutionStatus status = ExecutionStatus::kNotRun;
  double position_error = 0.0, orientation_error = 0.0, max_pass_miss = 0.0, total_time = 0.0;
  int missed_pass_points = 0;
};

/// Order statistics of one quantity over the completed trials of a cell (median and 95th
/// percentile by linear interpolation between order statistics, Hyndman-Fan type 7).
struct Distribution {
  double median = 0.0, p95 = 0.0, max = 0.0, mean = 0.0;
};
/// The Distribution of the values (empty: all zero).
Distribution Distribute(std::vector<double> values);

/// The distributions are over the completed trials; a cell where no trial completed has none
/// (nullopt: "no trial completed", never zeros).
struct MonteCarloCell {
  int n = 0;
  int scenario = 0;
  ExecutionStrategy strategy = ExecutionStrategy::kFeedback;
  int trials = 0, completed = 0;
  std::optional<Distribution> position_error, orientation_error, max_pass_miss, missed_pass_points, total_time;
};

/// Median final errors of one (scenario, strategy) against n, with the plan's own error. An n
/// whose cell has no completed trial is missing: its medians are nullopt and the fits leave it out.
struct SweepSeries {
  int scenario = 0;
  ExecutionStrategy strategy = ExecutionStrategy::kFeedback;
  std::vector<int> n;
  std::vector<std::optional<double>> median_orientation_error, median_position_error;
  std::vector<double> plan_orientation_error;
  /// Least-squares slope of log(median orientation error) against log(n) over every n with data
  /// (none when fewer than two n have a positive median), and between neighbouring n (none when
  /// either is missing).
  std::optional<double> slope;
  std::vector<std::optional<double>> local_slopes;
  std::optional<double> plan_slope;  ///< the same fit of plan_orientation_error (Theorem 2.6: -2)

  /// True when no trial of row i completed (its medians are null and the fit leaves it out).
  bool Missing(std::size_t i) const { return !median_orientation_error[i].has_value(); }
};

/// The nominal plan of one n.
struct NominalInfo {
  int n = 0;
  PlanStatus status = PlanStatus::kNotRun;
  std::string message;
  double orientation_error = 0.0;  ///< |LogSO3(A(T)^T Atilde_n)|, rad
  double measured_error = 0.0;     ///< ||A(T) - Atilde_n||, operator norm (Theorem 2.6)
  double total_time = 0.0;
};

enum class MonteCarloStatus {
  kNotRun,             ///< default
  kCompleted,          ///< every trial ran (some may have lost the ball: see the cells)
  kNominalPlanFailed,  ///< the deterministic plan of some n failed: nothing was executed
};
/// The value's word as the tools write it in their JSON output and messages.
std::string ToString(MonteCarloStatus status);

/// A default-constructed summary says "not run".
struct MonteCarloSummary {
  MonteCarloStatus status = MonteCarloStatus::kNotRun;
  std::string message = "not run";
  std::vector<NominalInfo> nominal;   ///< per n, ascending
  std::vector<MonteCarloCell> cells;  ///< per (n, scenario, strategy), in that order
  std::vector<SweepSeries> sweeps;    ///< per (scenario, strategy) when more than one n
  std::vector<TrialRecord> records;   ///< every trial (keep_trials), in task order
  long long failed_trials = 0;        ///< trials that did not complete (lost or integration failure)
  int empty_cells = 0;                ///< cells where no trial completed (named in message)

  /// True when the status gives a result that may be used.
  bool IsSolutionUsable() const { return status == MonteCarloStatus::kCompleted; }
  /// One line: the status, the message and the main numbers.
  std::string BriefReport() const;
};

/// The work of a study as a flat list of tasks (n, scenario, strategy, trial), for splitting over
/// threads or processes. The constructor validates, bounds the work (kMaxTasks, kMaxWork) and
/// plans every n, one at a time, keeping only the main n's plan: Run plans another n again (the
/// same deterministic plan) while it runs that n's tasks, so one sweep plan is held at a time.
class MonteCarloWork {
 public:
  /// Throws std::invalid_argument naming the field and value for invalid input.
  MonteCarloWork(const MonteCarloProblem& problem, const MonteCarloOptions& options);
  /// The number of (cell, trial) tasks.
  long long TaskCount() const { return total_; }
  /// Runs tasks [begin, end) on options.threads threads; the records in task order.
  std::vector<TrialRecord> Run(long long begin, long long end) const;
  /// The summary of the records of all tasks, in task order (as Run gives them).
  MonteCarloSummary Summarize(std::vector<TrialRecord> records) const;
  /// The nominal plan of the main n.
  const NominalPlan& MainPlan() const { return *main_; }
  /// The partition sizes n of the run, the main n first.
  const std::vector<int>& Ns() const { return ns_; }

 private:
  TrialRecord RunTask(long long task, std::size_t i, const std::shared_ptr<const NominalPlan>& nominal) const;
  std::shared_ptr<const NominalPlan> Plan(std::size_t i) const;
  std::vector<SweepSeries> MakeSweeps(const MonteCarloSummary& summary) const;
  MonteCarloProblem problem_;
  MonteCarloOptions options_;
  std::vector<int> ns_;                      // main n first, then the sweep's others
  std::shared_ptr<const NominalPlan> main_;  // the main n's plan; the others are re-planned
  std::vector<NominalInfo> info_;            // per n (in ns_ order): what the summary reports
  std::vector<long long> offsets_;           // first task of each n
  long long total_ = 0;
  bool planned_ = true;
};

/// Runs every task on this process: MonteCarloWork(problem, options).Summarize(Run(0, TaskCount())).
MonteCarloSummary RunMonteCarlo(const MonteCarloProblem& problem, const MonteCarloOptions& options = {});

}  // namespace PLATEBALL_EXPORT
