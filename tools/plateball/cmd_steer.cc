// `plateball steer PROBLEM.json`: exact arrival: the impulses that bring the ball to the
// steer section's goal position and orientation exactly, along a reference (the plan section's
// path, else the shortest isoparallel path of the isoparallel section), as JSON and optionally
// the plate as SVG (reference dashed, exact impulsive trajectory solid).
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>

#include "common/actuator_json.h"
#include "common/command_registry.h"
#include "common/exact_output.h"
#include "common/exit_codes.h"
#include "common/json_output.h"
#include "common/output_file.h"
#include "common/problem_options.h"
#include "common/progress.h"
#include "common/svg.h"
#include "common/units.h"
#include "plateball/exact_arrival.h"
#include "plateball/fewest_impulses.h"
#include "plateball/isoparallel.h"
#include "plateball/rig_reference.h"
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
  bool fewest = false;
  bool stop_at_goal = false;
  bool start_at_rest = false;
  long long max_impulses = 0;
  long long starts = 0;
  CLI::Option* max_impulses_opt = nullptr;
  CLI::Option* starts_opt = nullptr;
  ActuatorOptions actuator;
};

// A message of the solvers about the start, the goal or the search window ("x1: ...",
// "max_total_time: ...") with the problem file's field instead: "FILE: steer.goal: ...",
// "FILE: initial.x0: ...", "FILE: steer.fewest.max_total_time: ...". The start is the isoparallel
// section's when the file has one and no plan (task_adapters.h), else initial.x0.
std::string FileFieldsOfSearch(const std::string& message, const Problem& p, const std::string& file) {
  const std::string start = p.isoparallel && !p.plan ? "isoparallel.start" : "initial.x0";
  for (const auto& [name, field] : {std::pair<std::string, std::string>{"x1", "steer.goal"},
                                    {"x0", start},
                                    {"max_total_time", "steer.fewest.max_total_time"}})
    if (message.rfind(name + ": ", 0) == 0) return file + ": " + field + message.substr(name.size());
  return message;
}

// The fewest-impulse search (steer.fewest in the file, or --fewest-impulses).
int RunFewest(const SteerCliOptions& o, const Problem& p) {
  FewestImpulsesSetup setup = FewestImpulsesSetupFor(p);
  if (p.steer && p.steer->objective == ArrivalObjective::kTotalImpulse)
    ThrowInvalidInput(o.problem.file() + ": steer.objective",
                      "\"impulse\"",
                      "the fewest-impulse search ranks the arrivals of a count by total time (the Pareto table "
                      "reports each count's total impulse): use \"fewest\" or \"time\"");
  using O = FewestImpulsesOptions;
  if (o.max_impulses_opt->count() > 0)
    setup.options.max_impulses =
        static_cast<int>(RequireIntegerInRange("--max-impulses", o.max_impulses, 1, O::kMaxImpulses));
  if (o.starts_opt->count() > 0)
    setup.options.starts = static_cast<int>(RequireIntegerInRange("--starts", o.starts, 1, O::kMaxStarts));
  setup.problem.stop_at_goal = setup.problem.stop_at_goal || o.stop_at_goal;
  setup.problem.start_at_rest = setup.problem.start_at_rest || o.start_at_rest;
  const ActuatorContext actuator{p, o.actuator.Request(), ""};
  const FewestImpulsesSummary s = [&] {
    Progress progress("plateball steer: fewest-impulse search, starts tried", 0);
    setup.options.progress = [&progress](int, int starts) { progress.Update(starts); };
    try {
      return SolveFewestImpulses(setup.problem, setup.options);
    } catch (const std::invalid_argument& e) {  // the search's own limits name the file's fields
      throw std::invalid_argument(FileFieldsOfSearch(e.what(), p, o.problem.file()));
    }
  }();
  Json doc = HeaderJson("plateball", "steer", p, o.problem.file());
  doc["initial"] = InitialJson(p);
  doc["goal"] = Json{{"x", ToJson(setup.problem.x1)}, {"rotation", RotationToJson(setup.problem.A1)}};
  Append(doc, FewestImpulsesToJson(setup.problem, s, !o.summary_only, &actuator));
  AddPhysicalUnits(p, &doc);
  WriteJson(doc, o.out);
  const FewestImpulsesCount* f = s.Fewest();
  if (!o.svg.empty() && f && f->impulses == 0)
    std::cerr << "steer: --svg: value " << o.svg << ": not written: the goal is met at the start (0 impulses)\n";
  if (!o.svg.empty() && f && f->impulses > 0) {
    std::ostringstream title;
    title.precision(3);
    title << (p.name.empty() ? std::string("steer") : p.name) << ": fewest impulses n = " << f->impulses
          << ", T = " << f->total_time << ", path length " << f->path_length;
    DrawExactArrival(
        ReplayProblemFor(setup.problem, f->impulses), f->plan, title.str(), o.svg, "straight line to the goal");
  }
  return s.IsSolutionUsable() ? kExitSuccess : kExitNoSolution;
}

int RunSteer(const SteerCliOptions& o) {
  CheckOutputPaths({{"--out", o.out.empty() ? "-" : o.out}, {"--svg", o.svg}}, {{"PROBLEM.json", o.problem.file()}});
  const Problem p = o.problem.Load();
  if (o.fewest || (p.steer && (p.steer->fewest || p.steer->objective == ArrivalObjective::kFewest)))
    return RunFewest(o, p);
  for (const CLI::Option* search : {o.max_impulses_opt, o.starts_opt})  // options of the search only
    if (search->count() > 0)
      ThrowInvalidInput(CommandLineField(search->get_name()),
                        search->as<std::string>(),
                        "needs --fewest-impulses (or steer.fewest in the problem file)");
  const int n = o.impulses_opt->count() == 0
                    ? 0
                    : static_cast<int>(RequireIntegerInRange("--impulses", o.impulses, 3, 1'000'000));
  const std::string n_field = std::string(kCommandLine) + ": --impulses";
  ExactArrivalSetup setup;
  std::string reference = "plan.path";
  Json reference_limits;  // with a rig: the limits the reference breaks
  if (p.plan || !p.isoparallel) {
    setup = ExactArrivalSetupFor(p, n, n_field);
    if (!p.rig.Empty()) reference_limits = Json{{"breaks", PathLimitBreaks(setup.problem.reference, p.rig, p.x0)}};
  } else {
    const IsoparallelSetup iso = IsoparallelSetupFor(p);
    const IsoparallelSummary solved = SolveIsoparallel(iso.problem, iso.options);
    if (!solved.IsSolutionUsable()) throw std::runtime_error("isoparallel reference: " + solved.BriefReport());
    const ReferenceChoice choice =
        p.rig.Empty() ? ReferenceChoice{} : ChooseIsoparallelReference(solved, p.rig, solved.Shortest().start);
    setup = ExactArrivalSetupFor(p, solved.solutions[choice.index], n, n_field);
    reference = choice.index == 0 ? "isoparallel shortest path"
                                  : "isoparallel solution " + std::to_string(choice.index) +
                                        " (the shortest within the rig's plate, obstacles and stroke)";
    if (!p.rig.Empty())
      reference_limits = Json{{"solution_index", choice.index},
                              {"shortest_breaks", choice.shortest_breaks},
                              {"breaks", choice.chosen_breaks}};
  }
  setup.problem.stop_at_goal = setup.problem.stop_at_goal || o.stop_at_goal;
  setup.problem.start_at_rest = setup.problem.start_at_rest || o.start_at_rest;
  const ActuatorContext actuator{p, o.actuator.Request(), ""};
  const ExactArrivalSummary s = [&] {
    Progress progress("plateball steer", 0);  // one solve: the elapsed time
    try {
      return SolveExactArrival(setup.problem, setup.options);
    } catch (const std::invalid_argument& e) {  // the start and goal checks name the file's fields
      throw std::invalid_argument(FileFieldsOfSearch(e.what(), p, o.problem.file()));
    }
  }();
  const ReplayResult replay = ReplayExactArrival(setup.problem, s.impulses);

  Json doc = HeaderJson("plateball", "steer", p, o.problem.file());
  doc["initial"] = InitialJson(p);
  doc["reference"] = Json{{"source", reference}, {"length", setup.problem.reference.Length()}};
  if (!reference_limits.is_null()) doc["reference"]["limits"] = reference_limits;
  doc["goal"] = Json{{"x", ToJson(setup.problem.x1)}, {"rotation", RotationToJson(setup.problem.A1)}};
  Append(doc, ExactArrivalToJson(s, replay, !o.summary_only, &actuator));
  std::optional<RigCheck> check;
  if (HasRigSection(setup.problem)) {
    check = CheckRigLimits(setup.problem, s);
    doc["rig"] = RigJson(setup.problem, s, *check);
  }
  AddPhysicalUnits(p, &doc);
  WriteJson(doc, o.out);
  if (!o.svg.empty()) {
    std::ostringstream title;
    title.precision(3);
    title << (p.name.empty() ? std::string("steer") : p.name) << ": n = " << s.impulses.size() << ", arrival errors "
          << replay.position_error << ", " << replay.orientation_error << " rad";
    DrawExactArrival(setup.problem, s, title.str(), o.svg);
  }
  return s.IsSolutionUsable() && (!check || check->passed) ? kExitSuccess : kExitNoSolution;
}

std::function<int()> SetupSteer(CLI::App& sub) {
  auto o = std::make_shared<SteerCliOptions>();
  o->problem.Add(sub);
  o->impulses_opt = sub.add_option("--impulses", o->impulses, "impulse count n >= 3 (overrides steer.impulses)");
  sub.add_option("--out", o->out, "write the JSON to this file instead of standard output (\"-\": standard output)");
  sub.add_option("--svg", o->svg, "draw the plate to this SVG file (reference dashed, trajectory solid)");
  AddFigureSizeOption(sub);
  sub.add_flag("--summary-only", o->summary_only, "omit the per-impulse records");
  sub.add_flag("--fewest-impulses", o->fewest, "search the fewest impulses that reach the goal exactly (Pareto table)");
  o->max_impulses_opt = sub.add_option("--max-impulses",
                                       o->max_impulses,
                                       "largest impulse count the search tries (overrides steer.fewest.max_impulses)");
  o->starts_opt =
      sub.add_option("--starts", o->starts, "starts per impulse count of the search (overrides steer.fewest.starts)");
  sub.add_flag("--stop-at-goal", o->stop_at_goal, "arrive and stop: one more impulse brings omega to zero at the goal");
  sub.add_flag("--start-at-rest", o->start_at_rest, "the ball starts at rest (the first impulse sets it rolling)");
  o->actuator.Add(sub);
  sub.footer(
      "Exact arrival: corrects the paper's plan along the reference (the plan section's path,\n"
      "else the shortest isoparallel path) so that the ball reaches steer.goal with steer.goal_orientation:\n"
      "per impulse the time, position, delta psi, delta omega and the upper plate's velocity change, the\n"
      "actuator's impulse J and, with --pulse-duration, its pulse's force and friction (docs/rig.md); the\n"
      "arrival errors, those of an independent re-integration, the deviation from the reference.\n"
      "With steer.fewest in the file or --fewest-impulses: the fewest impulses that reach the goal exactly\n"
      "(a systematic multi-start search over n = 1, 2, ...; the JSON says what was searched) and a Pareto\n"
      "table of impulse count against total time, path length, total impulse and deviation.\n"
      "With steer.objective \"fewest\": the same search. With a rig section the search keeps only\n"
      "arrivals within the limits (each through the constrained solver when needed) and checks each\n"
      "reached count by an independent replay.\n"
      "With a rig section (plate region, obstacles, stroke, impulse bounds, shortest interval, tick) or\n"
      "steer.objective: the arrival that meets the limits (SQP from the free optimum; unchanged when\n"
      "they are slack), the active limits and an independent replay check (docs/guide/steer.md).\n"
      "Example: plateball steer problems/figure7_exact.json --summary-only\n"
      "Exit codes: 0 arrived, 2 usage, 3 invalid input, 4 goal not reached or the limits not met\n"
      "(closest arrival reported), "
      "5 unreadable file.");
  return [o] { return RunSteer(*o); };
}

const CommandRegistrar kRegistrar{
    {"steer", "impulses that reach a goal position and orientation exactly along a reference (JSON, SVG)", SetupSteer}};

}  // namespace
}  // namespace plateball::tools
