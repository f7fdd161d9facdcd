// `plateball join`: join the initial contact point to nearby targets with one energy-preserving
// impulse each (Lemma 2.1, join.h) and print the solutions as JSON.
#include <memory>
#include <string>
#include <vector>

#include "common/command_registry.h"
#include "common/exit_codes.h"
#include "common/json_output.h"
#include "common/output_file.h"
#include "common/problem_options.h"
#include "common/progress.h"
#include "common/units.h"
#include "plateball/join.h"
#include "plateball/task_adapters.h"

namespace plateball::tools {
namespace {

struct JoinCliOptions {
  ProblemOptions problem;
  std::string targets;
  std::string out;
  int max_iterations = 30;
  double residual_tolerance = 1e-12;
};

Json ImpulseToJson(const Impulse& i) {
  return Json{{"angles_before", ToJson(i.before)},
              {"angles_after", ToJson(i.after)},
              {"mu", i.mu_after},
              {"delta_u", ToJson(i.delta_u)},
              {"delta_v0", i.delta_v0},
              {"delta_omega", ToJson(i.delta_omega)},
              {"plate_velocity_change", ToJson(i.plate_velocity_change)},
              {"omega_before", ToJson(i.state_before.omega)},
              {"omega_after", ToJson(i.state_after.omega)}};
}

Json JoinToJson(const JoinSummary& j) {
  Json out{{"target", ToJson(j.target)}};
  Append(out, ResultJson(ToString(j.status), j.IsSolutionUsable(), j.message, j.BriefReport()));
  Append(out,
         Json{{"delta_psi", j.delta_psi},
              {"t", j.t},
              {"residual", j.residual},
              {"iterations", j.iterations},
              {"initial_guess_residual", j.initial_guess_residual},
              {"time_limit_K1_distance", j.time_limit},
              {"jacobian_conditioning", j.jacobian_conditioning}});
  out["impulse"] = ImpulseToJson(j.impulse);
  out["arrival"] = Json{{"x", ToJson(j.x_after)},
                        {"angles", ToJson(j.angles_after)},
                        {"z", ToJson(j.state_after.z)},
                        {"omega", ToJson(j.state_after.omega)}};
  return out;
}

int RunJoin(const JoinCliOptions& o) {
  CheckOutputPaths({{"--out", o.out}}, {{"PROBLEM.json", o.problem.file()}});
  const Problem p = o.problem.Load();
  std::vector<Eigen::Vector2d> targets;
  if (!o.targets.empty())
    RequireCoordinatesOption("--targets", targets = ParsePointsOption("--targets", o.targets));
  else if (p.reach)
    targets = p.reach->targets;
  if (targets.empty())
    ThrowInvalidInput(CommandLineField("--targets"),
                      "(missing)",
                      "give targets with --targets X,Y;X,Y or in the file's reach.targets");
  JoinOptions options = JoinSetupFor(p, p.x0).options;
  options.max_iterations = static_cast<int>(RequireIntegerInRange("--max-iterations", o.max_iterations, 1, 10000));
  options.residual_tolerance = RequirePositiveOption("--residual-tolerance", o.residual_tolerance);

  Json doc = HeaderJson("plateball", "join", p, o.problem.file());
  doc["initial"] = InitialJson(p);
  doc["options"] = Json{{"max_iterations", options.max_iterations}, {"residual_tolerance", options.residual_tolerance}};
  doc["minimum_contact_speed"] = MinimumContactSpeed(p.mu, p.model);
  Json list = Json::array();
  bool all = true;
  Progress progress("plateball join", static_cast<double>(targets.size()));
  for (const auto& target : targets) {
    const JoinSummary j = Join(JoinSetupFor(p, target).problem, options);
    all = all && j.IsSolutionUsable();
    list.push_back(JoinToJson(j));
    progress.Update(static_cast<double>(list.size()));
  }
  doc["joins"] = std::move(list);
  AddPhysicalUnits(p, &doc);
  WriteJson(doc, o.out);
  return all ? kExitSuccess : kExitNoSolution;
}

std::function<int()> SetupJoin(CLI::App& sub) {
  auto o = std::make_shared<JoinCliOptions>();
  o->problem.Add(sub, ProblemOptions::Seed::kNone);  // deterministic: no --seed
  sub.add_option("--targets", o->targets, "targets \"X1,Y1;X2,Y2;...\" (default: the file's reach.targets)");
  sub.add_option("--max-iterations", o->max_iterations, "Levenberg-Marquardt iterations per join (default 30)");
  sub.add_option("--residual-tolerance", o->residual_tolerance, "accepted |x(t) - target| (default 1e-12)");
  sub.add_option("--out", o->out, "write the JSON to this file instead of standard output");
  sub.footer(
      "For each target x near x0 finds (delta_psi, t), t >= 0, such that the free motion from\n"
      "(theta, phi, psi + delta_psi) at x0 passes through x at time t (Lemma 2.1), with the impulse\n"
      "(delta omega, upper-plate velocity change 2 delta omega x e3) and the state on arrival.\n"
      "A target beyond the local radius is reported with status target_beyond_local_radius.\n"
      "Example: plateball join --lambda 2 --theta 1.0471975511965976 --phi 0.4 --psi 0.1 --targets \"0.05,0;0,0.05\"\n"
      "Exit codes: 0 ok, 2 usage, 3 invalid input, 4 a target not joined, 5 unreadable file.");
  return [o] { return RunJoin(*o); };
}

const CommandRegistrar kRegistrar{
    {"join", "join the start point to nearby targets with one energy-preserving impulse each (Lemma 2.1)", SetupJoin}};

}  // namespace
}  // namespace plateball::tools
