// The isoparallel command, the project's main job, behind both `isoparallel_solve` and
// `plateball isoparallel` (one implementation, two entry points). Solves the isoparallel problem
// of section 2.2 (the shortest path whose rolling gives a prescribed reorientation), then plans its
// impulsive approximation (section 2.3) as in Figure 7. Failures are reported by the caller's
// RunWithExitCodes (tools/common/errors.h), the plan file is written with json_output.h and the
// figure with svg.h.
#include "common/isoparallel_command.h"

#include <CLI/CLI.hpp>
#include <chrono>
#include <cmath>
#include <exception>
#include <iomanip>
#include <iostream>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "common/command_line.h"
#include "common/errors.h"
#include "common/exact_output.h"
#include "common/exit_codes.h"
#include "common/invalid_input.h"
#include "common/json_output.h"
#include "common/number_format.h"
#include "common/output_file.h"
#include "common/plan_json.h"
#include "common/progress.h"
#include "common/svg.h"
#include "plateball/exact_arrival.h"
#include "plateball/free_motion.h"
#include "plateball/isoparallel.h"
#include "plateball/isoparallel_certificate.h"
#include "plateball/isoparallel_plan.h"
#include "plateball/problem_io.h"
#include "plateball/so3.h"
#include "plateball/task_adapters.h"

namespace plateball::tools {
namespace {

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
                                                     const plateball::PlanSummary& plan,
                                                     int per_arc) {
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

// Index pairs (into "solutions") of equal-length solutions: Maxwell points at the goal.
Json MaxwellPairsJson(const plateball::IsoparallelSummary& summary) {
  Json pairs = Json::array();
  for (const plateball::MaxwellPair& m : summary.maxwell_pairs) pairs.push_back(Json::array({m.first, m.second}));
  return pairs;
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
  j["orientation_distance"] = s.orientation_error;
  j["endpoint_error"] = s.endpoint_error;
  // null: no conjugate point up to kConjugateSearchFactor x the length
  j["conjugate_time"] = std::isfinite(s.conjugate_time) ? Json(s.conjugate_time) : Json(nullptr);
  j["locally_optimal"] = s.locally_optimal;
  return j;
}

// The plan file (--out): the header, what was solved, every solution, the sampled optimal path and
// the impulsive plan. No timings, so the same problem and seed give a byte-identical file.
Json PlanFileJson(const IsoparallelCliOptions& cli,
                  const plateball::Problem& problem,
                  const plateball::IsoparallelProblem& prob,
                  const plateball::IsoparallelOptions& opt,
                  const plateball::IsoparallelSummary& summary,
                  const std::vector<Eigen::Vector2d>& path_pts,
                  const plateball::PlanSummary& plan,
                  const std::vector<std::vector<Eigen::Vector2d>>& arcs,
                  double final_error,
                  const ActuatorRequest& request) {
  using namespace plateball;
  Json j = HeaderJson(cli.tool, "isoparallel", problem, cli.problem.file());
  // The state the plan starts from: the axis of the start orientation, the file's psi and mu.
  j["initial"] = Json{{"angles", ToJson(InitialAnglesFromOrientation(prob.start_orientation, problem.initial.psi))},
                      {"mu", problem.mu},
                      {"x0", ToJson(prob.start)},
                      {"orientation", ToJson(prob.start_orientation)}};
  j["isoparallel"] = Json{{"start", ToJson(prob.start)},
                          {"goal", ToJson(prob.goal)},
                          {"start_orientation", ToJson(prob.start_orientation)},
                          {"goal_orientation", ToJson(prob.goal_orientation)},
                          {"impulses", plan.steps.size()}};
  // No "report": the solver's BriefReport() includes its wall time, and this file has none.
  Json solver{
      {"status", ToString(summary.status)}, {"usable", summary.IsSolutionUsable()}, {"message", summary.message}};
  Append(solver,
         Json{{"method", ToString(summary.method)},
              {"complete", summary.complete},
              {"periods_searched", summary.periods_searched},
              {"starts", opt.starts},
              {"length_cap_factor", opt.length_cap_factor},
              {"tolerance", opt.tolerance},
              {"local_solves", summary.local_solves},
              {"searched_length", summary.searched_length},
              {"maxwell_pairs", MaxwellPairsJson(summary)}});
  j["solver"] = std::move(solver);
  Json sols = Json::array();
  for (const auto& s : summary.solutions) sols.push_back(SolutionJson(s));
  j["solutions"] = std::move(sols);
  j["optimal_path"] = ToJson(path_pts);
  // The plan in the layout of `plateball plan` (plan_json.h), with what only this command knows:
  // the sampled impulsive trajectory and the distance of its final orientation from the goal.
  const ActuatorContext actuator{problem, request, "plan."};
  Json pj = tools::PlanSummaryToJson(plan, true, &actuator);
  Json traj = Json::array();
  for (const auto& a : arcs) traj.push_back(ToJson(a));
  pj["trajectory"] = std::move(traj);
  pj["orientation_distance"] = final_error;
  j["plan"] = std::move(pj);
  return j;
}

// The plate as in Figure 7: optimal path dashed, impulsive trajectory solid, impulse points as dots,
// start x0 and goal x1 with the direction of motion (svg.h).
plateball::tools::SvgFigure Figure(const std::string& name,
                                   const plateball::IsoparallelProblem& prob,
                                   const plateball::IsoparallelSolution& best,
                                   const std::vector<Eigen::Vector2d>& path,
                                   const std::vector<std::vector<Eigen::Vector2d>>& arcs,
                                   const plateball::PlanSummary& plan) {
  using plateball::tools::SvgFigure;
  const SvgFigure::Style optimal{"#555", 2.0, "8,6", "none"};
  const SvgFigure::Style impulsive{"#c03", 1.5, "", "none"};
  const SvgFigure::Style dot{"#c03", 1.0, "", "#c03"};
  SvgFigure fig;
  fig.Polyline(path, optimal);
  for (const auto& a : arcs) fig.Polyline(a, impulsive);
  for (const plateball::PlanStep& st : plan.steps) fig.Marker(st.p_begin, 4, dot);
  fig.Start(prob.start, plateball::tools::CurveDirection(path, false), "x0");
  fig.Goal(prob.goal, plateball::tools::CurveDirection(path, true), "x1");
  fig.Legend("optimal isoparallel path", optimal);
  fig.Legend("impulsive trajectory", impulsive);
  fig.Legend("impulse points", dot);
  std::ostringstream title;
  title.precision(3);
  title << name << ": optimal path length " << best.length << ", " << plan.steps.size() << " impulses";
  fig.Title(title.str());
  return fig;
}

// The problem (file or built-in Figure 7) mapped by the task adapter, with the command line's
// overrides.
plateball::IsoparallelSetup LoadSetup(const IsoparallelCliOptions& cli, plateball::Problem* problem) {
  using namespace plateball;
  // Outputs checked before the solve: distinct, not the input, writable. Standard output carries the
  // report or the JSON.
  const std::string out_file = cli.json_to_stdout && cli.out.empty() ? "-" : cli.out;
  CheckOutputPaths({{cli.json_to_stdout ? "standard output (the JSON)" : "standard output (the report)", "-"},
                    {"--out", out_file == "-" && cli.json_to_stdout ? "" : out_file},
                    {"--svg", cli.svg}},
                   {{"problem file", cli.problem.file()}});
  *problem = cli.problem.Load();
  IsoparallelSetup setup = IsoparallelSetupFor(*problem);
  if (cli.shooting) setup.options.enumerate_families = false;
  return setup;
}

// Solves with a progress line on stderr (progress.h): starts done of all for the multi-start,
// the elapsed time for the family enumeration.
plateball::IsoparallelSummary SolveWithProgress(plateball::IsoparallelSetup setup, const std::string& program) {
  plateball::tools::Progress progress(program, 0);
  setup.options.progress = [&](int done, int total) {
    if (total > 0) progress.SetTotal(total), progress.Update(done);
  };
  return plateball::SolveIsoparallel(setup.problem, setup.options);
}

void PrintNoSolution(const plateball::IsoparallelSummary& summary,
                     const plateball::IsoparallelOptions& opt,
                     std::ostream& out) {
  using plateball::IsoparallelMethod;
  if (summary.status == plateball::IsoparallelStatus::kIntegrationFailure)
    out << "solver failed: " << plateball::ToString(summary.status) << ": " << summary.message << "\n";
  else if (summary.method == IsoparallelMethod::kFamilyEnumeration)
    out << "no solution found (family enumeration over 1.." << summary.periods_searched
        << " curvature periods, paths up to length " << summary.searched_length << ")\n";
  else
    out << "no solution found (" << summary.local_solves << " local solves from " << opt.starts
        << (summary.seeded ? " starts, " : " shapes, ")
        << (summary.seeded ? "seed " + std::to_string(opt.seed) : "deterministic") << ", paths up to length "
        << summary.searched_length << ")\n";
}

// Jacobi's condition for the shortest and how many solutions meet it; the Maxwell pairs.
void PrintConjugatePoints(const plateball::IsoparallelSummary& summary, std::ostream& out) {
  const plateball::IsoparallelSolution& best = summary.Shortest();
  int local = 0;
  for (const plateball::IsoparallelSolution& s : summary.solutions) local += s.locally_optimal ? 1 : 0;
  const std::streamsize precision = out.precision(10);
  out << "first conjugate point of the shortest: ";
  if (!std::isfinite(best.conjugate_time))
    out << "none up to " << plateball::kConjugateSearchFactor << "x its length";
  else if (best.locally_optimal && best.conjugate_time <= best.length * (1 + plateball::kConjugateEndTolerance))
    out << "at its end (s = " << best.conjugate_time << ")";
  else
    out << "s = " << best.conjugate_time;
  out << (best.locally_optimal ? ", none before the end: locally optimal" : ", before the end: NOT locally optimal")
      << "; locally optimal: " << local << " of " << summary.solutions.size()
      << " solutions; Maxwell pairs (equal length): " << summary.maxwell_pairs.size() << "\n";
  out.precision(precision);
}

void PrintSolutions(const plateball::IsoparallelSummary& summary,
                    const plateball::IsoparallelOptions& opt,
                    std::ostream& out) {
  using namespace plateball;
  const IsoparallelSolution& best = summary.Shortest();
  out << "solutions found: " << summary.solutions.size() << " (distinct, up to " << opt.length_cap_factor
      << "x the shortest; ";
  if (summary.method == IsoparallelMethod::kFamilyEnumeration)
    out << "identity target: one-parameter families enumerated over 1.." << summary.periods_searched
        << " curvature periods, " << (summary.complete ? "certified complete" : "NOT certified complete") << ")\n";
  else
    out << opt.starts << (summary.seeded ? " starts, " : " shapes, ")
        << (summary.seeded ? "seed " + std::to_string(opt.seed) : "deterministic")
        << ": a sample, NOT certified complete)\n";
  out << std::setprecision(10) << "shortest length: " << best.length << std::setprecision(6) << "  ("
      << ToString(best.parameters.regime) << " pendulum, G = " << best.G << ", energy = " << best.energy << ", "
      << best.periods << " curvature period(s)"
      << (best.family ? ", a one-parameter family: phase free, phase 0 reported" : "") << ")\n";
  out << std::setprecision(3) << "verified by rolling (Runge-Kutta-Fehlberg 7(8)): orientation residual "
      << best.orientation_residual << " rad, endpoint error " << best.endpoint_error << "\n";
  PrintConjugatePoints(summary, out);
}

void PrintPlan(const plateball::PlanSummary& plan,
               double final_error,
               double solve_seconds,
               double plan_seconds,
               std::ostream& out) {
  out << "impulses: " << plan.steps.size() << " (" << plateball::ToString(plan.status) << "), max pass miss "
      << plan.max_pass_miss << "\n";
  if (plan.IsSolutionUsable()) {
    out << "final orientation error ||A_goal - A~_n|| = " << final_error << ", bound (Theorem 2.6) "
        << plan.bounds.theorem_2_6 << ", a-posteriori bound " << plan.bounds.a_posteriori << "\n";
  } else {
    out << "impulsive plan failed: " << plan.message << " (try more impulses)\n";
  }
  out << std::setprecision(3) << "time: solve " << solve_seconds * 1e3 << " ms, plan " << plan_seconds * 1e3 << " ms\n";
  out.flush();
}

// --exact: exact arrival at the goal (position and orientation) with the same impulse count along
// the optimal path (exact_arrival.h), re-integrated independently; one line on standard output.
struct ExactRun {
  plateball::ExactArrivalProblem problem;
  plateball::ExactArrivalSummary summary;
  plateball::ReplayResult replay;
};
ExactRun SolveExact(const plateball::Problem& problem,
                    const plateball::IsoparallelSolution& best,
                    int impulses,
                    std::ostream& out) {
  using namespace plateball;
  const ExactArrivalSetup setup = ExactArrivalSetupFor(problem, best, impulses, "--impulses");
  const auto t0 = std::chrono::steady_clock::now();
  ExactRun r{setup.problem, SolveExactArrival(setup.problem, setup.options), {}};
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  r.replay = ReplayExactArrival(setup.problem, r.summary.impulses);
  out << std::setprecision(3) << "exact arrival: " << ToString(r.summary.status) << " with "
      << r.summary.impulses.size() << " impulses, re-integrated errors: position " << r.replay.position_error
      << ", orientation " << r.replay.orientation_error << " rad; max pass-point displacement "
      << r.summary.max_pass_displacement << ", total time " << r.summary.total_time << ", " << r.summary.iterations
      << " iterations, " << seconds * 1e3 << " ms\n";
  return r;
}

// The --certify options, checked before the solve (a bad value must not cost a solve).
void CheckCertifyOptions(const IsoparallelCliOptions& cli, const plateball::IsoparallelProblem& prob) {
  using plateball::IsoparallelCertificateOptions;
  RequireIntegerInRange("--certify-budget", cli.certify_budget, 1, IsoparallelCertificateOptions::kMaxBoxes);
  if (!(cli.certify_cap >= 1.0 && cli.certify_cap <= plateball::IsoparallelOptions::kMaxLengthCapFactor))
    ThrowInvalidInput(CommandLineField("--certify-cap"), FormatNumber(cli.certify_cap), "must be in [1, 10]");
  const double chord = (prob.goal - prob.start).norm();
  if (cli.certify_length_given && !(cli.certify_length > chord && cli.certify_length <= 1e3))
    ThrowInvalidInput(CommandLineField("--certify-length"),
                      FormatNumber(cli.certify_length),
                      "must exceed |goal - start| = " + FormatNumber(chord) + " and be <= 1000");
}

// --certify: the certificate of the solution list (isoparallel_certificate.h), one line per
// piece on standard error as it ends (not under --quiet), the result on `out`.
plateball::IsoparallelCertificate Certify(const IsoparallelCliOptions& cli,
                                          const plateball::IsoparallelSummary& summary,
                                          std::ostream& out) {
  using namespace plateball;
  IsoparallelCertificateOptions o;
  o.cap_factor = cli.certify_cap;
  if (cli.certify_length_given) o.length_cap = cli.certify_length;
  o.max_boxes = cli.certify_budget;
  o.threads = summary.options.threads;
  o.progress = [&](const IsoparallelCertificatePiece& p, int done, int total) {
    if (Verbose())
      std::cerr << cli.program << ": certificate piece " << done << " of " << total << ": "
                << (p.closed ? "closed, " : "NOT closed, ") << p.name << " (" << p.boxes << " boxes, "
                << std::setprecision(3) << p.cpu_seconds << " s CPU)" << std::endl;
  };
  const IsoparallelCertificate c = CertifyIsoparallel(summary, o);
  out << "certificate: " << ToString(c.status);
  if (!c.IsComplete()) {
    out << ": " << c.message << "\n";
    return c;
  }
  out << std::setprecision(10) << " up to length " << c.length_cap << std::setprecision(6);
  if (!cli.certify_length_given) out << " (" << cli.certify_cap << " x 1.0001 x the shortest)";
  out << ": " << c.solutions.size() << " solution(s), " << c.MissedBySolver() << " of them not in the solver's list ("
      << c.boxes << " boxes in " << c.pieces.size() << " pieces, " << std::setprecision(4) << c.cpu_seconds
      << " s CPU)\n";
  for (const CertifiedSolution& m : c.solutions)
    if (m.solver_index < 0)
      out << std::setprecision(10) << "  missed by the solver: " << ToString(m.regime) << ", length " << m.length
          << ", rate " << m.rate << ", k " << m.modulus << ", phase " << m.phase << "\n";
  return c;
}

Json CertificateJson(const plateball::IsoparallelCertificate& c, double cap_factor) {
  Json sols = Json::array(), pieces = Json::array();
  for (const plateball::CertifiedSolution& s : c.solutions)
    sols.push_back(Json{{"regime", plateball::ToString(s.regime)},
                        {"rate", s.rate},
                        {"modulus", s.modulus},
                        {"phase", s.phase},
                        {"length", s.length},
                        {"solver_index", s.solver_index}});
  for (const plateball::IsoparallelCertificatePiece& p : c.pieces)
    pieces.push_back(Json{{"name", p.name},
                          {"closed", p.closed},
                          {"result", p.result},
                          {"boxes", p.boxes},
                          {"resolved_volume", p.resolved_volume},
                          {"proved", p.proved}});
  // The result state without "report" (its BriefReport has a wall time; docs/output_contract.md).
  return Json{{"status", plateball::ToString(c.status)},
              {"usable", c.IsSolutionUsable()},
              {"message", c.message},
              {"complete", c.IsComplete()},
              {"cap_factor", cap_factor},
              {"length_cap", c.length_cap},
              {"straight_residual", c.straight_residual},
              {"solutions", std::move(sols)},
              {"solver_unproved", c.solver_unproved},
              {"pieces", std::move(pieces)},
              {"boxes", c.boxes}};
}

int Run(const IsoparallelCliOptions& cli, std::ostream& out) {
  using namespace plateball;
  Problem problem;
  const IsoparallelSetup setup = LoadSetup(cli, &problem);
  const ActuatorRequest request = cli.actuator.Request();
  const IsoparallelProblem& prob = setup.problem;
  const IsoparallelOptions& opt = setup.options;
  const int impulses = cli.impulses_opt->count() == 0
                           ? 0
                           : static_cast<int>(RequireIntegerInRange("--impulses", cli.impulses, 1, 10'000));
  if (cli.certify) CheckCertifyOptions(cli, prob);
  // Exact arrival needs 2n unknowns >= 5 conditions (exact_arrival.h): checked before the solve.
  if (cli.exact && impulses != 0 && (impulses < 3 || impulses > plateball::kMaxExactImpulses))
    ThrowInvalidInput(CommandLineField("--impulses"),
                      std::to_string(impulses),
                      "--exact needs 3 ... " + std::to_string(plateball::kMaxExactImpulses) + " impulses");
  const IsoparallelSummary summary = SolveWithProgress(setup, cli.program);

  const double angle =
      RotationAngle(prob.goal_orientation * prob.start_orientation.transpose(), Eigen::Matrix3d::Identity());
  const std::string name = ProblemName(problem);
  out << std::setprecision(6);
  out << cli.program << ": " << TerminalSafe(name) << ": (" << prob.start.x() << ", " << prob.start.y() << ") -> ("
      << prob.goal.x() << ", " << prob.goal.y() << "), target reorientation angle " << angle << " rad\n";
  if (!summary.IsSolutionUsable()) {
    PrintNoSolution(summary, opt, out);
    return kExitNoSolution;
  }
  PrintSolutions(summary, opt, out);
  const IsoparallelSolution& best = summary.Shortest();
  const IsoparallelPlanSetup plan_setup = IsoparallelPlanSetupFor(problem, best, impulses);
  const auto t_plan = std::chrono::steady_clock::now();
  const PlanSummary plan = PlanOptimalPath(plan_setup.problem, plan_setup.options);
  const double plan_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t_plan).count();
  const double final_error = OperatorNormDistance(prob.goal_orientation, plan.A_impulsive);
  PrintPlan(plan, final_error, summary.time_seconds, plan_seconds, out);

  const std::vector<Eigen::Vector2d> path_pts = SamplePath(best, 400);
  const std::vector<std::vector<Eigen::Vector2d>> arcs =
      plan.IsSolutionUsable() ? SampleArcs(problem.model, plan, 40) : std::vector<std::vector<Eigen::Vector2d>>{};
  std::optional<ExactRun> exact;
  if (cli.exact) exact = SolveExact(problem, best, impulses, out);
  std::optional<IsoparallelCertificate> certificate;
  if (cli.certify && summary.complete)
    out << "certificate: not needed (the family enumeration is complete up to the cap)\n";
  else if (cli.certify)
    certificate = Certify(cli, summary, out);
  if (!cli.out.empty() || cli.json_to_stdout) {
    Json doc = PlanFileJson(cli, problem, prob, opt, summary, path_pts, plan, arcs, final_error, request);
    const ActuatorContext exact_actuator{problem, request, "exact."};
    if (exact) doc["exact"] = ExactArrivalToJson(exact->summary, exact->replay, true, &exact_actuator);
    if (certificate) doc["certificate"] = CertificateJson(*certificate, cli.certify_cap);
    WriteJson(doc, cli.out);
  }
  if (!cli.svg.empty() && exact)
    DrawExactArrival(exact->problem, exact->summary, name + ": exact arrival", cli.svg);
  else if (!cli.svg.empty())
    Figure(name, prob, best, path_pts, arcs, plan).Write(cli.svg);
  if (exact && !exact->summary.IsSolutionUsable()) return kExitNoSolution;
  if (!plan.IsSolutionUsable()) return kExitNoSolution;
  return certificate && !certificate->IsComplete() ? kExitNotCertified : kExitSuccess;
}

}  // namespace

void AddIsoparallelOptions(CLI::App& app, IsoparallelCliOptions& cli) {
  cli.problem.SetDefault(kFigure7, "figure7 (built-in)");
  cli.problem.Add(app);
  cli.problem.AddIsoparallel(app);
  cli.impulses_opt =
      app.add_option("--impulses", cli.impulses, "number of impulses, 1 ... 1e4 (overrides isoparallel.impulses)");
  app.add_option(
      "--out",
      cli.out,
      cli.json_to_stdout ? "write the JSON to this file instead of standard output" : "write the full plan as JSON");
  app.add_option("--svg", cli.svg, "write an SVG figure of the plate (as Figure 7)");
  AddFigureSizeOption(app);
  app.add_flag(
      "--shooting", cli.shooting, "identity targets: use the multi-start shooting instead of the family enumeration");
  CLI::Option* certify =
      app.add_flag("--certify",
                   cli.certify,
                   "general targets: also certify the solution list, every solution up to --certify-cap x 1.0001 x the "
                   "shortest proved and the rest of parameter space excluded (an offline check: minutes to hours; "
                   "JSON section \"certificate\", exit code 7 when it does not close)");
  app.add_option("--certify-cap",
                 cli.certify_cap,
                 "with --certify: the length cap as a factor of the shortest, 1 ... 10 "
                 "(default 1: the shortest proved the shortest)")
      ->needs(certify);
  app.add_option_function<double>(
         "--certify-length",
         [&cli](double length) {
           cli.certify_length = length;
           cli.certify_length_given = true;
         },
         "with --certify: the length cap itself instead (a cap below the shortest proves that no solution is "
         "shorter)")
      ->needs(certify)
      ->excludes("--certify-cap");
  app.add_option("--certify-budget", cli.certify_budget, "with --certify: boxes per piece, 1 ... 1e10 (default 2.5e8)")
      ->needs(certify);
  app.add_flag("--exact",
               cli.exact,
               "also solve exact arrival at the goal position and orientation with the same impulse count "
               "(JSON section \"exact\", SVG: the exact trajectory)");
  cli.actuator.Add(app);
}

int RunIsoparallel(const IsoparallelCliOptions& cli) {
  // `plateball isoparallel` prints the JSON on standard output and its report on standard error,
  // `isoparallel_solve` its report on standard output (and the JSON with --out).
  return Run(cli, cli.json_to_stdout ? std::cerr : std::cout);
}

}  // namespace plateball::tools
