// isoparallel_solve: the project's main job. Solves the isoparallel problem of section 2.2 (the
// shortest path whose rolling gives a prescribed reorientation), then plans its impulsive
// approximation (section 2.3) as in Figure 7.
//
//   isoparallel_solve [problem.json] [--out plan.json] [--svg figure.svg] [--impulses N] [--seed S]
//
// With no problem file it solves the built-in Figure 7 problem (problems/figure7.json).
// Exit codes (tools/common/exit_codes.h): 0 solved and planned, 2 usage, 3 bad input,
// 4 no solution (or the impulsive plan failed), 5 I/O error, 6 internal error.
#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <mutex>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "common/exit_codes.h"
#include "plateball/free_motion.h"
#include "plateball/isoparallel.h"
#include "plateball/isoparallel_plan.h"
#include "plateball/problem_io.h"
#include "plateball/so3.h"

namespace {

using plateball::tools::ExitCode;
using Json = nlohmann::ordered_json;

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

Json Vec(const Eigen::Vector2d& v) { return Json::array({v.x(), v.y()}); }
Json Vec(const Eigen::Vector3d& v) { return Json::array({v.x(), v.y(), v.z()}); }
Json Mat(const Eigen::Matrix3d& m) {
  Json rows = Json::array();
  for (int i = 0; i < 3; ++i) rows.push_back(Json::array({m(i, 0), m(i, 1), m(i, 2)}));
  return rows;
}

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
  Json j;
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

std::string Svg(const plateball::IsoparallelProblem& prob, const std::vector<Eigen::Vector2d>& path,
                const std::vector<std::vector<Eigen::Vector2d>>& arcs, const plateball::PlanSummary& plan) {
  Eigen::Vector2d lo = path.front(), hi = path.front();
  auto grow = [&](const Eigen::Vector2d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  };
  for (const auto& p : path) grow(p);
  for (const auto& a : arcs)
    for (const auto& p : a) grow(p);
  const double margin = 0.05 * std::max(hi.x() - lo.x(), hi.y() - lo.y()) + 0.2;
  lo.array() -= margin;
  hi.array() += margin;
  const double scale = 600.0 / std::max(hi.x() - lo.x(), hi.y() - lo.y());
  const double w = (hi.x() - lo.x()) * scale, h = (hi.y() - lo.y()) * scale;
  std::ostringstream os;
  os << std::fixed << std::setprecision(2);
  auto pt = [&](const Eigen::Vector2d& p) {
    std::ostringstream q;
    q << std::fixed << std::setprecision(2) << (p.x() - lo.x()) * scale << "," << (hi.y() - p.y()) * scale;
    return q.str();
  };
  os << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << w << "\" height=\"" << h + 30 << "\" viewBox=\"0 0 "
     << w << " " << h + 30 << "\">\n";
  os << "<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n";
  os << "<polyline fill=\"none\" stroke=\"#555\" stroke-width=\"2\" stroke-dasharray=\"8,6\" points=\"";
  for (const auto& p : path) os << pt(p) << " ";
  os << "\"/>\n";
  for (const auto& a : arcs) {
    os << "<polyline fill=\"none\" stroke=\"#c03\" stroke-width=\"1.5\" points=\"";
    for (const auto& p : a) os << pt(p) << " ";
    os << "\"/>\n";
  }
  for (const plateball::PlanStep& st : plan.steps) {
    const std::string c = pt(st.p_begin);
    os << "<circle cx=\"" << c.substr(0, c.find(',')) << "\" cy=\"" << c.substr(c.find(',') + 1)
       << "\" r=\"4\" fill=\"#c03\"/>\n";
  }
  for (const auto& [p, label] : {std::pair{prob.start, "x0"}, std::pair{prob.goal, "x1"}}) {
    const std::string c = pt(p);
    os << "<circle cx=\"" << c.substr(0, c.find(',')) << "\" cy=\"" << c.substr(c.find(',') + 1)
       << "\" r=\"6\" fill=\"none\" stroke=\"black\" stroke-width=\"2\"/>\n";
    os << "<text x=\"" << c.substr(0, c.find(',')) << "\" y=\"" << c.substr(c.find(',') + 1)
       << "\" dx=\"8\" dy=\"-8\" font-family=\"sans-serif\" font-size=\"14\">" << label << "</text>\n";
  }
  os << "<text x=\"10\" y=\"" << h + 20
     << "\" font-family=\"sans-serif\" font-size=\"13\">dashed: optimal path; solid: impulsive approximation ("
     << plan.steps.size() << " impulses, dots)</text>\n";
  os << "</svg>\n";
  return os.str();
}

}  // namespace

int main(int argc, char** argv) {
  using namespace plateball;
  using namespace plateball::tools;
  CLI::App app{"isoparallel_solve: shortest path on the plate whose rolling gives a prescribed reorientation "
               "(section 2.2), and its impulsive approximation (Figure 7)"};
  app.set_version_flag("--version", std::string("isoparallel_solve (plateball) ") + PLATEBALL_VERSION_STRING);
  std::string problem_file, out_file, svg_file;
  int impulses = 0, starts = 0;
  long long seed = -1;
  app.add_option("problem", problem_file, "problem JSON file (default: the built-in Figure 7 problem)");
  app.add_option("--out", out_file, "write the full plan as JSON");
  app.add_option("--svg", svg_file, "write an SVG figure of the plate (as Figure 7)");
  app.add_option("--impulses", impulses, "number of impulses (overrides isoparallel.impulses)")->check(CLI::Range(1, 100000));
  app.add_option("--seed", seed, "seed of the multi-start (overrides the problem's seed)")->check(CLI::NonNegativeNumber);
  app.add_option("--starts", starts, "multi-start count (overrides isoparallel.solver.starts)")->check(CLI::Range(1, 1000000));
  bool shooting = false;
  app.add_flag("--shooting", shooting,
               "identity targets: use the multi-start shooting instead of the family enumeration");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitSuccess : kExitUsage;
  }

  try {
    const Problem problem = problem_file.empty() ? ParseProblem(kFigure7, "figure7 (built-in)") : ReadProblemFile(problem_file);
    if (!problem.isoparallel)
      throw std::invalid_argument(problem.source + ": isoparallel: value (missing): the problem has no isoparallel section");
    const IsoparallelTask& task = *problem.isoparallel;
    IsoparallelProblem prob;
    prob.start = task.start;
    prob.goal = task.goal;
    prob.start_orientation = task.start_orientation;
    prob.goal_orientation = task.goal_orientation;
    IsoparallelOptions opt;
    opt.starts = starts > 0 ? starts : task.solver.starts;
    opt.length_cap_factor = task.solver.length_cap_factor;
    opt.max_iterations = task.solver.max_iterations;
    opt.tolerance = task.solver.tolerance;
    opt.threads = task.solver.threads;
    opt.enumerate_families = task.solver.enumerate_families && !shooting;
    opt.seed = seed >= 0 ? static_cast<std::uint64_t>(seed) : problem.seed;
    const int n_impulses = impulses > 0 ? impulses : task.impulses;

    // Solve; a progress line on stderr when it takes longer than a second.
    std::atomic<int> done{0}, total{0};
    opt.progress = [&](int d, int t) {
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
    IsoparallelSummary summary;
    std::exception_ptr failure;
    try {
      summary = SolveIsoparallel(prob, opt);
    } catch (...) {
      failure = std::current_exception();
    }
    {
      std::lock_guard<std::mutex> lock(mu);
      finished = true;
    }
    cv.notify_all();
    monitor.join();
    if (failure) std::rethrow_exception(failure);

    const double angle = RotationAngle(prob.goal_orientation * prob.start_orientation.transpose(), Eigen::Matrix3d::Identity());
    std::cout << std::setprecision(6);
    std::cout << "isoparallel_solve: " << (problem.name.empty() ? problem.source : problem.name) << ": ("
              << prob.start.x() << ", " << prob.start.y() << ") -> (" << prob.goal.x() << ", " << prob.goal.y()
              << "), target reorientation angle " << angle << " rad\n";
    if (!summary.IsSolutionUsable()) {
      if (summary.method == IsoparallelMethod::kFamilyEnumeration)
        std::cout << "no solution found (family enumeration over 1.." << summary.periods_searched
                  << " curvature periods, paths up to length " << summary.searched_length << ")\n";
      else
        std::cout << "no solution found (" << summary.local_solves << " local solves from " << opt.starts
                  << " starts, seed " << opt.seed << ", paths up to length " << summary.searched_length << ")\n";
      return kExitNoSolution;
    }
    const IsoparallelSolution& best = summary.Shortest();
    std::cout << "solutions found: " << summary.solutions.size() << " (distinct, up to " << opt.length_cap_factor
              << "x the shortest; ";
    if (summary.method == IsoparallelMethod::kFamilyEnumeration)
      std::cout << "identity target: one-parameter families enumerated over 1.." << summary.periods_searched
                << " curvature periods, " << (summary.complete ? "certified complete" : "NOT certified complete") << ")\n";
    else
      std::cout << opt.starts << " starts, seed " << opt.seed << ")\n";
    std::cout << std::setprecision(10) << "shortest length: " << best.length << std::setprecision(6) << "  ("
              << ToString(best.parameters.regime) << " pendulum, G = " << best.G << ", energy = " << best.energy
              << ", " << best.periods << " curvature period(s)"
              << (best.family ? ", a one-parameter family: phase free, phase 0 reported" : "") << ")\n";
    std::cout << std::setprecision(3) << "verified by rolling (dopri5): orientation residual " << best.orientation_residual
              << " rad, endpoint error " << best.endpoint_error << "\n";
    const auto t_plan = std::chrono::steady_clock::now();
    const PlanSummary plan =
        PlanOptimalPath(problem.model, problem.initial_angles.psi, problem.mu, prob.start_orientation, best, n_impulses);
    const double plan_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_plan).count();
    const double final_error = OperatorNormDistance(prob.goal_orientation, plan.A_impulsive);
    std::cout << "impulses: " << plan.steps.size() << " (" << ToString(plan.status) << "), max pass miss "
              << plan.max_pass_miss << "\n";
    if (plan.IsSolutionUsable()) {
      std::cout << "final orientation error ||A_goal - A~_n|| = " << final_error << ", bound (Theorem 2.6) "
                << plan.bounds.theorem_2_6 << ", a-posteriori bound " << plan.bounds.a_posteriori << "\n";
    } else {
      std::cout << "impulsive plan failed: " << plan.message << " (try more impulses)\n";
    }
    std::cout << std::setprecision(3) << "time: solve " << summary.time_seconds * 1e3 << " ms, plan " << plan_seconds * 1e3
              << " ms\n";

    const std::vector<Eigen::Vector2d> path_pts = SamplePath(best, 400);
    const std::vector<std::vector<Eigen::Vector2d>> arcs =
        plan.IsSolutionUsable() ? SampleArcs(problem.model, plan, 40) : std::vector<std::vector<Eigen::Vector2d>>{};
    if (!out_file.empty()) {
      Json j;
      j["problem"] = {{"name", problem.name},
                      {"start", Vec(prob.start)},
                      {"goal", Vec(prob.goal)},
                      {"start_orientation", Mat(prob.start_orientation)},
                      {"goal_orientation", Mat(prob.goal_orientation)}};
      j["solver"] = {{"method", ToString(summary.method)},
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
      j["solutions"] = sols;
      Json path = Json::array();
      for (const auto& p : path_pts) path.push_back(Vec(p));
      j["optimal_path"] = path;
      const AngleState a0 = InitialAnglesFromOrientation(prob.start_orientation, problem.initial_angles.psi);
      Json pj;
      pj["status"] = ToString(plan.status);
      pj["message"] = plan.message;
      pj["initial_angles"] = {{"theta", a0.theta}, {"phi", a0.phi}, {"psi", a0.psi}};
      pj["mu"] = problem.mu;
      Json steps = Json::array();
      for (const PlanStep& st : plan.steps) {
        steps.push_back({{"k", st.global_index},
                         {"point", Vec(st.p_begin)},
                         {"t_impulse", st.t_impulse},
                         {"duration", st.duration},
                         {"delta_psi", st.delta_psi},
                         {"delta_omega", Vec(st.delta_omega)},
                         {"plate_velocity_change", Vec(st.plate_velocity_change)},
                         {"pass_miss", st.pass_miss}});
      }
      pj["impulses"] = steps;
      Json traj = Json::array();
      for (const auto& a : arcs) {
        Json arc = Json::array();
        for (const auto& p : a) arc.push_back(Vec(p));
        traj.push_back(arc);
      }
      pj["trajectory"] = traj;
      pj["A_impulsive"] = Mat(plan.A_impulsive);
      pj["orientation_error"] = final_error;
      pj["measured_error_vs_planned"] = plan.measured_error;
      pj["bound_theorem_2_6"] = plan.bounds.theorem_2_6;
      pj["bound_a_posteriori"] = plan.bounds.a_posteriori;
      j["plan"] = pj;
      std::ofstream f(out_file);
      if (!(f << j.dump(2) << "\n")) {
        std::cerr << "isoparallel_solve: cannot write " << out_file << "\n";
        return kExitIoError;
      }
    }
    if (!svg_file.empty()) {
      std::ofstream f(svg_file);
      if (!(f << Svg(prob, path_pts, arcs, plan))) {
        std::cerr << "isoparallel_solve: cannot write " << svg_file << "\n";
        return kExitIoError;
      }
    }
    return plan.IsSolutionUsable() ? kExitSuccess : kExitNoSolution;
  } catch (const ProblemFileReadError& e) {
    std::cerr << "isoparallel_solve: " << e.what() << "\n";
    return kExitIoError;
  } catch (const std::invalid_argument& e) {
    std::cerr << "isoparallel_solve: invalid input: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::exception& e) {
    std::cerr << "isoparallel_solve: error: " << e.what() << "\n";
    return kExitInternalError;
  }
}
