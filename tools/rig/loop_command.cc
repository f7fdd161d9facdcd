#include "rig/loop_command.h"

#include <mujoco/mujoco.h>

#include <cmath>
#include <memory>
#include <string>

#include "common/exit_codes.h"
#include "common/invalid_input.h"
#include "common/json_output.h"
#include "common/number_format.h"
#include "common/output_file.h"
#include "common/problem_options.h"
#include "common/rig_plan_output.h"
#include "common/units.h"
#include "plateball/closed_loop.h"
#include "plateball/task_adapters.h"
#include "rig/twin_loop.h"

namespace plateball::tools {
namespace {

struct LoopCliOptions {
  ProblemOptions problem;
  long long n = 0;
  CLI::Option* n_opt = nullptr;
  std::string noise = "none";
  long long trial = 0;
  std::string strategy = "feedback";
  double tick = 1e-4;
  double dt = 1e-4;
  bool contact_point_only = false;
  double pulse_duration = 0.0;
  std::string out;
  bool rig_check_only = false;
};

std::string Option(const char* name) { return CommandLineField(name); }

Json ErrorsJson(const ErrorModel& e) {
  return Json{{"impulse_magnitude", e.impulse_magnitude},
              {"impulse_angle", e.impulse_angle},
              {"timing", e.timing},
              {"energy_loss", e.energy_loss},
              {"lambda", e.lambda},
              {"observation", e.observation},
              {"pulse_duration", e.pulse_duration},
              {"pulse_causal", e.pulse_causal}};
}

Json RunJson(const rig::TwinLoopRun& r, bool closed, bool pulsed) {
  Json impulses = Json::array();
  for (const rig::TwinLoopImpulse& i : r.impulses)
    impulses.push_back(Json{{"k", i.k},
                            {"tick", closed ? Json(i.tick) : Json(nullptr)},
                            {"t", i.t},
                            {"x", ToJson(i.x)},
                            {"delta_omega", ToJson(i.delta_omega)},
                            {"applied_delta_omega", ToJson(i.applied)},
                            {"plate_impulse", ToJson(i.plate_impulse)},
                            {"pulse_impulse", pulsed ? ToJson(i.pulse_impulse) : Json(nullptr)},
                            {"exact_replan", i.exact_replan},
                            {"late", i.late}});
  Json j{{"status", ToString(r.status)},
         {"ticks", r.ticks},
         {"rejected_measurements", r.rejected},
         {"exact_solves", r.exact_solves},
         {"steps", r.steps},
         {"t_end", r.t_end},
         {"position_error", r.position_error},
         {"orientation_error", r.orientation_error},
         {"max_slip_speed", r.max_slip_speed},
         {"max_spin_rate", r.max_spin_rate},
         {"impulses", impulses}};
  if (!r.message.empty()) j["message"] = r.message;
  return j;
}

Json SimulatedJson(const SimulatedLoopResult& s) {
  return Json{{"status", ToString(s.status)},
              {"impulses", s.impulses},
              {"ticks", s.ticks},
              {"rejected_measurements", s.rejected},
              {"lambda", s.lambda},
              {"position_error", s.position_error},
              {"orientation_error", s.orientation_error}};
}

struct LoopSetup {
  std::shared_ptr<const NominalPlan> nominal;
  ControllerOptions controller;
  ErrorModel errors;
  std::uint64_t trial = 0;
  rig::TwinLoopOptions twin;
  RigNominal rig;  // the nominal plan's rig record (PlanOnRig; its plan is moved into `nominal`)
};

// The command line as the library's objects, every value checked and named by its option.
LoopSetup BuildLoop(const LoopCliOptions& o, const Problem& p) {
  if (!p.physical)
    ThrowInvalidInput(
        "ball.physical", "(missing)", "the twin needs the ball's physical parameters (problem " + p.source + ")");
  if (const std::string m = rig::TwinBuildableMessage(*p.physical); !m.empty()) throw std::invalid_argument(m);
  const int n = o.n_opt->count() == 0 ? 0 : static_cast<int>(RequireIntegerInRange("--impulses", o.n, 1, 10'000));
  if (n > 0) RequirePartitionSteps("--impulses", n, p);
  LoopSetup s;
  s.errors = ParseErrorModel(o.noise, Option("--noise"));
  rig::RequireTwinModelled(s.errors, Option("--noise"));
  s.trial = static_cast<std::uint64_t>(RequireIntegerInRange("--trial", o.trial, 0, 1'000'000'000));
  s.controller.strategy = ParseExecutionStrategy(o.strategy, Option("--strategy"));
  if (s.controller.strategy == ExecutionStrategy::kOpenLoop)
    ThrowInvalidInput(Option("--strategy"),
                      o.strategy,
                      "the controller feeds back (feedback, feedback_exact); the open loop is always run beside it");
  if (!(std::isfinite(o.tick) && o.tick >= 1e-5 && o.tick <= 0.1))
    ThrowInvalidInput(Option("--tick"), FormatNumber(o.tick), "must be in [1e-5, 0.1] s");
  if (!(std::isfinite(o.dt) && o.dt > 0 && o.dt <= o.tick))
    ThrowInvalidInput(
        Option("--dt"), FormatNumber(o.dt), "must be in (0, --tick] s (the engine steps within each tick)");
  s.controller.tick_period = o.tick;
  // Not a real-time loop: the budget never cuts an exact re-plan short, so the run is reproducible.
  s.controller.time_budget = 10.0;
  s.controller.physical = *p.physical;
  s.twin.settings.timestep = o.dt;
  s.twin.contact_point_only = o.contact_point_only;
  if (!(std::isfinite(o.pulse_duration) && o.pulse_duration >= 0))
    ThrowInvalidInput(
        Option("--pulse-duration"), FormatNumber(o.pulse_duration), "must be finite and >= 0 s (0: ideal jumps)");
  s.twin.pulse_duration = o.pulse_duration;
  const PlanSetup setup = PlanSetupFor(p, n, Option("--impulses"));
  // With a rig section the nominal plan honours it as `plateball plan`'s does (unless --rig-check-only).
  s.rig = PlanOnRig(p, setup, o.rig_check_only);
  auto nominal = std::make_shared<NominalPlan>(MakeNominalPlan(setup.problem, setup.options, std::move(s.rig.plan)));
  if (!nominal->plan.IsSolutionUsable())
    throw std::runtime_error("the nominal plan failed: " + nominal->plan.BriefReport());
  if (!s.rig.limits_met && !o.rig_check_only)
    throw std::runtime_error("limits_not_met: " + s.rig.message + " (--rig-check-only runs the plan as given)");
  if (o.pulse_duration > 0) {
    const rig::RigPlan plan = rig::RigPlanOf(*nominal, *p.physical);
    rig::CheckPulseWindows(plan, o.pulse_duration, Option("--pulse-duration"));
    rig::CheckPulseFriction(plan, o.pulse_duration, s.twin.settings, Option("--pulse-duration"));
  }
  if (s.errors.lambda != 0.0)
    rig::BallWithLambda(*p.physical,
                        TrialErrors(s.errors, p.seed, s.trial).TrueLambda(nominal->model.lambda()),
                        Option("--noise") + " lambda");
  s.nominal = std::move(nominal);
  return s;
}

std::string Brief(const rig::TwinLoopRun& closed, const rig::TwinLoopRun& open, const SimulatedLoopResult& sim) {
  return "closed loop in the twin " + ToString(closed.status) + " after " + std::to_string(closed.impulses.size()) +
         " impulses: position error " + FormatNumber(closed.position_error) + ", orientation error " +
         FormatNumber(closed.orientation_error) + " (open loop in the twin " + FormatNumber(open.position_error) +
         ", " + FormatNumber(open.orientation_error) + "; the library's simulated closed loop " +
         FormatNumber(sim.position_error) + ", " + FormatNumber(sim.orientation_error) + ")";
}

int RunLoop(const LoopCliOptions& o) {
  CheckOutputPaths({{"--out", o.out.empty() ? "-" : o.out}}, {{"PROBLEM.json", o.problem.file()}});
  const Problem p = o.problem.Load();
  const LoopSetup s = BuildLoop(o, p);
  const TrialErrors errors(s.errors, p.seed, s.trial);
  Controller controller(s.nominal, s.controller);
  const rig::TwinLoopRun closed = rig::RunTwinClosedLoop(controller, *p.physical, errors, s.twin);
  const rig::TwinLoopRun open = rig::RunTwinOpenLoop(*s.nominal, *p.physical, errors, s.twin);
  const SimulatedLoopResult sim =
      RunSimulatedClosedLoop(s.nominal, s.controller, s.errors, p.seed, s.trial, s.twin.contact_point_only);
  Json doc = HeaderJson("plateball", "rig_loop", p, o.problem.file());
  doc["initial"] = InitialJson(p);
  doc["initial"]["orientation"] = ToJson(s.nominal->plan.A0);
  doc["settings"] = TwinSettingsJson(s.twin.settings);
  doc["loop"] = Json{
      {"strategy", ToString(s.controller.strategy)},
      {"tick_period", s.controller.tick_period},
      {"contact_point_only", s.twin.contact_point_only},
      {"execution",
       Json{{"kind", o.pulse_duration > 0 ? "causal_pulses" : "ideal_jumps"}, {"pulse_duration", o.pulse_duration}}},
      {"trial", s.trial},
      {"errors", ErrorsJson(s.errors)},
      {"true_lambda", errors.TrueLambda(s.nominal->model.lambda())}};
  doc["nominal"] = Json{{"impulse_count", s.nominal->plan.steps.size()},
                        {"total_time", s.nominal->plan.total_time},
                        {"goal", ToJson(s.nominal->goal)},
                        {"plan_orientation_error", s.nominal->plan_orientation_error}};
  doc["closed_loop"] = RunJson(closed, true, o.pulse_duration > 0);
  doc["open_loop"] = RunJson(open, false, o.pulse_duration > 0);
  doc["simulated_rig"] = SimulatedJson(sim);
  const bool done = closed.status == ControllerStatus::kDone;
  Append(doc, ResultJson(ToString(closed.status), done, done ? "" : closed.message, Brief(closed, open, sim)));
  if (!s.rig.rig.is_null()) {
    doc["rig"] = s.rig.rig;
    doc["report"] = doc["report"].get<std::string>() +
                    (s.rig.limits_met ? "; rig limits met" + s.rig.note
                                      : "; rig limits NOT met (--rig-check-only: the loop ran the plan as given)");
  }
  AddPhysicalUnits(p, &doc);
  WriteJson(doc, o.out);
  return done ? kExitSuccess : kExitNoSolution;
}

}  // namespace

Json TwinSettingsJson(const rig::TwinSettings& s) {
  return Json{{"integrator", "RK4"},
              {"timestep", s.timestep},
              {"cone", "elliptic"},
              {"condim", 4},
              {"contact_time_constant", s.time_constant_steps * s.timestep},
              {"contact_damping_ratio", 1.0},
              {"sliding_friction", s.sliding_friction},
              {"torsional_friction", s.torsional_friction},
              {"noslip_iterations", s.noslip_iterations},
              {"gravity", s.gravity},
              {"mujoco_version", mj_versionString()}};
}

std::function<int()> SetupRigLoop(CLI::App& sub) {
  auto o = std::make_shared<LoopCliOptions>();
  o->problem.Add(sub);
  o->n_opt = sub.add_option("--impulses", o->n, "impulses of the plan, overrides plan.partition.n");
  sub.add_option("--noise",
                 o->noise,
                 "the trial's errors KEY=VALUE[,KEY=VALUE] with keys impulse_magnitude, impulse_angle, energy_loss, "
                 "lambda (default none; drawn as montecarlo's trial from the problem's seed)");
  sub.add_option("--trial", o->trial, "the trial whose errors are drawn (default 0)");
  sub.add_option("--strategy", o->strategy, "feedback or feedback_exact (default feedback)");
  sub.add_option("--tick", o->tick, "the loop's tick period in s (default 1e-4)");
  sub.add_option("--dt", o->dt, "the engine's RK4 timestep in s, at most the tick (default 1e-4)");
  sub.add_flag(
      "--contact-point-only", o->contact_point_only, "measure the contact point alone (a camera without orientation)");
  sub.add_option(
      "--pulse-duration",
      o->pulse_duration,
      "causal pulses: a force J/D on the plate over [t_k, t_k + D] s from each decision (default 0: ideal jumps)");
  sub.add_option("--out", o->out, "write the JSON to this file instead of standard output (\"-\": standard output)");
  sub.add_flag("--rig-check-only",
               o->rig_check_only,
               "with a rig section: plan the partition as given, check it against the limits and run the loop "
               "whatever the check says (default: honour the limits as `plateball plan` does, and refuse a plan "
               "that cannot meet them, exit 4)");
  return [o] { return RunLoop(*o); };
}

}  // namespace plateball::tools
