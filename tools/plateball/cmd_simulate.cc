// `plateball simulate`: sample the free rolling of the ball (free_motion.h) and print it as JSON.
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/command_registry.h"
#include "common/exit_codes.h"
#include "common/json_output.h"
#include "common/limits.h"
#include "common/number_format.h"
#include "common/output_file.h"
#include "common/problem_options.h"
#include "common/progress.h"
#include "common/sample_table.h"
#include "common/units.h"
#include "plateball/free_motion.h"
#include "plateball/task_adapters.h"

namespace plateball::tools {
namespace {

struct SimulateOptions {
  ProblemOptions problem;
  double t_end = 0.0;
  long long samples = 0;
  std::string out;
  std::string csv;
  CLI::Option* t_end_opt = nullptr;
  CLI::Option* samples_opt = nullptr;
};

int RunSimulate(const SimulateOptions& o) {
  // With --csv only, the JSON document is not written (unless --out names a file).
  CheckOutputPaths({{"--out", o.out}, {"--csv", o.csv}}, {{"PROBLEM.json", o.problem.file()}});
  const Problem p = o.problem.Load();
  SimulateTask task = p.simulate.value_or(SimulateTask{});
  if (o.t_end_opt->count() > 0) task.t_end = RequirePositiveOption("--t-end", o.t_end);
  if (o.samples_opt->count() > 0)
    task.samples = static_cast<int>(RequireIntegerInRange("--samples", o.samples, 2, kMaxSamples));
  // free_motion.h evaluates |t| <= 1e12 periods: checked here to name the option.
  const double period = 2.0 * M_PI / std::sqrt(p.mu);
  if (task.t_end > kMaxPeriods * period)
    ThrowInvalidInput(
        o.t_end_opt->count() > 0 ? CommandLineField("--t-end") : p.source + ": simulate.t_end",
        FormatNumber(task.t_end),
        "must be <= 1e12 periods (" + FormatNumber(kMaxPeriods * period) + " at mu = " + FormatNumber(p.mu) + ")");

  const FreeMotion motion = FreeMotionFor(p);

  Json doc = HeaderJson("plateball", "simulate", p, o.problem.file());
  const MotionSample start = motion.At(0.0);
  Json initial = InitialJson(p);
  Append(initial,
         Json{{"orientation", ToJson(motion.start().A0)},
              {"z", ToJson(motion.start().state.z)},
              {"omega", ToJson(motion.start().state.omega)},
              {"energy", start.energy}});
  doc["initial"] = std::move(initial);
  doc["period"] = motion.Period();
  doc["drift_per_period"] = ToJson(motion.DriftPerPeriod());
  doc["mean_velocity"] = ToJson(motion.MeanVelocity());
  doc["stored_steps_per_period"] = motion.StoredSteps();
  doc["t_end"] = task.t_end;
  AddPhysicalUnits(p, &doc);
  // Streamed (sample_table.h): sample i at t_end i/(n-1), as FreeMotion::Sample, one at a time.
  const auto n = static_cast<std::size_t>(task.samples);
  const SampleSource sample = [&](std::size_t i) {
    return ToJson(motion.At(task.t_end * static_cast<double>(i) / static_cast<double>(n - 1)));
  };
  const bool json = o.csv.empty() || !IsStandardOutput(o.out);
  if (!o.csv.empty()) {
    Progress progress(json ? "plateball simulate (CSV)" : "plateball simulate", static_cast<double>(n));
    WriteSampleCsv(o.csv, n, sample, &progress);
  }
  if (json) {
    Progress progress(o.csv.empty() ? "plateball simulate" : "plateball simulate (JSON)", static_cast<double>(n));
    WriteSampleDocument(o.out, std::move(doc), n, sample, &progress);
  }
  return kExitSuccess;
}

std::function<int()> SetupSimulate(CLI::App& sub) {
  auto o = std::make_shared<SimulateOptions>();
  o->problem.Add(sub, ProblemOptions::Seed::kNone);  // deterministic: no --seed
  o->t_end_opt = sub.add_option("--t-end", o->t_end, "end time > 0 (default: the file's simulate.t_end, else 10)");
  o->samples_opt =
      sub.add_option("--samples",
                     o->samples,
                     "number of equally spaced samples on [0, t-end], 2 ... 100000 (default: the file's, else 101)");
  sub.add_option("--out", o->out, "write the JSON to this file instead of standard output");
  sub.add_option("--csv",
                 o->csv,
                 "write the samples as CSV to this file (\"-\": standard output); the JSON is then written only "
                 "with --out FILE");
  sub.footer(
      "Prints JSON (docs/output_contract.md): the header (model, tolerances, seed, problem), the initial state,\n"
      "period T = 2 pi/sqrt(mu), drift of the contact point per period, and per sample t, angles (theta, phi,\n"
      "psi), z, x, orientation (3x3, rows), omega, energy.\n"
      "Example: plateball simulate problems/simulate_example.json --samples 3\n"
      "         plateball simulate --lambda 2 --theta 1.0472 --phi 0 --psi 0 --mu 4 --t-end 3.14159 --samples 2\n"
      "Exit codes: 0 ok, 2 usage, 3 invalid input, 4 computation failed, 5 unreadable file.");
  return [o] { return RunSimulate(*o); };
}

const CommandRegistrar kRegistrar{
    {"simulate",
     "sample the free rolling of the ball (angles, z, x, orientation, omega, energy) as JSON",
     SetupSimulate}};

}  // namespace
}  // namespace plateball::tools
