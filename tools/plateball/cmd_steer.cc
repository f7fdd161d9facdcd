// `plateball steer PROBLEM.json`: exact arrival (issue 11): the impulses that bring the ball to the
// steer section's goal position and orientation exactly, along a reference (the plan section's
// path, else the shortest isoparallel path of the isoparallel section), as JSON and optionally
// the plate as SVG (reference dashed, exact impulsive trajectory solid).
#include <memory>
#include <sstream>
#include <string>

#include "common/command_registry.h"
#include "common/exact_output.h"
#include "common/exit_codes.h"
#include "common/json_output.h"
#include "common/output_file.h"
#include "common/problem_options.h"
#include "plateball/exact_arrival.h"
#include "plateball/isoparallel.h"
#include "plateball/task_adapters.h"

namespace plateball::tools {
namespace {

struct SteerCliOptions {
  ProblemOptions problem;
  long long impulses = 0;
  CLI::Option* impulses_opt = nullptr;
  std::string out;
  std::string svg;
  bool summary_only = false;
};

int RunSteer(const SteerCliOptions& o) {
  CheckOutputPaths({{"--out", o.out.empty() ? "-" : o.out}, {"--svg", o.svg}}, {{"PROBLEM.json", o.problem.file()}});
  const Problem p = o.problem.Load();
  const int n = o.impulses_opt->count() == 0
                    ? 0
                    : static_cast<int>(RequireIntegerInRange("--impulses", o.impulses, 3, 1'000'000));
  const std::string n_field = std::string(kCommandLine) + ": --impulses";
  ExactArrivalSetup setup;
  std::string reference = "plan.path";
  if (p.plan || !p.isoparallel) {
    setup = ExactArrivalSetupFor(p, n, n_field);
  } else {
    const IsoparallelSetup iso = IsoparallelSetupFor(p);
    const IsoparallelSummary solved = SolveIsoparallel(iso.problem, iso.options);
    if (!solved.IsSolutionUsable()) throw std::runtime_error("isoparallel reference: " + solved.BriefReport());
    setup = ExactArrivalSetupFor(p, solved.Shortest(), n, n_field);
    reference = "isoparallel shortest path";
  }
  const ExactArrivalSummary s = SolveExactArrival(setup.problem, setup.options);
  const ReplayResult replay = ReplayExactArrival(setup.problem, s.impulses);

  Json doc = HeaderJson("plateball", "steer", p, o.problem.file());
  doc["initial"] = InitialJson(p);
  doc["reference"] = Json{{"source", reference}, {"length", setup.problem.reference.Length()}};
  doc["goal"] = Json{{"x", ToJson(setup.problem.x1)}, {"rotation", RotationToJson(setup.problem.A1)}};
  Append(doc, ExactArrivalToJson(s, replay, !o.summary_only));
  WriteJson(doc, o.out);
  if (!o.svg.empty()) {
    std::ostringstream title;
    title.precision(3);
    title << (p.name.empty() ? std::string("steer") : p.name) << ": n = " << s.impulses.size()
          << ", arrival errors " << replay.position_error << ", " << replay.orientation_error << " rad";
    DrawExactArrival(setup.problem, s, title.str(), o.svg);
  }
  return s.IsSolutionUsable() ? kExitSuccess : kExitNoSolution;
}

std::function<int()> SetupSteer(CLI::App& sub) {
  auto o = std::make_shared<SteerCliOptions>();
  o->problem.Add(sub);
  o->impulses_opt = sub.add_option("--impulses", o->impulses, "impulse count n >= 3 (overrides steer.impulses)");
  sub.add_option("--out", o->out, "write the JSON to this file instead of standard output (\"-\": standard output)");
  sub.add_option("--svg", o->svg, "draw the plate to this SVG file (reference dashed, trajectory solid)");
  sub.add_flag("--summary-only", o->summary_only, "omit the per-impulse records");
  sub.footer(
      "Exact arrival (issue 11): corrects the paper's plan along the reference (the plan section's path,\n"
      "else the shortest isoparallel path) so that the ball reaches steer.goal with steer.goal_orientation:\n"
      "per impulse the time, position, delta psi, delta omega and the upper plate's velocity change; the\n"
      "arrival errors, those of an independent re-integration, the deviation from the reference.\n"
      "Example: plateball steer problems/figure7_exact.json --summary-only\n"
      "Exit codes: 0 arrived, 2 usage, 3 invalid input, 4 goal not reached (closest arrival reported),\n"
      "5 unreadable file.");
  return [o] { return RunSteer(*o); };
}

const CommandRegistrar kRegistrar{
    {"steer", "impulses that reach a goal position and orientation exactly along a reference (JSON, SVG)",
     SetupSteer}};

}  // namespace
}  // namespace plateball::tools
