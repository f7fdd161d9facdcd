// `plateball rig export|replay RESULT.json`: the MuJoCo digital twin of a plan (rig/mujoco_twin.h), from
// a result of `plan`, `steer` or `isoparallel`.
// export writes the machine as MJCF and the pulse schedule beside it; replay runs the plan in MuJoCo
// and reports how far the engine's ball ends from the plan. `rig loop PROBLEM.json` runs the
// real-time controller with the twin as its plant (rig/loop_command.h).
#include <mujoco/mujoco.h>

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>

#include "common/actuator_json.h"
#include "common/command_registry.h"
#include "common/exit_codes.h"
#include "common/invalid_input.h"
#include "common/json_output.h"
#include "common/number_format.h"
#include "common/output_file.h"
#include "common/units.h"
#include "plateball/actuator_command.h"
#include "rig/loop_command.h"
#include "rig/mujoco_twin.h"
#include "rig/rig_plan.h"

namespace plateball::tools {
namespace {

struct RigCliOptions {
  std::string result;
  std::string mjcf;
  std::string out;
  double dt = 1e-3;
  double pulse_duration = 0.0;
  bool causal = false;
  CLI::App* export_cmd = nullptr;
  CLI::App* replay_cmd = nullptr;
};

// Options named as on the command line in every message.
rig::ReplayOptions ReplayOptionsOf(const RigCliOptions& o) {
  rig::ReplayOptions r;
  r.settings.timestep = o.dt;
  r.pulse_duration = o.pulse_duration;
  r.causal = o.causal;
  if (!(std::isfinite(o.dt) && o.dt > 0 && o.dt <= 0.1))
    ThrowInvalidInput(CommandLineField("--dt"), FormatNumber(o.dt), "must be in (0, 0.1] s");
  if (!(std::isfinite(o.pulse_duration) && o.pulse_duration >= 0))
    ThrowInvalidInput(CommandLineField("--pulse-duration"),
                      FormatNumber(o.pulse_duration),
                      "must be finite and >= 0 s (0: ideal velocity jumps)");
  if (o.causal && o.pulse_duration == 0)
    ThrowInvalidInput(
        CommandLineField("--pulse-causal"), "true", "needs --pulse-duration > 0 (ideal jumps have no window)");
  return r;
}

void RequireBuildable(const rig::RigPlan& plan) {
  const std::string m = rig::TwinBuildableMessage(plan.physical);
  if (!m.empty()) throw std::invalid_argument(m);
}

// Messages of the library name "pulse_duration"; the command line calls it --pulse-duration.
template <typename F>
auto WithOptionNames(F f) {
  try {
    return f();
  } catch (const std::invalid_argument& e) {
    std::string m = e.what();
    if (m.rfind("pulse_duration:", 0) == 0)
      m = CommandLineField("--pulse-duration") + m.substr(std::string("pulse_duration").size());
    throw std::invalid_argument(m);
  }
}

std::string ScheduleFileFor(const std::string& mjcf) {
  std::filesystem::path p(mjcf);
  p.replace_extension(".pulses.json");
  return p.string();
}

Json ScheduleJson(const RigCliOptions& o, const rig::RigPlan& plan, const std::string& schedule_file) {
  const double D = o.pulse_duration;
  Json doc = HeaderJson("plateball", "rig_export", plan.problem, plan.problem.source, false);
  doc["result"] = o.result;
  doc["mjcf"] = o.mjcf;
  doc["schedule"] = schedule_file;
  doc["settings"] = TwinSettingsJson(ReplayOptionsOf(o).settings);
  doc["pulse_duration"] = D;
  doc["pulse_alignment"] =
      D > 0 ? Json(PulseAlignmentName(o.causal ? PulseAlignment::kCausal : PulseAlignment::kCentred)) : Json(nullptr);
  doc["start"] =
      Json{{"t", 0.0}, {"x0", ToJson(plan.x0)}, {"orientation", ToJson(plan.A0)}, {"omega", ToJson(plan.start.omega)}};
  Json pulses = Json::array();
  for (std::size_t k = 0; k < plan.impulses.size(); ++k) {
    const rig::RigImpulse& i = plan.impulses[k];
    ActuatorRequest request;  // the engine's friction is checked by CheckPulseFriction
    request.has_pulse = D > 0;
    if (D > 0) request.pulse.duration = D;
    Json j{
        {"k", k},
        {"t_impulse", i.t},
        {"z", ToJson(i.z)},
        {"delta_omega", ToJson(i.delta_omega)},
        {"omega_after", ToJson(i.omega_after)},
        {"actuator", ActuatorJson(plan.problem, i.z, i.delta_omega, request, "impulses[" + std::to_string(k) + "]")}};
    const double start = o.causal ? i.t : i.t - D / 2;
    if (D > 0) j["window"] = Json::array({start, start + D});
    pulses.push_back(std::move(j));
  }
  doc["pulses"] = std::move(pulses);
  return doc;
}

int RunExport(const RigCliOptions& o) {
  const std::string schedule = ScheduleFileFor(o.mjcf);
  CheckOutputPaths({{"--mjcf", o.mjcf}, {"--mjcf (schedule)", schedule}}, {{"RESULT.json", o.result}});
  const rig::RigPlan plan = rig::ReadRigPlan(o.result);
  RequireBuildable(plan);
  const rig::ReplayOptions options = ReplayOptionsOf(o);
  if (o.pulse_duration > 0) {
    WithOptionNames([&] {
      rig::CheckPulseWindows(plan, o.pulse_duration, "pulse_duration");
      rig::CheckPulseFriction(plan, o.pulse_duration, options.settings, "pulse_duration");
      return 0;
    });
  }
  rig::TwinSettings settings = options.settings;
  settings.plate_half_size_radii = rig::PlateHalfSizeFor(plan, rig::PlannedTrajectory(plan), settings);
  const std::string xml = rig::TwinMjcf(plan.physical, plan.x0, plan.A0, settings, plan.start.omega);
  Json doc = ScheduleJson(o, plan, schedule);
  AddPhysicalUnits(plan.problem, &doc);
  WriteOutput(o.mjcf, xml);
  WriteOutput(schedule, DumpJson(doc));
  WriteJson(doc, "");  // the schedule on standard output too, as every subcommand prints its JSON
  return kExitSuccess;
}

int RunReplay(const RigCliOptions& o) {
  CheckOutputPaths({{"--out", o.out.empty() ? "-" : o.out}}, {{"RESULT.json", o.result}});
  const rig::RigPlan plan = rig::ReadRigPlan(o.result);
  RequireBuildable(plan);
  const rig::ReplayOptions options = ReplayOptionsOf(o);
  const rig::PlannedTrajectory reference(plan);
  const rig::ReplayReport r = WithOptionNames([&] { return rig::ReplayInTwin(plan, reference, options); });
  Json doc = HeaderJson("plateball", "rig_replay", plan.problem, plan.problem.source);
  doc["result"] = Json{{"file", o.result},
                       {"command", plan.command},
                       {"impulse_count", plan.impulses.size()},
                       {"total_time", plan.t_end}};
  doc["settings"] = TwinSettingsJson(options.settings);
  doc["execution"] = Json{{"kind",
                           o.pulse_duration == 0 ? "ideal_jumps"
                           : o.causal            ? "causal_pulses"
                                                 : "centred_pulses"},
                          {"pulse_duration", o.pulse_duration}};
  doc["replay"] = Json{
      {"t_begin", r.t_begin},
      {"t_end", r.t_end},
      {"steps", r.steps},
      {"position_error", r.position_error},
      {"orientation_error", r.orientation_error},
      {"energy", Json{{"planned", r.energy_planned}, {"engine", r.energy_engine}, {"relative_error", r.energy_error}}},
      {"max_slip_speed", r.max_slip_speed},
      {"max_spin_rate", r.max_spin_rate}};
  AddPhysicalUnits(plan.problem, &doc);
  WriteJson(doc, o.out);
  return kExitSuccess;
}

void AddCommon(CLI::App& sub, RigCliOptions& o) {
  sub.add_option("result",
                 o.result,
                 "a result of `plateball plan`, `steer` or `isoparallel` (with its per-impulse records) whose problem "
                 "has ball.physical")
      ->required();
  sub.add_option("--dt", o.dt, "the engine's RK4 timestep in s (default 1e-3)");
  sub.add_option(
      "--pulse-duration",
      o.pulse_duration,
      "pulse duration D in s: force J/D on the plate over [t_k - D/2, t_k + D/2] (default 0: ideal velocity jumps)");
  sub.add_flag("--pulse-causal",
               o.causal,
               "with --pulse-duration: causal pulses over [t_k, t_k + D] (error O(D)) instead of centred (O(D^2))");
}

std::function<int()> SetupRig(CLI::App& sub) {
  auto o = std::make_shared<RigCliOptions>();
  sub.require_subcommand(1);
  o->export_cmd = sub.add_subcommand(
      "export",
      "write the machine of a plan as MuJoCo MJCF and its pulse schedule (JSON) beside it and on standard output");
  AddCommon(*o->export_cmd, *o);
  o->export_cmd
      ->add_option("--mjcf", o->mjcf, "the MJCF file to write; the schedule goes to the same name with .pulses.json")
      ->required();
  o->replay_cmd =
      sub.add_subcommand("replay", "run a plan in MuJoCo and report how far the engine ends from it (JSON)");
  AddCommon(*o->replay_cmd, *o);
  o->replay_cmd->add_option(
      "--out", o->out, "write the JSON to this file instead of standard output (\"-\": standard output)");
  CLI::App* loop_cmd = sub.add_subcommand("loop",
                                          "run the real-time controller with the twin as its plant, beside the open "
                                          "loop and the library's simulated loop (JSON)");
  const std::function<int()> run_loop = SetupRigLoop(*loop_cmd);
  sub.footer(
      "The MuJoCo digital twin (docs/mujoco_twin.md): a fixed lower plate, the ball (inertia I1 I1 I3 along its\n"
      "symmetry axis) and the upper plate on slide joints pressed by its weight; condim 4 contacts with high\n"
      "sliding and torsional friction, elliptic cones, no-slip iterations, RK4, contact time constant 2 dt.\n"
      "Example: plateball plan problems/circle_physical.json --out circle.json && plateball rig replay circle.json\n"
      "Closed loop: plateball rig loop tests/data/rig_loop_physical.json --noise impulse_magnitude=0.02,lambda=0.02\n"
      "Exit codes: 0 ok, 2 usage, 3 invalid input (no ball.physical, a ball MuJoCo cannot build, overlapping\n"
      "pulses, too little friction), 4 the engine failed or the loop lost the ball, 5 unreadable or unwritable file.");
  return [o, loop_cmd, run_loop] {
    if (loop_cmd->parsed()) return run_loop();
    return o->export_cmd->parsed() ? RunExport(*o) : RunReplay(*o);
  };
}

const CommandRegistrar kRegistrar{{"rig",
                                   "the MuJoCo digital twin: export a plan's machine (MJCF), replay the plan in MuJoCo "
                                   "or close the controller's loop on it (JSON)",
                                   SetupRig}};

}  // namespace
}  // namespace plateball::tools
