// `plateball plan PROBLEM.json`: the impulses that make the ball follow the planned path of the
// problem's plan task (impulse_planner.h), as JSON, and optionally the plate as SVG (Figure 7:
// planned path dashed, impulsive trajectory solid, impulse points marked).
#include <cmath>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "common/actuator_json.h"
#include "common/command_registry.h"
#include "common/exit_codes.h"
#include "common/json_output.h"
#include "common/number_format.h"
#include "common/output_file.h"
#include "common/plan_json.h"
#include "common/problem_options.h"
#include "common/progress.h"
#include "common/rig_plan_output.h"
#include "common/svg.h"
#include "common/units.h"
#include "plateball/execution.h"
#include "plateball/free_motion.h"
#include "plateball/impulse_planner.h"
#include "plateball/path.h"
#include "plateball/task_adapters.h"

namespace plateball::tools {
namespace {

struct PlanCliOptions {
  ProblemOptions problem;
  long long n = 0;
  CLI::Option* n_opt = nullptr;
  std::string out;
  std::string svg;
  bool summary_only = false;
  ActuatorOptions actuator;
  double pulse_error = 0.0;
  CLI::Option* pulse_error_opt = nullptr;
  bool rig_check_only = false;
};

// The pulse schedule for a stated error: ChoosePulseDuration's duration (centred pulses, executed open
// loop against the ideal impulses) and per impulse its window, J and mean force (ActuatorJson).
Json PulseScheduleJson(const Problem& p,
                       const std::shared_ptr<const NominalPlan>& nominal,
                       double tolerance,
                       ActuatorRequest* request) {
  const PulseDurationChoice c = ChoosePulseDuration(nominal, tolerance, false);
  request->pulse.duration = c.duration;
  request->has_pulse = true;
  Json pulses = Json::array();
  for (const PlanStep& s : nominal->plan.steps) {
    const std::string where = "steps[" + std::to_string(s.global_index) + "]";
    const Json a = ActuatorJson(p, s.state_before.z, s.delta_omega, *request, where);
    pulses.push_back(Json{{"k", s.global_index},
                          {"centre", s.t_impulse},
                          {"window", Json::array({s.t_impulse - c.duration / 2, s.t_impulse + c.duration / 2})},
                          {"plate_impulse", a["plate_impulse"]},
                          {"mean_force", a["pulse"].is_null() ? Json(nullptr) : a["pulse"]["mean_force"]},
                          {"reason", a["reason"]}});
  }
  return Json{{"alignment", PulseAlignmentName(PulseAlignment::kCentred)},
              {"tolerance", tolerance},
              {"pulse_duration", c.duration},
              {"measured_error", c.measured_error},
              {"executions", c.executions},
              {"within", c.within},
              {"pulses", std::move(pulses)}};
}

void DrawPlan(const Problem& p, const Path& path, const PlanSummary& plan, const std::string& file) {
  SvgFigure fig;
  SvgFigure::Style planned{"#1f5fbf", 1.6, "7,5", "none"};
  SvgFigure::Style actual{"#c0392b", 1.4, "", "none"};
  SvgFigure::Style impulse{"black", 1.0, "", "black"};
  for (const SmoothCurve& c : path.pieces()) {
    std::vector<Eigen::Vector2d> pts;
    for (int i = 0; i <= 400; ++i) pts.push_back(c.Value(c.Begin() + (c.End() - c.Begin()) * i / 400.0));
    fig.Polyline(pts, planned);
  }
  // The impulsive trajectory: each free arc re-integrated from its impulse (free_motion.h).
  std::vector<Eigen::Vector2d> traj;
  Eigen::Vector2d x = path.StartPoint();
  Eigen::Matrix3d a = plan.A0;
  for (const PlanStep& s : plan.steps) {
    if (s.duration <= 0) break;
    FreeMotionStart fs;
    fs.state = s.impulse.state_after;
    fs.x0 = x;
    fs.A0 = a;
    std::vector<double> times;
    const int m = 24;
    for (int i = 0; i <= m; ++i) times.push_back(s.duration * i / m);
    for (const MotionSample& q : IntegrateFreeMotion(p.model, fs, times, p.integration)) traj.push_back(q.x);
    x = s.x_end;
    a = s.A_impulsive;
  }
  fig.Polyline(traj, actual);
  for (const PlanStep& s : plan.steps) fig.Marker(s.p_begin, 2.6, impulse);
  if (!plan.steps.empty()) fig.Marker(plan.steps.back().p_end, 2.6, impulse);
  const SmoothCurve& first = path.pieces().front();
  const SmoothCurve& last = path.pieces().back();
  fig.Start(path.StartPoint(), first.Derivative(first.Begin()), "p(0)");
  fig.Goal(path.EndPoint(), last.Derivative(last.End()), "p(T)");
  std::ostringstream title;
  title.precision(3);
  title << (p.name.empty() ? std::string("plan") : p.name) << ": n = " << plan.segments << ", error "
        << plan.measured_error << " <= bound " << plan.bounds.a_posteriori;
  fig.Title(title.str());
  fig.Legend("planned path p(tau)", planned);
  fig.Legend("impulsive trajectory", actual);
  fig.Legend("impulse points p(tau_k)", impulse);
  fig.Write(file);
}

int RunPlan(const PlanCliOptions& o) {
  CheckOutputPaths({{"--out", o.out.empty() ? "-" : o.out}, {"--svg", o.svg}}, {{"PROBLEM.json", o.problem.file()}});
  const Problem p = o.problem.Load();
  const int n = o.n_opt->count() == 0 ? 0 : static_cast<int>(RequireIntegerInRange("--impulses", o.n, 1, 1'000'000));
  if (n > 0) RequirePartitionSteps("--impulses", n, p);
  const PlanSetup setup = PlanSetupFor(p, n, std::string(kCommandLine) + ": --impulses");
  ActuatorRequest request = o.actuator.Request();
  const bool schedule = o.pulse_error_opt->count() > 0;
  if (schedule && !(std::isfinite(o.pulse_error) && o.pulse_error > 0))
    ThrowInvalidInput(CommandLineField("--pulse-error"), FormatNumber(o.pulse_error), "must be finite and > 0");
  // With --pulse-error the plan is executed (execution.h), which needs its pass points and goal.
  // With a rig section the plan honours it (PlanImpulsesOnRig) unless --rig-check-only.
  RigNominal planned = [&] {
    Progress progress("plateball plan", 0);  // one solve: the elapsed time
    return PlanOnRig(p, setup, o.rig_check_only);
  }();
  const auto nominal = std::make_shared<const NominalPlan>([&] {
    if (schedule) return MakeNominalPlan(setup.problem, setup.options, std::move(planned.plan));
    NominalPlan n;
    n.plan = std::move(planned.plan);
    return n;
  }());
  const PlanSummary& plan = nominal->plan;
  const Path& path = setup.problem.path;

  Json doc = HeaderJson("plateball", "plan", p, o.problem.file());
  Json initial = InitialJson(p);
  initial["orientation"] = ToJson(plan.A0);
  doc["initial"] = std::move(initial);
  doc["path"] = Json{{"type", ToString(p.plan->path)}, {"pieces", path.PieceCount()}, {"length", path.Length()}};
  doc["partition"] = Json{{"type", ToString(p.plan->partition)}, {"segments", plan.segments}};
  if (schedule) {
    doc["pulse_schedule"] =
        plan.IsSolutionUsable() ? PulseScheduleJson(p, nominal, o.pulse_error, &request) : Json(nullptr);
    doc["pulse_schedule_reason"] = plan.IsSolutionUsable() ? Json(nullptr) : Json("the plan is not usable");
  }
  const ActuatorContext actuator{p, request, ""};
  Append(doc, PlanSummaryToJson(plan, !o.summary_only, &actuator));
  const bool within_limits = AddRigRecord(planned, &doc);
  AddPhysicalUnits(p, &doc);
  WriteJson(doc, o.out);
  if (!o.svg.empty()) DrawPlan(p, path, plan, o.svg);
  return plan.IsSolutionUsable() && within_limits ? kExitSuccess : kExitNoSolution;
}

std::function<int()> SetupPlan(CLI::App& sub) {
  auto o = std::make_shared<PlanCliOptions>();
  o->problem.Add(sub, ProblemOptions::Seed::kNone);  // deterministic: no --seed
  o->n_opt = sub.add_option(
      "--impulses,--n",
      o->n,
      "impulses (partition segments) per smooth piece, overrides plan.partition.n (--n: deprecated alias)");
  sub.add_option("--out", o->out, "write the JSON to this file instead of standard output (\"-\": standard output)");
  sub.add_option("--svg",
                 o->svg,
                 "draw the plate to this SVG file (planned path dashed, trajectory solid; \"-\": standard output, with "
                 "--out FILE)");
  AddFigureSizeOption(sub);
  o->pulse_error_opt =
      sub.add_option("--pulse-error",
                     o->pulse_error,
                     "emit a pulse schedule: centred pulses of a duration chosen from the measured "
                     "O(D^2) error and verified by executing open loop, ending within this error of the "
                     "ideal impulses' (position + rotation angle; \"within\" says whether it did); "
                     "the impulses' pulse records use it");
  o->actuator.Add(sub, o->pulse_error_opt);
  sub.add_flag("--summary-only", o->summary_only, "omit the per-impulse records");
  sub.add_flag("--rig-check-only",
               o->rig_check_only,
               "with a rig section: plan the partition as given and only check it against the limits "
               "(default: honour them, refining the partition and sliding its points onto the tick grid)");
  sub.footer(
      "Plans one energy-preserving impulse per partition point of plan.path (section 2.3): per impulse the\n"
      "time, p(tau_k), delta psi, delta omega, the upper plate's velocity change, the states and the\n"
      "orientations A(tau_k) (planned path), the polyline's and the impulsive trajectory's; the measured\n"
      "error ||A(T) - A_n|| and its bounds (Theorems 2.5, 2.6, Corollary 3, a-posteriori sum); the actuator's\n"
      "impulse J, contact impulses and, with --pulse-duration or --pulse-error, each pulse's force and the\n"
      "friction it needs (with ball.physical, docs/rig.md).\n"
      "Example: plateball plan problems/circle.json --summary-only --svg circle.svg\n"
      "With a rig section the plan honours its limits: the partition is refined where a flight leaves the plate\n"
      "or the stroke box or enters an obstacle, and its points slide along the path onto the tick grid; the\n"
      "limits it cannot change (the path itself outside, shortest interval, impulse bounds) are named in\n"
      "\"rig\": {\"blocking\"} with status limits_not_met. An independent replay checks every limit (\"rig\":\n"
      "{\"check\"}); --rig-check-only plans the partition as given and only checks it.\n"
      "Exit codes: 0 ok, 2 usage, 3 invalid input (also: friction below a pulse's need), 4 a segment could not be "
      "joined\n"
      "or the plan exceeds the rig's limits, 5 unreadable file.");
  return [o] { return RunPlan(*o); };
}

const CommandRegistrar kRegistrar{
    {"plan",
     "plan the impulses that follow a planned path, with orientations and error bounds (JSON, SVG)",
     SetupPlan}};

}  // namespace
}  // namespace plateball::tools
