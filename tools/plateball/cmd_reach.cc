// `plateball reach PROBLEM.json`: every (delta_psi, t) that takes the ball from its initial state
// to each target of the problem's "reach" section (section 2.3, last remark; Figure 8). Prints
// JSON with all solutions; `--svg FILE` draws the trajectories that reach the targets.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <sstream>
#include <string>
#include <vector>

#include "common/command_registry.h"
#include "common/errors.h"
#include "common/exit_codes.h"
#include "common/json_output.h"
#include "common/problem_options.h"
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
  json out{{"target", Vec(s.problem.target)},
           {"status", ToString(s.status)},
           {"report", s.BriefReport()},
           {"period", s.period},
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
             {"global_evaluations", s.global_evaluations}}}};
  // The paper's first guess (absent when the target is x0: no direction).
  if (std::isfinite(s.drift_guess_delta_psi)) out["drift_guess_delta_psi"] = s.drift_guess_delta_psi;
  if (!s.message.empty()) out["message"] = s.message;
  return out;
}

// Figure 8 style drawing: the contact-point paths from x0 to every target (one colour per
// target; dashed grey: the closest approach of an unreachable target).
std::string Svg(const Problem& problem, const std::vector<ReachSummary>& summaries, bool all_solutions) {
  struct Curve {
    std::vector<Eigen::Vector2d> points;
    std::string colour;
    bool dashed;
  };
  static const char* kColours[] = {"#1f77b4", "#d62728", "#2ca02c", "#9467bd", "#ff7f0e", "#17becf", "#8c564b", "#e377c2"};
  std::vector<Curve> curves;
  Eigen::Vector2d lo = problem.x0, hi = problem.x0;
  auto add_path = [&](double s, double t, const std::string& colour, bool dashed) {
    AngleState a = problem.initial_angles;
    a.psi += s;
    const FreeMotion m = FreeMotion::FromAngles(problem.model, a, problem.mu, problem.x0, problem.A0, problem.integration);
    const int n = std::clamp(static_cast<int>(t / m.Period() * 200.0), 50, 5000);
    Curve c{{}, colour, dashed};
    for (int i = 0; i <= n; ++i) {
      c.points.push_back(m.PositionAt(t * i / n));
      lo = lo.cwiseMin(c.points.back());
      hi = hi.cwiseMax(c.points.back());
    }
    curves.push_back(std::move(c));
  };
  for (std::size_t k = 0; k < summaries.size(); ++k) {
    const ReachSummary& s = summaries[k];
    const std::string colour = kColours[k % 8];
    lo = lo.cwiseMin(s.problem.target);
    hi = hi.cwiseMax(s.problem.target);
    if (s.IsSolutionUsable()) {
      const std::size_t count = all_solutions ? s.solutions.size() : 1;
      for (std::size_t i = 0; i < count; ++i) add_path(s.solutions[i].delta_psi, s.solutions[i].t, colour, i > 0);
    } else if (s.status == ReachStatus::kUnreachableWithinHorizon) {
      add_path(s.closest_approach.delta_psi, s.closest_approach.t, "#7f7f7f", true);
    }
  }
  const double size = 640.0, pad = 40.0;
  const double span = std::max({hi.x() - lo.x(), hi.y() - lo.y(), 1e-9});
  const double scale = (size - 2 * pad) / span;
  auto px = [&](const Eigen::Vector2d& p) {
    std::ostringstream os;
    os.precision(6);
    os << pad + (p.x() - lo.x()) * scale << "," << size - pad - (p.y() - lo.y()) * scale;
    return os.str();
  };
  std::ostringstream svg;
  svg.precision(6);
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << size << "\" height=\"" << size + 30
      << "\" viewBox=\"0 0 " << size << " " << size + 30 << "\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  // Axes through the origin when it is in view.
  if (lo.y() <= 0 && hi.y() >= 0)
    svg << "<line x1=\"0\" y1=\"" << size - pad + lo.y() * scale << "\" x2=\"" << size << "\" y2=\""
        << size - pad + lo.y() * scale << "\" stroke=\"#cccccc\"/>\n";
  if (lo.x() <= 0 && hi.x() >= 0)
    svg << "<line x1=\"" << pad - lo.x() * scale << "\" y1=\"0\" x2=\"" << pad - lo.x() * scale << "\" y2=\"" << size
        << "\" stroke=\"#cccccc\"/>\n";
  for (const Curve& c : curves) {
    svg << "<polyline fill=\"none\" stroke=\"" << c.colour << "\" stroke-width=\"1.5\""
        << (c.dashed ? " stroke-dasharray=\"6,4\"" : "") << " points=\"";
    for (const Eigen::Vector2d& p : c.points) svg << px(p) << " ";
    svg << "\"/>\n";
  }
  auto split = [](const std::string& xy, std::string* x, std::string* y) {
    const auto comma = xy.find(',');
    *x = xy.substr(0, comma);
    *y = xy.substr(comma + 1);
  };
  std::string x, y;
  split(px(problem.x0), &x, &y);
  svg << "<circle cx=\"" << x << "\" cy=\"" << y << "\" r=\"4\" fill=\"black\"/>\n";
  for (std::size_t k = 0; k < summaries.size(); ++k) {
    split(px(summaries[k].problem.target), &x, &y);
    svg << "<circle cx=\"" << x << "\" cy=\"" << y << "\" r=\"5\" fill=\"none\" stroke=\"" << kColours[k % 8]
        << "\" stroke-width=\"2\"/>\n<text x=\"" << x << "\" y=\"" << y << "\" dx=\"7\" dy=\"-7\" font-family=\"sans-serif\" font-size=\"12\">("
        << summaries[k].problem.target.x() << ", " << summaries[k].problem.target.y() << ")</text>\n";
  }
  svg << "<text x=\"" << pad << "\" y=\"" << size + 18 << "\" font-family=\"sans-serif\" font-size=\"12\">"
      << (problem.name.empty() ? std::string("reach") : problem.name) << ": lambda = " << problem.model.lambda()
      << ", mu = " << problem.mu << ", (theta, phi, psi) = (" << problem.initial_angles.theta << ", "
      << problem.initial_angles.phi << ", " << problem.initial_angles.psi << "); scale 1 unit = " << scale << " px</text>\n";
  svg << "</svg>\n";
  return svg.str();
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
  const Problem problem = o.problem.Load();
  ReachTask task = problem.reach.value_or(ReachTask{});
  if (o.targets_opt->count() > 0) task.targets = ParsePointsOption("--targets", o.targets);
  if (o.horizon_opt->count() > 0) {
    task.horizon_periods = RequirePositiveOption("--horizon-periods", o.horizon_periods);
    if (task.horizon_periods > 1e4)
      throw std::invalid_argument(std::string(kCommandLine) + ": --horizon-periods: value " + std::to_string(task.horizon_periods) +
                                  ": must be <= 1e4 (as the problem file)");
  }
  if (task.targets.empty())
    throw std::invalid_argument((o.problem.file().empty() ? std::string(kCommandLine) : o.problem.file()) +
                                ": reach.targets: value (missing): no target; give a problem file with a \"reach\" section or --targets X,Y");
  std::vector<ReachSummary> summaries;
  json results = json::array();
  bool all_solved = true;
  for (const Eigen::Vector2d& target : task.targets) {
    ReachSetup setup = ReachSetupFor(problem, target);
    setup.options.horizon_periods = task.horizon_periods;
    summaries.push_back(Reach(setup.problem, setup.options));
    if (summaries.back().status == ReachStatus::kNumericalFailure) throw std::runtime_error(summaries.back().BriefReport());
    results.push_back(SummaryJson(summaries.back()));
    all_solved = all_solved && summaries.back().IsSolutionUsable();
  }
  json doc;
  doc["command"] = "reach";
  doc["problem"] = problem.name.empty() ? problem.source : problem.name;
  doc["model"] = ToJson(problem.model);
  doc["initial"] = json{{"theta", problem.initial_angles.theta},
                        {"phi", problem.initial_angles.phi},
                        {"psi", problem.initial_angles.psi},
                        {"mu", problem.mu},
                        {"x0", ToJson(problem.x0)}};
  doc["horizon_periods"] = task.horizon_periods;
  doc["seed"] = problem.seed;
  doc["results"] = std::move(results);
  WriteJson(doc, o.out);
  if (!o.svg.empty()) {
    std::ofstream f(o.svg);
    f << Svg(problem, summaries, o.svg_all);
    if (!f) throw IoError("cannot write " + o.svg);
  }
  for (const ReachSummary& s : summaries) std::cerr << s.BriefReport() << "\n";
  return all_solved ? kExitSuccess : kExitNoSolution;
}

std::function<int()> SetupReach(CLI::App& sub) {
  auto o = std::make_shared<ReachCliOptions>();
  o->problem.Add(sub);
  o->targets_opt = sub.add_option("--targets", o->targets, "reach these points \"X1,Y1;X2,Y2;...\" instead of the file's reach.targets");
  o->horizon_opt = sub.add_option("--horizon-periods", o->horizon_periods,
                                  "enumerate solutions with t up to this many periods, (0, 1e4] (default: the file's, else 5)");
  sub.add_option("--out", o->out, "write the JSON to this file instead of standard output");
  sub.add_option("--svg", o->svg, "draw the trajectories reaching the targets (like Figure 8) into this SVG file");
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
    {"reach", "reach distant points: every (delta psi, t) within a horizon of periods (section 2.3, Figure 8)", SetupReach}};

}  // namespace
}  // namespace plateball::tools
