#include "plateball/monte_carlo.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <set>
#include <sstream>
#include <stdexcept>
#include <variant>

#include "check.h"
#include "parallel_for.h"
#include "partition_internal.h"
#include "plateball/convergence.h"

namespace plateball {

std::string ToString(MonteCarloStatus status) {
  switch (status) {
    case MonteCarloStatus::kNotRun:
      return "not_run";
    case MonteCarloStatus::kCompleted:
      return "completed";
    case MonteCarloStatus::kNominalPlanFailed:
      return "nominal_plan_failed";
  }
  return "unknown";
}

std::string MonteCarloOptions::Validate() const {
  if (threads < 1 || threads > 256) return internal::InvalidValueMessage("threads", threads, "must be in [1, 256]");
  if (sweep_trials < 0 || sweep_trials > kMaxTrials)
    return internal::InvalidValueMessage(
        "sweep_trials", sweep_trials, "must be in [0, " + std::to_string(kMaxTrials) + "] (0: trials)");
  std::string e = plan.Validate();
  if (!e.empty()) return "plan: " + e;
  e = execution.Validate();
  return e.empty() ? "" : "execution: " + e;
}

Distribution Distribute(std::vector<double> values) {
  Distribution d;
  if (values.empty()) return d;
  std::sort(values.begin(), values.end());
  auto quantile = [&values](double p) {
    const double h = p * static_cast<double>(values.size() - 1);
    const std::size_t lo = static_cast<std::size_t>(std::floor(h));
    const std::size_t hi = std::min(lo + 1, values.size() - 1);
    return values[lo] + (h - static_cast<double>(lo)) * (values[hi] - values[lo]);
  };
  d.median = quantile(0.5);
  d.p95 = quantile(0.95);
  d.max = values.back();
  double sum = 0.0;
  for (double v : values) sum += v;
  d.mean = sum / static_cast<double>(values.size());
  return d;
}

std::string MonteCarloSummary::BriefReport() const {
  std::ostringstream os;
  os.precision(4);
  os << "MonteCarlo: " << ToString(status) << ", " << records.size() << " trials";
  if (!cells.empty()) os << ", n = " << cells.front().n;
  if (failed_trials > 0) os << ", " << failed_trials << " not completed";
  const bool scenarios = !cells.empty() && cells.back().scenario > 0;
  for (const MonteCarloCell& c : cells) {
    if (c.n != cells.front().n) break;
    os << "; " << ToString(c.strategy);
    if (scenarios) os << " (scenario " << c.scenario << ")";
    if (!c.orientation_error || !c.position_error) {
      os << ": no trial completed";
      continue;
    }
    os << ": orientation error median " << c.orientation_error->median << " rad, p95 " << c.orientation_error->p95
       << ", position error median " << c.position_error->median;
  }
  if (!message.empty()) os << " (" << message << ")";
  return os.str();
}

namespace {

// The partition of `plan` with n segments (a single uniform rule), for the sweep.
PlanProblem WithN(const PlanProblem& plan, int n) {
  PlanProblem p = plan;
  if (std::holds_alternative<UniformParameter>(p.partition.front()))
    p.partition = {UniformParameter{n}};
  else
    p.partition = {UniformArcLength{n}};
  return p;
}

void ValidateProblem(const MonteCarloProblem& p, const MonteCarloOptions& o) {
  internal::ThrowIfInvalid(o.Validate());
  if (p.trials < 1 || p.trials > MonteCarloOptions::kMaxTrials)
    internal::ThrowInvalid("trials", p.trials, "must be in [1, " + std::to_string(MonteCarloOptions::kMaxTrials) + "]");
  if (p.strategies.empty() || p.strategies.size() > 3)
    internal::ThrowInvalid("strategies (count)", static_cast<int>(p.strategies.size()), "must be 1 ... 3");
  if (std::set<ExecutionStrategy>(p.strategies.begin(), p.strategies.end()).size() != p.strategies.size())
    internal::ThrowInvalid("strategies", "(repeated)", "give each strategy once");
  if (p.scenarios.empty() || p.scenarios.size() > 64)
    internal::ThrowInvalid("scenarios (count)", static_cast<int>(p.scenarios.size()), "must be 1 ... 64");
  for (std::size_t i = 0; i < p.scenarios.size(); ++i) {
    const std::string e = p.scenarios[i].errors.Validate();
    if (!e.empty()) throw std::invalid_argument("scenarios[" + std::to_string(i) + "]." + e);
  }
  if (p.sweep_n.empty()) return;
  if (p.main_plan)
    internal::ThrowInvalid("sweep_n", p.sweep_n.front(), "not with a given main_plan (its n is not the partition's)");
  ValidatePartitionSizes(p.sweep_n, "sweep_n");
  const bool uniform = p.plan.partition.size() == 1 && !std::holds_alternative<ExplicitTaus>(p.plan.partition.front());
  if (!uniform) internal::ThrowInvalid("sweep_n", p.sweep_n.front(), "needs a single uniform partition rule to vary n");
  // An n too small for a closed path (or too large for a short one) is named by its entry.
  for (std::size_t i = 0; i < p.sweep_n.size(); ++i)
    internal::MakePartition(
        p.plan.path, WithN(p.plan, p.sweep_n[i]).partition, "plan.partition", "sweep_n[" + std::to_string(i) + "]");
}

// Main n: the partition's (for a sweep a single uniform rule), else the nominal plan's segments.
int MainN(const PlanProblem& plan) {
  if (plan.partition.size() == 1) {
    if (const auto* u = std::get_if<UniformParameter>(&plan.partition.front())) return u->n;
    if (const auto* a = std::get_if<UniformArcLength>(&plan.partition.front())) return a->n;
  }
  return 0;
}

}  // namespace

MonteCarloWork::MonteCarloWork(const MonteCarloProblem& problem, const MonteCarloOptions& options)
    : problem_(problem), options_(options) {
  ValidateProblem(problem, options);
  options_.progress = nullptr;  // Run takes it from `options` each time
  std::vector<int> others;
  for (int n : problem.sweep_n)
    if (n != MainN(problem.plan)) others.push_back(n);
  std::sort(others.begin(), others.end());
  main_ =
      std::make_shared<NominalPlan>(problem.main_plan ? MakeNominalPlan(problem.plan, options.plan, *problem.main_plan)
                                                      : MakeNominalPlan(problem.plan, options.plan));
  ns_.push_back(main_->plan.segments);
  for (int n : others) ns_.push_back(n);
  // The tasks and the work up front, before the sweep's plans (each n also plans once, about n
  // impulses of work: fewer than its trials execute).
  const bool exact =
      std::find(problem.strategies.begin(), problem.strategies.end(), ExecutionStrategy::kFeedbackExact) !=
      problem.strategies.end();
  const long long w = options.execution.exact_window, per_trial_exact = exact ? w * w * w : 0;
  const long long scenarios = static_cast<long long>(problem.scenarios.size());
  const long long strategies = static_cast<long long>(problem.strategies.size());
  long long work = 0;
  for (std::size_t i = 0; i < ns_.size(); ++i) {
    const long long t = i == 0 || options.sweep_trials == 0 ? problem.trials : options.sweep_trials;
    offsets_.push_back(total_);
    total_ += scenarios * strategies * t;
    work += scenarios * t * (strategies * ns_[i] + per_trial_exact);
  }
  if (total_ > MonteCarloOptions::kMaxTasks)
    internal::ThrowInvalid("trials",
                           problem.trials,
                           "the study would run " + std::to_string(total_) +
                               " trials (cells x trials over all n), more than " +
                               std::to_string(MonteCarloOptions::kMaxTasks));
  if (work > MonteCarloOptions::kMaxWork)
    internal::ThrowInvalid("trials",
                           problem.trials,
                           "the study would execute about " + std::to_string(work) +
                               " impulses (the sum over cells of trials x (n + W^3 with feedback_exact)), more than " +
                               std::to_string(MonteCarloOptions::kMaxWork) + ": fewer trials, n or sweep_n");
  for (std::size_t i = 0; i < ns_.size(); ++i) {
    const std::shared_ptr<const NominalPlan> p = Plan(i);  // the sweep's plans one at a time
    info_.push_back({ns_[i],
                     p->plan.status,
                     p->plan.message,
                     p->plan_orientation_error,
                     p->plan.measured_error,
                     p->plan.total_time});
    planned_ = planned_ && p->plan.IsSolutionUsable();
    // Pulses longer than a flight are invalid input, found before any trial runs.
    for (std::size_t k = 0; k < problem.scenarios.size() && p->plan.IsSolutionUsable(); ++k) {
      const std::string e = PulseScheduleError(*p, problem.scenarios[k].errors);
      if (!e.empty()) throw std::invalid_argument("scenarios[" + std::to_string(k) + "]." + e);
    }
  }
  if (!planned_) total_ = 0;
  options_.progress = options.progress;
}

std::shared_ptr<const NominalPlan> MonteCarloWork::Plan(std::size_t i) const {
  if (i == 0) return main_;
  return std::make_shared<NominalPlan>(MakeNominalPlan(WithN(problem_.plan, ns_[i]), options_.plan));
}

TrialRecord MonteCarloWork::RunTask(long long task,
                                    std::size_t i,
                                    const std::shared_ptr<const NominalPlan>& nominal) const {
  const long long trials = i == 0 || options_.sweep_trials == 0 ? problem_.trials : options_.sweep_trials;
  const long long local = task - offsets_[i];
  const long long cell = local / trials;
  const int strategies = static_cast<int>(problem_.strategies.size());
  ExecutionProblem ep;
  ep.nominal = nominal;
  ep.strategy = problem_.strategies[static_cast<std::size_t>(cell % strategies)];
  const int scenario = static_cast<int>(cell / strategies);
  ep.errors = problem_.scenarios[static_cast<std::size_t>(scenario)].errors;
  ep.seed = problem_.seed;
  ep.trial = static_cast<std::uint64_t>(local % trials);
  const ExecutionSummary s = Execute(ep, options_.execution);
  TrialRecord r;
  r.n = ns_[i];
  r.scenario = scenario;
  r.strategy = ep.strategy;
  r.trial = static_cast<std::int64_t>(ep.trial);
  r.status = s.status;
  r.position_error = s.position_error;
  r.orientation_error = s.orientation_error;
  r.max_pass_miss = s.max_pass_miss;
  r.total_time = s.total_time;
  r.missed_pass_points = s.missed_pass_points;
  return r;
}

std::vector<TrialRecord> MonteCarloWork::Run(long long begin, long long end) const {
  begin = std::clamp(begin, 0LL, total_);
  end = std::clamp(end, begin, total_);
  const int count = static_cast<int>(end - begin);
  std::vector<TrialRecord> out(static_cast<std::size_t>(count));
  const int threads = std::max(1, std::min(options_.threads, count));
  std::atomic<long long> done{0};
  // The tasks of one n at a time, with that n's plan (the sweep's plans are not all held at once).
  for (std::size_t i = 0; i < ns_.size(); ++i) {
    const long long n_end = i + 1 < ns_.size() ? offsets_[i + 1] : total_;
    const long long from = std::max(begin, offsets_[i]), to = std::min(end, n_end);
    if (from >= to) continue;
    const std::shared_ptr<const NominalPlan> nominal = Plan(i);
    internal::ParallelFor(static_cast<int>(to - from), threads, [&](int j) {
      const long long task = from + j;
      out[static_cast<std::size_t>(task - begin)] = RunTask(task, i, nominal);
      const long long d = ++done;
      if (options_.progress) options_.progress(d, count);
    });
  }
  if (options_.progress) options_.progress(count, count);
  return out;
}

namespace {

MonteCarloCell MakeCell(const std::vector<TrialRecord>& records, std::size_t first, std::size_t count) {
  MonteCarloCell c;
  const TrialRecord& r0 = records[first];
  c.n = r0.n;
  c.scenario = r0.scenario;
  c.strategy = r0.strategy;
  c.trials = static_cast<int>(count);
  std::vector<double> pos, ori, miss, missed, time;
  for (std::size_t i = first; i < first + count; ++i) {
    const TrialRecord& r = records[i];
    if (r.status != ExecutionStatus::kCompleted) continue;
    ++c.completed;
    pos.push_back(r.position_error);
    ori.push_back(r.orientation_error);
    miss.push_back(r.max_pass_miss);
    missed.push_back(r.missed_pass_points);
    time.push_back(r.total_time);
  }
  if (c.completed == 0) return c;  // no distribution: not zeros
  c.position_error = Distribute(pos);
  c.orientation_error = Distribute(ori);
  c.max_pass_miss = Distribute(miss);
  c.missed_pass_points = Distribute(missed);
  c.total_time = Distribute(time);
  return c;
}

}  // namespace

MonteCarloSummary MonteCarloWork::Summarize(std::vector<TrialRecord> records) const {
  if (static_cast<long long>(records.size()) != total_)
    throw std::logic_error("MonteCarloWork::Summarize: " + std::to_string(records.size()) + " records for " +
                           std::to_string(total_) + " tasks");
  MonteCarloSummary s;
  s.status = planned_ ? MonteCarloStatus::kCompleted : MonteCarloStatus::kNominalPlanFailed;
  s.message.clear();
  for (const NominalInfo& info : info_) {
    s.nominal.push_back(info);
    if (info.status != PlanStatus::kSuccess && s.message.empty())
      s.message = "the nominal plan with n = " + std::to_string(info.n) + " failed: " + info.message;
  }
  std::sort(s.nominal.begin(), s.nominal.end(), [](const NominalInfo& a, const NominalInfo& b) { return a.n < b.n; });
  const std::size_t per_n = problem_.scenarios.size() * problem_.strategies.size();
  for (std::size_t i = 0; planned_ && i < ns_.size(); ++i) {
    const long long end = i + 1 < ns_.size() ? offsets_[i + 1] : total_;
    const std::size_t trials = static_cast<std::size_t>(end - offsets_[i]) / per_n;
    for (std::size_t c = 0; c < per_n; ++c)
      s.cells.push_back(MakeCell(records, static_cast<std::size_t>(offsets_[i]) + c * trials, trials));
  }
  for (const TrialRecord& r : records) s.failed_trials += r.status != ExecutionStatus::kCompleted;
  std::string empty;
  for (const MonteCarloCell& c : s.cells) {
    if (c.completed > 0) continue;
    ++s.empty_cells;
    empty += std::string(s.empty_cells > 1 ? "; " : "") + ToString(c.strategy) + " at n = " + std::to_string(c.n);
    if (problem_.scenarios.size() > 1) empty += " (scenario " + std::to_string(c.scenario) + ")";
  }
  if (s.empty_cells > 0 && s.message.empty())
    s.message = "no trial completed in " + std::to_string(s.empty_cells) + " cell" + (s.empty_cells > 1 ? "s" : "") +
                (ns_.size() > 1 ? " (no distribution; missing from the sweep's fits): " : " (no distribution): ") +
                empty;
  if (planned_ && ns_.size() > 1) s.sweeps = MakeSweeps(s);
  if (options_.keep_trials) s.records = std::move(records);
  return s;
}

std::vector<SweepSeries> MonteCarloWork::MakeSweeps(const MonteCarloSummary& s) const {
  std::vector<SweepSeries> out;
  const std::size_t per_n = problem_.scenarios.size() * problem_.strategies.size();
  std::vector<std::size_t> order(ns_.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [this](std::size_t a, std::size_t b) { return ns_[a] < ns_[b]; });
  for (std::size_t c = 0; c < per_n; ++c) {
    SweepSeries series;
    series.scenario = s.cells[c].scenario;
    series.strategy = s.cells[c].strategy;
    std::vector<double> xn;
    for (std::size_t i : order) {
      const MonteCarloCell& cell = s.cells[i * per_n + c];
      series.n.push_back(ns_[i]);
      xn.push_back(ns_[i]);
      series.median_orientation_error.push_back(
          cell.orientation_error ? std::optional<double>(cell.orientation_error->median) : std::nullopt);
      series.median_position_error.push_back(cell.position_error ? std::optional<double>(cell.position_error->median)
                                                                 : std::nullopt);
      series.plan_orientation_error.push_back(info_[i].orientation_error);
    }
    std::vector<double> x_data, y_data;  // the n with data: a missing n is left out of the fit
    for (std::size_t i = 0; i < xn.size(); ++i) {
      if (series.Missing(i)) continue;
      x_data.push_back(xn[i]);
      y_data.push_back(*series.median_orientation_error[i]);
    }
    series.slope = LogLogSlope(x_data, y_data);
    series.plan_slope = LogLogSlope(xn, series.plan_orientation_error);
    for (std::size_t i = 0; i + 1 < xn.size(); ++i)
      series.local_slopes.push_back(
          series.Missing(i) || series.Missing(i + 1)
              ? std::nullopt
              : LogLogSlope({xn[i], xn[i + 1]},
                            {*series.median_orientation_error[i], *series.median_orientation_error[i + 1]}));
    out.push_back(std::move(series));
  }
  return out;
}

MonteCarloSummary RunMonteCarlo(const MonteCarloProblem& problem, const MonteCarloOptions& options) {
  const MonteCarloWork work(problem, options);
  return work.Summarize(work.Run(0, work.TaskCount()));
}

}  // namespace plateball
