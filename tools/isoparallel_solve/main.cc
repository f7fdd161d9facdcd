// isoparallel_solve: the project's main job. Solves the isoparallel problem of section 2.2 (the
// shortest path whose rolling gives a prescribed reorientation), then plans its impulsive
// approximation (section 2.3) as in Figure 7.
//
//   isoparallel_solve [problem.json] [--out plan.json] [--svg figure.svg] [--impulses N] [--seed S]
//                     [--starts N] [--shooting]
//
// With no problem file it solves the built-in Figure 7 problem (problems/figure7.json).
// Exit codes (tools/common/exit_codes.h): 0 solved and planned, 2 usage, 3 bad input,
// 4 no solution (or the impulsive plan failed), 5 I/O error, 6 internal error; failures are
// reported as by the `plateball` subcommands (tools/common/errors.h), the plan file is written
// with tools/common/json_output.h and the figure with tools/common/svg.h.
#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <exception>
#include <iomanip>
#include <iostream>
#include <mutex>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "common/command_line.h"
#include "common/errors.h"
#include "common/exact_output.h"
#include "common/exit_codes.h"
#include "common/json_output.h"
#include "common/output_file.h"
#include "common/plan_json.h"
#include "common/svg.h"
#include "plateball/free_motion.h"
#include "plateball/isoparallel.h"
#include "plateball/isoparallel_plan.h"
#include "plateball/task_adapters.h"
#include "plateball/problem_io.h"
#include "plateball/so3.h"
#include "plateball/version.h"

namespace {

using plateball::tools::Json;
using plateball::tools::ToJson;

// The paper's Figure 7 problem: from (0, 0) to (3, 3), final reorientation the identity. The
// ball of Figures 8 and T2/T3 (lambda = 2, mu = 1); A0 = I puts the symmetry axis at the pole.
const char* const kFigure7 = R"json({
  "name": "figure7",
  "description": "Figure 7 of the paper: the isoparallel problem from (0, 0) to (3, 3) with final reorientation equal to the identity, approximated with 12 impulses.",
  "seed": 1,
  "ball": {"lambda": 2.0},
  "initial": {"theta": 0.0, "phi": 0.0, "psi": 0.0, "mu": 1.0, "x0": [0.0, 0.0]},
  "isoparallel": {
    "start": [0.0, 0.0],
    "goal": [3.0, 3.0],
    "impulses": 12,
    "solver": {"starts": 1024, "length_cap_factor": 3.0, "max_iterations": 100, "tolerance": 1e-12, "threads": 1, "enumerate_families": true}
  }
})json";

std::vector<Eigen::Vector2d> SamplePath(const plateball::IsoparallelSolution& s, int n) {
  std::vector<Eigen::Vector2d> pts;
  for (int i = 0; i <= n; ++i) pts.push_back(s.PositionAt(s.length * i / n));
  return pts;
}

// The impulsive trajectory: each free arc sampled from its post-impulse state.
std::vector<std::vector<Eigen::Vector2d>> SampleArcs(const plateball::BallModel& model,
                                                     const plateball::PlanSummary& plan, int per_arc) {
  std::vector<std::vector<Eigen::Vector2d>> arcs;
  for (const plateball::PlanStep& st : plan.steps) {
    plateball::FreeMotionStart start;
    start.state = st.impulse.state_after;
    start.x0 = st.p_begin;
    start.A0 = plateball::AlignOrientationToAxis(Eigen::Matrix3d::Identity(), start.state.z);  // positions only
    const plateball::FreeMotion m(model, start);
    std::vector<Eigen::Vector2d> pts;
    for (int i = 0; i <= per_arc; ++i) pts.push_back(m.PositionAt(st.duration * i / per_arc));
    arcs.push_back(pts);
  }
  return arcs;
}

Json SolutionJson(const plateball::IsoparallelSolution& s) {
  Json j = Json::object();
  j["length"] = s.length;
  j["regime"] = plateball::ToString(s.parameters.regime);
  j["G"] = s.G;
  j["R"] = s.G > 0 ? 1.0 / std::sqrt(s.G) : 0.0;
  j["energy"] = s.energy;
  j["rate"] = s.parameters.rate;
  j["modulus"] = s.parameters.modulus;
  j["phase"] = s.parameters.phase;
  j["heading_w"] = s.parameters.heading_w;
  j["periods"] = s.periods;
  j["family"] = s.family;
  j["crossing"] = s.crossing;
  j["shooting_residual"] = s.shooting_residual;
  j["orientation_residual"] = s.orientation_residual;
  j["orientation_error"] = s.orientation_error;
  j["endpoint_error"] = s.endpoint_error;
  return j;
}

// The plan file (--out): what was solved, every solution, the sampled optimal path and the
// impulsive plan. No timings, so the same problem and seed give a byte-identical file.
Json PlanFileJson(const plateball::Problem& problem, const plateball::IsoparallelProblem& prob,
                  const plateball::IsoparallelOptions& opt, const plateball::IsoparallelSummary& summary,
                  const std::vector<Eigen::Vector2d>& path_pts, const plateball::PlanSummary& plan,
                  const std::vector<std::vector<Eigen::Vector2d>>& arcs, double final_error) {
  using namespace plateball;
  Json j;
  j["problem"] = Json{{"name", problem.name},
                      {"start", ToJson(prob.start)},
                      {"goal", ToJson(prob.goal)},
                      {"start_orientation", ToJson(prob.start_orientation)},
                      {"goal_orientation", ToJson(prob.goal_orientation)}};
  j["solver"] = Json{{"method", ToString(summary.method)},
                     {"complete", summary.complete},
                     {"periods_searched", summary.periods_searched},
                     {"starts", opt.starts},
                     {"seed", opt.seed},
                     {"length_cap_factor", opt.length_cap_factor},
                     {"tolerance", opt.tolerance},
                     {"status", ToString(summary.status)},
                     {"local_solves", summary.local_solves},
                     {"searched_length", summary.searched_length}};
  Json sols = Json::array();
  for (const auto& s : summary.solutions) sols.push_back(SolutionJson(s));
  j["solutions"] = std::move(sols);
  j["optimal_path"] = ToJson(path_pts);
  // The plan in the layout of `plateball plan` (plan_json.h), with what only this tool knows: the
  // start angles and energy, the sampled impulsive trajectory and the error against the goal.
  Json pj = tools::PlanSummaryToJson(plan);
  pj["initial_angles"] = ToJson(InitialAnglesFromOrientation(prob.start_orientation, problem.initial_angles.psi));
  pj["mu"] = problem.mu;
  Json traj = Json::array();
  for (const auto& a : arcs) traj.push_back(ToJson(a));
  pj["trajectory"] = std::move(traj);
  pj["orientation_error"] = final_error;
  j["plan"] = std::move(pj);
  return j;
}

// The plate as in Figure 7: optimal path dashed, impulsive trajectory solid, impulse points as dots,
// start x0 and goal x1 circled.
plateball::tools::SvgFigure Figure(const std::string& name, const plateball::IsoparallelProblem& prob,
                                   const plateball::IsoparallelSolution& best,
                                   const std::vector<Eigen::Vector2d>& path,
                                   const std::vector<std::vector<Eigen::Vector2d>>& arcs,
                                   const plateball::PlanSummary& plan) {
  using plateball::tools::SvgFigure;
  const SvgFigure::Style optimal{"#555", 2.0, "8,6", "none"};
  const SvgFigure::Style impulsive{"#c03", 1.5, "", "none"};
  const SvgFigure::Style dot{"#c03", 1.0, "", "#c03"};
  const SvgFigure::Style end_point{"black", 2.0, "", "none"};
  SvgFigure fig;
  fig.Polyline(path, optimal);
  for (const auto& a : arcs) fig.Polyline(a, impulsive);
  for (const plateball::PlanStep& st : plan.steps) fig.Marker(st.p_begin, 4, dot);
  // Labels a little above and right of their points (1.5% of the drawing's extent).
  Eigen::Vector2d lo = path.front(), hi = path.front();
  for (const auto& p : path) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  for (const auto& a : arcs)
    for (const auto& p : a) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  const Eigen::Vector2d label_offset = Eigen::Vector2d::Constant(0.015 * (hi - lo).maxCoeff());
  for (const auto& [p, label] : {std::pair{prob.start, "x0"}, std::pair{prob.goal, "x1"}}) {
    fig.Marker(p, 6, end_point);
    fig.Text(p + label_offset, label, 14);
  }
  // The caption goes in the title: a legend in the corner would cover the path.
  std::ostringstream title;
  title.precision(3);
  title << name << ": optimal path dashed (length " << best.length << "); " << plan.steps.size()
        << " impulses solid, dots";
  fig.Title(title.str());
  return fig;
}

struct CliOptions {
  std::string problem_file, out_file, svg_file;
  int impulses = 0, starts = 0;
  std::string seed;  // empty: the problem's
  bool shooting = false;
  bool exact = false;  // exact arrival along the optimal path (issue 11)
};

// The problem (file or built-in Figure 7) mapped by the task adapter, with the command line's
// overrides.
plateball::IsoparallelSetup LoadSetup(const CliOptions& cli, plateball::Problem* problem) {
  using namespace plateball;
  using namespace plateball::tools;
  // Outputs checked before the solve: distinct, not the input, writable. Standard output carries the
  // report, so "-" is not an output file here.
  CheckOutputPaths({{"standard output (the report)", "-"}, {"--out", cli.out_file}, {"--svg", cli.svg_file}},
                   {{"problem file", cli.problem_file}});
  const std::uint64_t seed_override = cli.seed.empty() ? 0 : ParseSeedOption("--seed", cli.seed);
  *problem = cli.problem_file.empty() ? ParseProblem(kFigure7, "figure7 (built-in)") : ReadProblemFile(cli.problem_file);
  IsoparallelSetup setup = IsoparallelSetupFor(*problem);
  if (cli.starts > 0) setup.options.starts = cli.starts;
  if (cli.shooting) setup.options.enumerate_families = false;
  if (!cli.seed.empty()) setup.options.seed = seed_override;
  return setup;
}

// Solves; a progress line on stderr when it takes longer than a second.
plateball::IsoparallelSummary SolveWithProgress(plateball::IsoparallelSetup setup) {
  std::atomic<int> done{0}, total{0};
  setup.options.progress = [&](int d, int t) {
    done = d;
    total = t;
  };
  std::mutex mu;
  std::condition_variable cv;
  bool finished = false;
  std::thread monitor([&]() {
    std::unique_lock<std::mutex> lock(mu);
    int seconds = 0;
    while (!cv.wait_for(lock, std::chrono::seconds(1), [&] { return finished; })) {
      ++seconds;
      if (total.load() > 0)
        std::cerr << "isoparallel_solve: solving, " << seconds << " s, start " << done.load() << " of "
                  << total.load() << "\n";
      else
        std::cerr << "isoparallel_solve: solving, " << seconds << " s, families over 1.." << done.load()
                  << " curvature periods examined\n";
    }
  });
  plateball::IsoparallelSummary summary;
  std::exception_ptr failure;
  try {
    summary = plateball::SolveIsoparallel(setup.problem, setup.options);
  } catch (...) {
    failure = std::current_exception();
  }
  {
    std::lock_guard<std::mutex> lock(mu);
    finished = true;
  }
  cv.notify_all();
  monitor.join();
  if (failure) std::rethrow_exception(failure);  // reported by RunWithExitCodes
  return summary;
}

void PrintNoSolution(const plateball::IsoparallelSummary& summary, const plateball::IsoparallelOptions& opt) {
  using plateball::IsoparallelMethod;
  if (summary.status == plateball::IsoparallelStatus::kIntegrationFailure)
    std::cout << "solver failed: " << plateball::ToString(summary.status) << ": " << summary.message << "\n";
  else if (summary.method == IsoparallelMethod::kFamilyEnumeration)
    std::cout << "no solution found (family enumeration over 1.." << summary.periods_searched
              << " curvature periods, paths up to length " << summary.searched_length << ")\n";
  else
    std::cout << "no solution found (" << summary.local_solves << " local solves from " << opt.starts
              << " starts, seed " << opt.seed << ", paths up to length " << summary.searched_length << ")\n";
}

void PrintSolutions(const plateball::IsoparallelSummary& summary, const plateball::IsoparallelOptions& opt) {
  using namespace plateball;
  const IsoparallelSolution& best = summary.Shortest();
  std::cout << "solutions found: " << summary.solutions.size() << " (distinct, up to " << opt.length_cap_factor
            << "x the shortest; ";
  if (summary.method == IsoparallelMethod::kFamilyEnumeration)
    std::cout << "identity target: one-parameter families enumerated over 1.." << summary.periods_searched
              << " curvature periods, " << (summary.complete ? "certified complete" : "NOT certified complete") << ")\n";
  else
    std::cout << opt.starts << " starts, seed " << opt.seed << ": a sample, NOT certified complete)\n";
  std::cout << std::setprecision(10) << "shortest length: " << best.length << std::setprecision(6) << "  ("
            << ToString(best.parameters.regime) << " pendulum, G = " << best.G << ", energy = " << best.energy
            << ", " << best.periods << " curvature period(s)"
            << (best.family ? ", a one-parameter family: phase free, phase 0 reported" : "") << ")\n";
  std::cout << std::setprecision(3) << "verified by rolling (Runge-Kutta-Fehlberg 7(8)): orientation residual " << best.orientation_residual
            << " rad, endpoint error " << best.endpoint_error << "\n";
}

void PrintPlan(const plateball::PlanSummary& plan, double final_error, double solve_seconds, double plan_seconds) {
  std::cout << "impulses: " << plan.steps.size() << " (" << plateball::ToString(plan.status) << "), max pass miss "
            << plan.max_pass_miss << "\n";
  if (plan.IsSolutionUsable()) {
    std::cout << "final orientation error ||A_goal - A~_n|| = " << final_error << ", bound (Theorem 2.6) "
              << plan.bounds.theorem_2_6 << ", a-posteriori bound " << plan.bounds.a_posteriori << "\n";
  } else {
    std::cout << "impulsive plan failed: " << plan.message << " (try more impulses)\n";
  }
  std::cout << std::setprecision(3) << "time: solve " << solve_seconds * 1e3 << " ms, plan " << plan_seconds * 1e3
            << " ms\n";
  std::cout.flush();
}

// --exact: exact arrival at the goal (position and orientation) with the same impulse count along
// the optimal path (exact_arrival.h), re-integrated independently; one line on standard output.
struct ExactRun {
  plateball::ExactArrivalProblem problem;
  plateball::ExactArrivalSummary summary;
  plateball::ReplayResult replay;
};
ExactRun SolveExact(const plateball::Problem& problem, const plateball::IsoparallelSolution& best, int impulses) {
  using namespace plateball;
  const ExactArrivalSetup setup = ExactArrivalSetupFor(problem, best, impulses, "--impulses");
  const auto t0 = std::chrono::steady_clock::now();
  ExactRun r{setup.problem, SolveExactArrival(setup.problem, setup.options), {}};
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.replay = ReplayExactArrival(setup.problem, r.summary.impulses);
  std::cout << std::setprecision(3) << "exact arrival: " << ToString(r.summary.status) << " with "
            << r.summary.impulses.size() << " impulses, re-integrated errors: position " << r.replay.position_error
            << ", orientation " << r.replay.orientation_error << " rad; max pass-point displacement "
            << r.summary.max_pass_displacement << ", total time " << r.summary.total_time << ", "
            << r.summary.iterations << " iterations, " << seconds * 1e3 << " ms\n";
  return r;
}

int Run(const CliOptions& cli) {
  using namespace plateball;
  using namespace plateball::tools;
  Problem problem;
  const IsoparallelSetup setup = LoadSetup(cli, &problem);
  const IsoparallelProblem& prob = setup.problem;
  const IsoparallelOptions& opt = setup.options;
  const IsoparallelSummary summary = SolveWithProgress(setup);

  const double angle = RotationAngle(prob.goal_orientation * prob.start_orientation.transpose(), Eigen::Matrix3d::Identity());
  const std::string name = problem.name.empty() ? problem.source : problem.name;
  std::cout << std::setprecision(6);
  std::cout << "isoparallel_solve: " << name << ": (" << prob.start.x() << ", " << prob.start.y() << ") -> ("
            << prob.goal.x() << ", " << prob.goal.y() << "), target reorientation angle " << angle << " rad\n";
  if (!summary.IsSolutionUsable()) {
    PrintNoSolution(summary, opt);
    return kExitNoSolution;
  }
  PrintSolutions(summary, opt);
  const IsoparallelSolution& best = summary.Shortest();
  const IsoparallelPlanSetup plan_setup = IsoparallelPlanSetupFor(problem, best, cli.impulses);
  const auto t_plan = std::chrono::steady_clock::now();
  const PlanSummary plan = PlanOptimalPath(plan_setup.problem, plan_setup.options);
  const double plan_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_plan).count();
  const double final_error = OperatorNormDistance(prob.goal_orientation, plan.A_impulsive);
  PrintPlan(plan, final_error, summary.time_seconds, plan_seconds);

  const std::vector<Eigen::Vector2d> path_pts = SamplePath(best, 400);
  const std::vector<std::vector<Eigen::Vector2d>> arcs =
      plan.IsSolutionUsable() ? SampleArcs(problem.model, plan, 40) : std::vector<std::vector<Eigen::Vector2d>>{};
  std::optional<ExactRun> exact;
  if (cli.exact) exact = SolveExact(problem, best, cli.impulses);
  if (!cli.out_file.empty()) {
    Json doc = PlanFileJson(problem, prob, opt, summary, path_pts, plan, arcs, final_error);
    if (exact) doc["exact"] = ExactArrivalToJson(exact->summary, exact->replay);
    WriteJson(doc, cli.out_file);
  }
  if (!cli.svg_file.empty() && exact)
    DrawExactArrival(exact->problem, exact->summary, name + ": exact arrival", cli.svg_file);
  else if (!cli.svg_file.empty())
    Figure(name, prob, best, path_pts, arcs, plan).Write(cli.svg_file);
  if (exact && !exact->summary.IsSolutionUsable()) return kExitNoSolution;
  return plan.IsSolutionUsable() ? kExitSuccess : kExitNoSolution;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace plateball::tools;
  CLI::App app{"isoparallel_solve: shortest path on the plate whose rolling gives a prescribed reorientation "
               "(section 2.2), and its impulsive approximation (Figure 7)"};
  app.set_version_flag("--version", std::string("isoparallel_solve (plateball) ") + PLATEBALL_VERSION_STRING);
  CliOptions cli;
  app.add_option("problem", cli.problem_file, "problem JSON file (default: the built-in Figure 7 problem)");
  app.add_option("--out", cli.out_file, "write the full plan as JSON");
  app.add_option("--svg", cli.svg_file, "write an SVG figure of the plate (as Figure 7)");
  app.add_option("--impulses", cli.impulses, "number of impulses (overrides isoparallel.impulses)")->check(CLI::Range(1, 100000));
  app.add_option("--seed", cli.seed, "seed of the multi-start, 0 ... 2^64 - 1 (overrides the problem's seed)")
      ->type_name(kSeedTypeName);
  app.add_option("--starts", cli.starts, "multi-start count (overrides isoparallel.solver.starts)")->check(CLI::Range(1, 1000000));
  app.add_flag("--shooting", cli.shooting,
               "identity targets: use the multi-start shooting instead of the family enumeration");
  app.add_flag("--exact", cli.exact,
               "also solve exact arrival at the goal position and orientation with the same impulse count "
               "(JSON section \"exact\", SVG: the exact trajectory)");
  if (const auto code = ParseCommandLine(app, argc, argv, "isoparallel_solve")) return *code;
  // Failures read as in the `plateball` CLI (errors.h): 3 bad input, 4 computation failed,
  // 5 unreadable/unwritable file, 6 internal error.
  return RunWithExitCodes("isoparallel_solve", [&] { return Run(cli); });
}
