// `plateball reach PROBLEM.json`: every (delta_psi, t) that takes the ball from its initial state
// to each target of the problem's "reach" section (section 2.3, last remark; Figure 8). Prints
// JSON with all solutions; `--svg FILE` draws the trajectories that reach the targets.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/command_registry.h"
#include "common/errors.h"
#include "common/exit_codes.h"
#include "common/json_output.h"
#include "common/limits.h"
#include "common/number_format.h"
#include "common/output_file.h"
#include "common/problem_options.h"
#include "common/progress.h"
#include "common/svg.h"
#include "common/units.h"
#include "plateball/free_motion.h"
#include "plateball/reach.h"
#include "plateball/task_adapters.h"

namespace plateball::tools {
namespace {

using json = Json;

json Vec(const Eigen::Vector2d& v) { return ToJson(v); }
json Vec(const Eigen::Vector3d& v) { return ToJson(v); }

json SolutionJson(const ReachSolution& s) {
  return json{{"delta_psi", s.delta_psi},
              {"t", s.t},
              {"periods", s.periods},
              {"residual", s.residual},
              {"jacobian_determinant", s.jacobian_determinant},
              {"plate_velocity_change", Vec(s.impulse.plate_velocity_change)},
              {"end", ToJson(s.end)}};
}

json SummaryJson(const ReachSummary& s) {
  json sols = json::array();
  for (const ReachSolution& sol : s.solutions) sols.push_back(SolutionJson(sol));
  json out{{"target", Vec(s.problem.target)}};
  Append(out, ResultJson(ToString(s.status), s.IsSolutionUsable(), s.message, s.BriefReport()));
  Append(out,
         json{{"period", s.period},
              {"horizon", s.horizon},
              {"solutions", sols},
              {"closest_approach",
               {{"distance", s.closest_approach.distance},
                {"delta_psi", s.closest_approach.delta_psi},
                {"t", s.closest_approach.t}}},
              {"counts",
               {{"candidates", s.candidates},
                {"refine_iterations", s.refine_iterations},
                {"tight_evaluations", s.tight_evaluations},
                {"scan_periods_integrated", s.scan_periods_integrated},
                {"global_evaluations", s.global_evaluations}}}});
  // The paper's first guess (absent when the target is x0: no direction).
  if (std::isfinite(s.drift_guess_delta_psi)) out["drift_guess_delta_psi"] = s.drift_guess_delta_psi;
  return out;
}

// Four significant digits for a figure's legend.
std::string Short(double v) {
  std::ostringstream os;
  os.precision(4);
  os << v;
  return os.str();
}

// The contact-point path of the free motion after the impulse delta_psi = s, on [0, t].
std::vector<Eigen::Vector2d> ReachPath(const Problem& problem, double s, double t) {
  AngleState a = problem.initial;
  a.psi += s;
  const FreeMotion m =
      FreeMotion::FromAngles(problem.model, a, problem.mu, problem.x0, problem.A0, problem.integration);
  const int n = std::clamp(static_cast<int>(t / m.Period() * 200.0), 50, 5000);
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i <= n; ++i) points.push_back(m.PositionAt(t * i / n));
  return points;
}

// Figure 8 style drawing: the contact-point paths from x0 to every target (one colour per
// target, later solutions dashed; dashed grey: the closest approach of an unreachable target),
// each tagged with a number on the curve and its delta psi and t in the legend.
SvgFigure Figure(const Problem& problem, const std::vector<ReachSummary>& summaries, bool all_solutions) {
  static const char* kColours[] = {
      "#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b", "#e377c2"};
  SvgFigure fig;
  int tag = 0;
  auto add_path = [&](const Eigen::Vector2d& target,
                      double s,
                      double t,
                      const std::string& colour,
                      bool dashed,
                      const std::string& what) {
    const std::vector<Eigen::Vector2d> points = ReachPath(problem, s, t);
    const SvgFigure::Style style{colour, 1.5, dashed ? "6,4" : "", "none"};
    fig.Polyline(points, style);
    fig.Text(points[points.size() * 11 / 20], std::to_string(++tag), 12, colour);
    fig.Legend(std::to_string(tag) + ": (" + FormatNumber(target.x()) + ", " + FormatNumber(target.y()) + ") " + what +
                   ": Δψ = " + Short(s) + ", t = " + Short(t),
               style,
               SvgFigure::Swatch::kLine);
    return CurveDirection(points, true);
  };
  for (std::size_t k = 0; k < summaries.size(); ++k) {
    const ReachSummary& s = summaries[k];
    const Eigen::Vector2d& target = s.problem.target;
    Eigen::Vector2d arrival = Eigen::Vector2d::Zero();
    if (s.IsSolutionUsable()) {
      const std::size_t count = all_solutions ? s.solutions.size() : 1;
      for (std::size_t i = count; i-- > 0;)
        arrival = add_path(target, s.solutions[i].delta_psi, s.solutions[i].t, kColours[k % 8], i > 0, "reached");
    } else if (s.status == ReachStatus::kUnreachableWithinHorizon) {
      add_path(target, s.closest_approach.delta_psi, s.closest_approach.t, "#7f7f7f", true, "closest approach");
    }
    fig.Goal(target, arrival, "(" + FormatNumber(target.x()) + ", " + FormatNumber(target.y()) + ")");
  }
  fig.Start(problem.x0, Eigen::Vector2d::Zero(), "x0");
  std::ostringstream title;
  title.precision(4);
  title << (problem.name.empty() ? std::string("reach") : problem.name) << ": lambda = " << problem.model.lambda()
        << ", mu = " << problem.mu << ", (theta, phi, psi) = (" << problem.initial.theta << ", " << problem.initial.phi
        << ", " << problem.initial.psi << ")";
  fig.Title(title.str());
  return fig;
}

struct ReachCliOptions {
  ProblemOptions problem;
  std::string targets;
  double horizon_periods = 0.0;
  std::string out;
  std::string svg;
  bool svg_all = false;
  CLI::Option* targets_opt = nullptr;
  CLI::Option* horizon_opt = nullptr;
};

int RunReach(const ReachCliOptions& o) {
  CheckOutputPaths({{"--out", o.out.empty() ? "-" : o.out}, {"--svg", o.svg}}, {{"PROBLEM.json", o.problem.file()}});
  const Problem problem = o.problem.Load();
  ReachTask task = problem.reach.value_or(ReachTask{});
  if (o.targets_opt->count() > 0)
    RequireCoordinatesOption("--targets", task.targets = ParsePointsOption("--targets", o.targets));
  if (o.horizon_opt->count() > 0) {
    task.horizon_periods = RequirePositiveOption("--horizon-periods", o.horizon_periods);
    if (task.horizon_periods > limits::kMaxHorizonPeriods)
      ThrowInvalidInput(CommandLineField("--horizon-periods"),
                        FormatNumber(task.horizon_periods),
                        "must be <= " + FormatNumber(limits::kMaxHorizonPeriods) + " (as in a problem file)");
  }
  if (task.targets.empty())
    ThrowInvalidInput((o.problem.file().empty() ? std::string(kCommandLine) : o.problem.file()) + ": reach.targets",
                      "(missing)",
                      "no target; give a problem file with a \"reach\" section or --targets X,Y");
  std::vector<ReachSummary> summaries;
  json results = json::array();
  bool all_solved = true;
  Progress progress("plateball reach", static_cast<double>(task.targets.size()));
  for (const Eigen::Vector2d& target : task.targets) {
    ReachSetup setup = ReachSetupFor(problem, target);
    setup.options.horizon_periods = task.horizon_periods;
    summaries.push_back(Reach(setup.problem, setup.options));
    if (summaries.back().status == ReachStatus::kNumericalFailure)
      throw std::runtime_error(summaries.back().BriefReport());
    results.push_back(SummaryJson(summaries.back()));
    all_solved = all_solved && summaries.back().IsSolutionUsable();
    progress.Update(static_cast<double>(summaries.size()));
  }
  json doc = HeaderJson("plateball", "reach", problem, o.problem.file());
  doc["initial"] = InitialJson(problem);
  doc["options"] = json{{"horizon_periods", task.horizon_periods}};
  doc["results"] = std::move(results);
  AddPhysicalUnits(problem, &doc);
  WriteJson(doc, o.out);
  if (!o.svg.empty()) Figure(problem, summaries, o.svg_all).Write(o.svg);
  if (Verbose())
    for (const ReachSummary& s : summaries) std::cerr << s.BriefReport() << "\n";
  return all_solved ? kExitSuccess : kExitNoSolution;
}

std::function<int()> SetupReach(CLI::App& sub) {
  auto o = std::make_shared<ReachCliOptions>();
  o->problem.Add(sub, ProblemOptions::Seed::kNone);  // deterministic: no --seed
  o->targets_opt = sub.add_option(
      "--targets", o->targets, "reach these points \"X1,Y1;X2,Y2;...\" instead of the file's reach.targets");
  o->horizon_opt =
      sub.add_option("--horizon-periods",
                     o->horizon_periods,
                     "enumerate solutions with t up to this many periods, (0, 1e4] (default: the file's, else 5)");
  sub.add_option("--out", o->out, "write the JSON to this file instead of standard output (\"-\": standard output)");
  sub.add_option("--svg",
                 o->svg,
                 "draw the trajectories reaching the targets (like Figure 8) into this SVG file (\"-\": standard "
                 "output, with --out FILE)");
  AddFigureSizeOption(sub);
  sub.add_flag("--svg-all", o->svg_all, "draw every solution, not only the earliest (later ones dashed)");
  sub.footer(
      "Prints JSON: per target the status, every solution (delta_psi, t, periods, residual, Jacobian\n"
      "determinant, plate velocity change of the impulse, end state) sorted by t, the closest approach\n"
      "(when unreachable within the horizon) and the paper's drift-direction first guess; one summary\n"
      "line per target on standard error.\n"
      "Example: plateball reach problems/figure8_reach.json --svg figure8.svg\n"
      "         plateball reach problems/figure8_reach.json --targets \"40,0\" --horizon-periods 5\n"
      "Exit codes: 0 every target reached, 2 usage, 3 invalid input, 4 a target not reachable within the\n"
      "horizon (or computation failed), 5 unreadable/unwritable file.");
  return [o] { return RunReach(*o); };
}

const CommandRegistrar kRegistrar{
    {"reach",
     "reach distant points: every (delta psi, t) within a horizon of periods (section 2.3, Figure 8)",
     SetupReach}};

}  // namespace
}  // namespace plateball::tools
