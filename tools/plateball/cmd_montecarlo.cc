// `plateball montecarlo PROBLEM.json`: executes the plan of the problem's plan section many times
// under seeded errors (error_model.h) with the open-loop, feedback and exact re-solve strategies
// (execution.h) and prints the distributions of the final errors (monte_carlo.h) as JSON; per-trial
// CSV, SVG charts, a progress line with an ETA on stderr. Under mpirun/srun (a build with MPI)
// the trials are split over the ranks (montecarlo_ranks.h); the output is the same for any split.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "common/command_registry.h"
#include "common/exit_codes.h"
#include "common/json_output.h"
#include "common/number_format.h"
#include "common/output_file.h"
#include "common/problem_options.h"
#include "common/progress.h"
#include "common/rig_plan_output.h"
#include "montecarlo_charts.h"
#include "montecarlo_ranks.h"
#include "plateball/monte_carlo.h"
#include "plateball/task_adapters.h"

namespace plateball::tools {
namespace {

struct MonteCarloCliOptions {
  ProblemOptions problem;
  long long trials = 100;
  std::vector<std::string> strategies{"open_loop", "feedback"};
  std::vector<std::string> noise;
  long long n = 0;
  CLI::Option* n_opt = nullptr;
  std::vector<long long> sweep_n;
  long long sweep_trials = 0;
  double miss_tolerance = 1e-3;
  long long exact_window = 12;
  long long threads = 0;
  std::string out, csv, svg, svg_sweep;
  bool timings = false;
  bool rig_check_only = false;
};

std::string Option(const char* name) { return CommandLineField(name); }

struct Study {
  MonteCarloProblem problem;
  MonteCarloOptions options;
  RigNominal rig;  // with a rig section: the main plan and its rig record (PlanOnRig)
};

// The command line as the library's problem and options (every value checked, naming the option).
// With a rig section the main plan is planned here, as `plateball plan` plans it (PlanOnRig).
Study BuildStudy(const MonteCarloCliOptions& o, const Problem& p) {
  const int n = o.n_opt->count() == 0 ? 0 : static_cast<int>(RequireIntegerInRange("--impulses", o.n, 1, 10'000));
  if (n > 0) RequirePartitionSteps("--impulses", n, p);
  const PlanSetup setup = PlanSetupFor(p, n, Option("--impulses"));
  MonteCarloProblem mp;
  MonteCarloOptions mo;
  mp.plan = setup.problem;
  mo.plan = setup.options;
  mp.trials = static_cast<int>(RequireIntegerInRange("--trials", o.trials, 1, MonteCarloOptions::kMaxTrials));
  mp.seed = p.seed;
  mp.strategies.clear();
  for (const std::string& s : o.strategies) mp.strategies.push_back(ParseExecutionStrategy(s, Option("--strategy")));
  const std::vector<std::string> noise = o.noise.empty() ? std::vector<std::string>{"impulse_magnitude=1e-3"} : o.noise;
  for (const std::string& spec : noise) {
    const ErrorModel e = ParseErrorModel(spec, Option("--noise"));
    mp.scenarios.push_back({ToString(e), e});
  }
  for (long long v : o.sweep_n) {
    mp.sweep_n.push_back(static_cast<int>(RequireIntegerInRange("--sweep-n", v, 1, 10'000)));
    RequirePartitionSteps("--sweep-n", v, p);
    PlanSetupFor(p, static_cast<int>(v), Option("--sweep-n"));  // an n too small for a closed path
  }
  mo.sweep_trials =
      static_cast<int>(RequireIntegerInRange("--sweep-trials", o.sweep_trials, 0, MonteCarloOptions::kMaxTrials));
  if (!(o.miss_tolerance > 0 && o.miss_tolerance <= 1e6))
    ThrowInvalidInput(Option("--miss-tolerance"), FormatNumber(o.miss_tolerance), "must be a number in (0, 1e6]");
  mo.execution.miss_tolerance = o.miss_tolerance;
  mo.execution.exact_window =
      static_cast<int>(RequireIntegerInRange("--exact-window", o.exact_window, 3, ExecutionOptions::kMaxExactWindow));
  mo.threads = ThreadsOption(o.threads);
  Study study{mp, mo, {}};
  if (p.rig.Empty()) return study;
  if (!o.rig_check_only && !mp.sweep_n.empty())
    ThrowInvalidInput(Option("--sweep-n"),
                      std::to_string(mp.sweep_n.front()),
                      "with a rig section the partition is refined to honour the limits (n is not the study's "
                      "variable): drop --sweep-n, or plan the partitions as given with --rig-check-only");
  study.rig = PlanOnRig(p, setup, o.rig_check_only);
  if (!o.rig_check_only) study.problem.main_plan = study.rig.plan;
  return study;
}

// null for a cell where no trial completed (it has no distribution).
Json DistributionJson(const std::optional<Distribution>& d) {
  if (!d) return Json(nullptr);
  return Json{{"median", d->median}, {"p95", d->p95}, {"max", d->max}, {"mean", d->mean}};
}

Json NullableNumber(const std::optional<double>& v) { return v ? Json(*v) : Json(nullptr); }

Json NullableSlope(const std::optional<double>& s) { return s ? Json(*s) : Json(nullptr); }

Json OptionsJson(const MonteCarloProblem& mp, const MonteCarloOptions& mo, int main_n) {
  Json strategies = Json::array(), scenarios = Json::array();
  for (ExecutionStrategy s : mp.strategies) strategies.push_back(ToString(s));
  for (const MonteCarloScenario& s : mp.scenarios) {
    const ErrorModel& e = s.errors;
    scenarios.push_back(Json{{"name", s.name},
                             {"errors",
                              Json{{"impulse_magnitude", e.impulse_magnitude},
                                   {"impulse_angle", e.impulse_angle},
                                   {"timing", e.timing},
                                   {"energy_loss", e.energy_loss},
                                   {"lambda", e.lambda},
                                   {"observation", e.observation},
                                   {"pulse_duration", e.pulse_duration},
                                   {"pulse_causal", e.pulse_causal}}}});
  }
  return Json{{"trials", mp.trials},
              {"impulses", main_n},
              {"strategies", strategies},
              {"scenarios", scenarios},
              {"sweep_n", mp.sweep_n},
              {"sweep_trials", mo.sweep_trials == 0 ? mp.trials : mo.sweep_trials},
              {"miss_tolerance", mo.execution.miss_tolerance},
              {"exact_window", mo.execution.exact_window}};
}

Json NominalJson(const NominalInfo& n) {
  return Json{{"n", n.n},
              {"status", ToString(n.status)},
              {"usable", n.status == PlanStatus::kSuccess},
              {"message", n.message},
              {"orientation_error", n.orientation_error},
              {"measured_error", n.measured_error},
              {"total_time", n.total_time}};
}

Json ResultsJson(const MonteCarloProblem& mp, const MonteCarloSummary& s) {
  Json nominal = Json::array(), results = Json::array(), sweeps = Json::array();
  for (const NominalInfo& n : s.nominal) nominal.push_back(NominalJson(n));
  for (const MonteCarloCell& c : s.cells) {
    Json cell{{"n", c.n},
              {"scenario", mp.scenarios[static_cast<std::size_t>(c.scenario)].name},
              {"strategy", ToString(c.strategy)},
              {"trials", c.trials},
              {"completed", c.completed},
              {"position_error", DistributionJson(c.position_error)},
              {"orientation_error", DistributionJson(c.orientation_error)},
              {"max_pass_miss", DistributionJson(c.max_pass_miss)},
              {"missed_pass_points", DistributionJson(c.missed_pass_points)},
              {"total_time", DistributionJson(c.total_time)}};
    if (c.completed == 0) cell["note"] = "no trial completed";
    results.push_back(cell);
  }
  for (const SweepSeries& w : s.sweeps) {
    Json rows = Json::array();
    for (std::size_t i = 0; i < w.n.size(); ++i) {
      Json row{{"n", w.n[i]},
               {"median_orientation_error", NullableNumber(w.median_orientation_error[i])},
               {"median_position_error", NullableNumber(w.median_position_error[i])},
               {"plan_orientation_error", w.plan_orientation_error[i]}};
      if (w.Missing(i)) row["missing"] = "no trial completed: left out of slope and local_slopes";
      rows.push_back(row);
    }
    Json local = Json::array();
    for (const auto& l : w.local_slopes) local.push_back(NullableSlope(l));
    sweeps.push_back(Json{{"scenario", mp.scenarios[static_cast<std::size_t>(w.scenario)].name},
                          {"strategy", ToString(w.strategy)},
                          {"rows", rows},
                          {"slope", NullableSlope(w.slope)},
                          {"local_slopes", local},
                          {"plan_slope", NullableSlope(w.plan_slope)}});
  }
  Json out = ResultJson(ToString(s.status), s.IsSolutionUsable(), s.message, s.BriefReport());
  Append(out, Json{{"failed_trials", s.failed_trials}, {"nominal", nominal}, {"results", results}, {"sweep", sweeps}});
  return out;
}

// With a rig section the record of the main plan (as `plateball plan` writes it); with
// --rig-check-only a plan that exceeds the limits was run all the same, and the report says so.
void AddStudyRigRecord(const RigNominal& r, bool check_only, Json* doc) {
  if (r.rig.is_null()) return;
  if (!check_only || r.limits_met) {
    AddRigRecord(r, doc);
    return;
  }
  (*doc)["rig"] = r.rig;
  (*doc)["report"] = (*doc)["report"].get<std::string>() +
                     "; rig limits NOT met (--rig-check-only: the trials ran "
                     "on the plan as given): " +
                     r.message;
}

// The output of a study whose nominal plan cannot meet the rig's limits: no trial ran.
Json LimitsNotMetJson(const MonteCarloCliOptions& o, const Problem& p, const Study& study) {
  Json doc = HeaderJson("plateball", "montecarlo", p, o.problem.file());
  doc["initial"] = InitialJson(p);
  doc["initial"]["orientation"] = ToJson(study.rig.plan.A0);
  doc["options"] = OptionsJson(study.problem, study.options, study.rig.plan.segments);
  Append(doc, ResultJson("limits_not_met", false, study.rig.message, ""));
  const NominalPlan n = MakeNominalPlan(study.problem.plan, study.options.plan, study.rig.plan);
  const NominalInfo info{n.plan.segments,
                         n.plan.status,
                         n.plan.message,
                         n.plan_orientation_error,
                         n.plan.measured_error,
                         n.plan.total_time};
  Append(doc,
         Json{{"failed_trials", 0},
              {"nominal", Json::array({NominalJson(info)})},
              {"results", Json::array()},
              {"sweep", Json::array()}});
  AddRigRecord(study.rig, &doc);
  return doc;
}

std::string TrialsCsv(const MonteCarloProblem& mp, const std::vector<TrialRecord>& records) {
  std::string out =
      "n,scenario,strategy,trial,status,position_error,orientation_error,max_pass_miss,missed_pass_points,total_time\n";
  for (const TrialRecord& r : records) {
    out += std::to_string(r.n) + ",\"" + mp.scenarios[static_cast<std::size_t>(r.scenario)].name + "\"," +
           ToString(r.strategy) + "," + std::to_string(r.trial) + "," + ToString(r.status) + "," +
           FormatNumber(r.position_error) + "," + FormatNumber(r.orientation_error) + "," +
           FormatNumber(r.max_pass_miss) + "," + std::to_string(r.missed_pass_points) + "," +
           FormatNumber(r.total_time) + "\n";
  }
  return out;
}

int RunMonteCarloCommand(const MonteCarloCliOptions& o) {
  CheckOutputPaths(
      {{"--out", o.out.empty() ? "-" : o.out}, {"--csv", o.csv}, {"--svg", o.svg}, {"--svg-sweep", o.svg_sweep}},
      {{"PROBLEM.json", o.problem.file()}});
  const Ranks ranks;
  // Standard input reaches one process only: under MPI the other ranks would read nothing. Rank 0
  // says so once; the others end with the same exit code in silence.
  if (ranks.size() > 1 && o.problem.file() == "-") {
    if (ranks.rank() != 0) return kExitBadInput;
    ThrowInvalidInput("PROBLEM.json",
                      "-",
                      "standard input reaches rank 0 only: under MPI (" + std::to_string(ranks.size()) +
                          " ranks) give the problem as a file");
  }
  const Problem p = o.problem.Load();
  Study study = BuildStudy(o, p);
  MonteCarloProblem& mp = study.problem;
  MonteCarloOptions& mo = study.options;
  if (!o.svg_sweep.empty() && mp.sweep_n.empty())
    ThrowInvalidInput(Option("--svg-sweep"), o.svg_sweep, "needs --sweep-n");
  // A nominal plan the rig cannot execute is not run (unless --rig-check-only: the plan as given).
  if (!study.rig.limits_met && !o.rig_check_only) {
    if (ranks.rank() != 0) return kExitNoSolution;
    WriteJson(LimitsNotMetJson(o, p, study), o.out);
    return kExitNoSolution;
  }
  const auto start = std::chrono::steady_clock::now();
  // Rank 0 shows the trials of its own share (the ranks' shares differ by at most one trial).
  const std::string label = ranks.size() > 1
                                ? "plateball montecarlo (trials of rank 0 of " + std::to_string(ranks.size()) + ")"
                                : "plateball montecarlo (trials)";
  Progress progress = ranks.rank() == 0 ? Progress(label, 0) : Progress(label, 0, ProgressMode::kQuiet, false);
  mo.progress = [&progress](long long done, long long) { progress.Update(static_cast<double>(done)); };
  const MonteCarloWork work = [&] {
    try {
      return MonteCarloWork(mp, mo);
    } catch (const std::invalid_argument& e) {  // the library's bound of the study: name the options
      const std::string m = e.what(), field = "trials: ";
      if (m.rfind(field, 0) != 0) throw;
      throw std::invalid_argument(Option("--trials") + ": " + m.substr(field.size()) +
                                  " (the limit counts --trials, --sweep-trials, --impulses and --sweep-n together)");
    }
  }();
  const auto [begin, end] = ranks.Share(work.TaskCount());
  progress.SetTotal(static_cast<double>(end - begin));
  std::vector<TrialRecord> records = ranks.Gather(work.Run(begin, end));
  if (ranks.rank() != 0) return kExitSuccess;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const MonteCarloSummary s = work.Summarize(std::move(records));
  Json doc = HeaderJson("plateball", "montecarlo", p, o.problem.file());
  doc["initial"] = InitialJson(p);
  doc["initial"]["orientation"] = ToJson(work.MainPlan().plan.A0);
  doc["options"] = OptionsJson(mp, mo, work.Ns().front());
  Append(doc, ResultsJson(mp, s));
  AddStudyRigRecord(study.rig, o.rig_check_only, &doc);
  if (o.timings)
    doc["timing"] = Json{{"run_seconds", seconds},
                         {"seconds_per_trial", seconds / std::max(1.0, double(s.records.size()))},
                         {"ranks", ranks.size()},
                         {"threads", mo.threads}};
  WriteJson(doc, o.out);
  if (!o.csv.empty()) WriteOutput(o.csv, TrialsCsv(mp, s.records));
  if (!o.svg.empty()) WriteOutput(o.svg, RenderErrorDistributions(mp, s, work.MainPlan()));
  if (!o.svg_sweep.empty()) WriteOutput(o.svg_sweep, RenderErrorAgainstN(mp, s));
  return s.IsSolutionUsable() ? kExitSuccess : kExitNoSolution;
}

std::function<int()> SetupMonteCarlo(CLI::App& sub) {
  auto o = std::make_shared<MonteCarloCliOptions>();
  o->problem.Add(sub);
  sub.add_option("--trials", o->trials, "trials per strategy and error scenario (1 ... 10^6, default 100)");
  sub.add_option("--strategy",
                 o->strategies,
                 "open_loop, feedback, feedback_exact (comma-separated; default open_loop,feedback)")
      ->delimiter(',');
  sub.add_option("--noise",
                 o->noise,
                 "an error scenario KEY=VALUE[,KEY=VALUE] with keys impulse_magnitude, impulse_angle, timing, "
                 "energy_loss, lambda, observation, pulse_duration, pulse_causal (\"none\": no error); repeat for more "
                 "scenarios (default "
                 "impulse_magnitude=1e-3)");
  o->n_opt =
      sub.add_option("--impulses,--n", o->n, "impulses of the main plan, overrides plan.partition.n (--n: alias)");
  sub.add_option("--sweep-n", o->sweep_n, "further n for the error against n, e.g. 16,32,128,256")->delimiter(',');
  sub.add_option("--sweep-trials", o->sweep_trials, "trials per cell at the sweep's other n (default: --trials)");
  sub.add_option("--miss-tolerance", o->miss_tolerance, "a pass point farther than this is missed (default 1e-3)");
  sub.add_option(
      "--exact-window", o->exact_window, "feedback_exact: re-plan exactly while 3 ... W impulses remain (default 12)");
  sub.add_option("--threads", o->threads, "threads per process (default: the hardware's; results do not depend on it)");
  sub.add_option("--out", o->out, "write the JSON summary to this file instead of standard output");
  sub.add_option("--csv", o->csv, "write one line per trial to this CSV file");
  sub.add_option("--svg", o->svg, "draw the distributions of the final errors per strategy (SVG)");
  sub.add_option(
      "--svg-sweep", o->svg_sweep, "draw the median final error against n, log-log, with the fitted slopes (SVG)");
  sub.add_flag("--timings", o->timings, "add the wall time (the output then differs from run to run)");
  sub.add_flag("--rig-check-only",
               o->rig_check_only,
               "with a rig section: plan the partition as given, check it against the limits and run the trials "
               "whatever the check says (default: honour the limits as `plateball plan` does, and run no trial on "
               "a plan that cannot meet them)");
  sub.footer(
      "Executes the plan of plan.path under seeded errors, trial i of every cell drawing from (seed, i) alone.\n"
      "Under MPI (a build with Open MPI): mpirun -np K plateball montecarlo ... splits the trials over the\n"
      "ranks; rank 0 writes one output, byte-identical for any K and any --threads.\n"
      "Example: plateball montecarlo problems/circle.json --trials 200 --noise impulse_magnitude=1e-3\n"
      "With a rig section the nominal plan honours its limits as `plateball plan`'s does (\"rig\" is the same\n"
      "record); a plan that cannot meet them runs no trial (status limits_not_met).\n"
      "Exit codes: 0 ok, 2 usage, 3 invalid input, 4 the nominal plan failed or cannot meet the rig's limits,\n"
      "5 unreadable/unwritable file.");
  return [o] { return RunMonteCarloCommand(*o); };
}

const CommandRegistrar kRegistrar{
    {"montecarlo",
     "execute a plan many times under seeded errors: open loop, feedback, exact re-solve (JSON, CSV, SVG)",
     SetupMonteCarlo}};

}  // namespace
}  // namespace plateball::tools
