// `plateball reach PROBLEM.json`: every (delta_psi, t) that takes the ball from its initial state
// to each target of the problem's "reach" section (section 2.3, last remark; Figure 8). Prints
// JSON with all solutions; `--svg FILE` draws the trajectories that reach the targets.
#include <CLI/CLI.hpp>
#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <limits>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "common/command_registry.h"
#include "common/exit_codes.h"
#include "plateball/free_motion.h"
#include "plateball/problem_io.h"
#include "plateball/reach.h"

namespace plateball::tools {
namespace {

using json = nlohmann::ordered_json;

json Vec(const Eigen::Vector2d& v) { return json::array({v.x(), v.y()}); }
json Vec(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }
json Mat(const Eigen::Matrix3d& m) {
  json rows = json::array();
  for (int r = 0; r < 3; ++r) rows.push_back(json::array({m(r, 0), m(r, 1), m(r, 2)}));
  return rows;
}

json SolutionJson(const ReachSolution& s) {
  return json{{"delta_psi", s.delta_psi},
              {"t", s.t},
              {"periods", s.periods},
              {"residual", s.residual},
              {"jacobian_determinant", s.jacobian_determinant},
              {"plate_velocity_change", Vec(s.impulse.plate_velocity_change)},
              {"end",
               {{"x", Vec(s.end.x)},
                {"z", Vec(s.end.state.z)},
                {"omega", Vec(s.end.state.omega)},
                {"angles", {{"theta", s.end.angles.theta}, {"phi", s.end.angles.phi}, {"psi", s.end.angles.psi}}},
                {"orientation", Mat(s.end.A)},
                {"energy", s.end.energy}}}};
}

json SummaryJson(const ReachSummary& s) {
  json sols = json::array();
  for (const ReachSolution& sol : s.solutions) sols.push_back(SolutionJson(sol));
  json out{{"target", Vec(s.problem.target)},
           {"status", ToString(s.status)},
           {"report", s.BriefReport()},
           {"period", s.period},
           {"horizon", s.horizon},
           {"drift_guess_delta_psi", std::isfinite(s.drift_guess_delta_psi) ? json(s.drift_guess_delta_psi) : json(nullptr)},
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

std::function<int()> Setup(CLI::App& sub) {
  struct Args {
    std::string problem;
    std::vector<double> target;
    double horizon_periods = std::numeric_limits<double>::quiet_NaN();
    std::string out;
    std::string svg;
    bool svg_all = false;
  };
  auto args = std::make_shared<Args>();
  sub.add_option("problem", args->problem, "problem file (JSON) with a \"reach\" section, e.g. problems/figure8_reach.json")
      ->required();
  sub.add_option("--target", args->target, "reach this point X Y instead of the file's targets")->expected(2);
  sub.add_option("--horizon-periods", args->horizon_periods, "enumerate solutions with t up to this many periods");
  sub.add_option("--out", args->out, "write the JSON here instead of standard output");
  sub.add_option("--svg", args->svg, "draw the trajectories reaching the targets (Figure 8) into this SVG file");
  sub.add_flag("--svg-all", args->svg_all, "draw every solution, not only the earliest (later ones dashed)");
  return [args]() -> int {
    Problem problem;
    try {
      problem = ReadProblemFile(args->problem);
    } catch (const ProblemFileReadError& e) {
      std::cerr << "plateball reach: " << e.what() << "\n";
      return kExitIoError;
    }
    ReachTask task = problem.reach.value_or(ReachTask{});
    if (!args->target.empty()) task.targets = {Eigen::Vector2d(args->target[0], args->target[1])};
    if (!std::isnan(args->horizon_periods)) task.horizon_periods = args->horizon_periods;
    if (task.targets.empty())
      throw std::invalid_argument(args->problem + ": reach.targets: value (missing): the problem has no \"reach\" section; give one or use --target X Y");
    ReachOptions options;
    options.horizon_periods = task.horizon_periods;
    options.seed = problem.seed;
    options.integration = problem.integration;
    std::vector<ReachSummary> summaries;
    json results = json::array();
    bool all_solved = true;
    for (const Eigen::Vector2d& target : task.targets) {
      ReachProblem rp;
      rp.model = problem.model;
      rp.start = problem.initial_angles;
      rp.mu = problem.mu;
      rp.x0 = problem.x0;
      rp.A0 = problem.A0;
      rp.target = target;
      summaries.push_back(Reach(rp, options));
      results.push_back(SummaryJson(summaries.back()));
      all_solved = all_solved && summaries.back().IsSolutionUsable();
    }
    const json doc{{"problem", problem.name.empty() ? problem.source : problem.name},
                   {"lambda", problem.model.lambda()},
                   {"mu", problem.mu},
                   {"initial", {{"theta", problem.initial_angles.theta}, {"phi", problem.initial_angles.phi}, {"psi", problem.initial_angles.psi}}},
                   {"x0", Vec(problem.x0)},
                   {"horizon_periods", task.horizon_periods},
                   {"seed", problem.seed},
                   {"results", results}};
    const std::string text = doc.dump(2) + "\n";
    if (args->out.empty()) {
      std::cout << text;
    } else {
      std::ofstream f(args->out);
      f << text;
      if (!f) {
        std::cerr << "plateball reach: cannot write " << args->out << "\n";
        return kExitIoError;
      }
    }
    if (!args->svg.empty()) {
      std::ofstream f(args->svg);
      f << Svg(problem, summaries, args->svg_all);
      if (!f) {
        std::cerr << "plateball reach: cannot write " << args->svg << "\n";
        return kExitIoError;
      }
    }
    for (const ReachSummary& s : summaries) std::cerr << s.BriefReport() << "\n";
    return all_solved ? kExitSuccess : kExitNoSolution;
  };
}

const CommandRegistrar kRegistrar{
    {"reach", "reach distant points: every (delta psi, t) within a horizon of periods (section 2.3, Figure 8)", Setup}};

}  // namespace
}  // namespace plateball::tools
