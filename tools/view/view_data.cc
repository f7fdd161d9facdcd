// Building what `plateball view` draws from a result (BuildView, one builder per command:
// simulate, plan and isoparallel, steer, montecarlo): the motion re-simulated arc by arc with the
// library, the planned path and the ghost ball rolling along it, the rig of a steer result, the
// Monte Carlo spread re-run from the result's seed, and the page's JSON of it all
// (ViewDataToJson). Reading and checking the result document is in result_reader.cc.
#include "view/view_data.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <variant>

#include "common/limits.h"
#include "common/number_format.h"
#include "common/plan_json.h"
#include "common/rig_plan_output.h"
#include "plateball/ball_model.h"
#include "plateball/ball_state.h"
#include "plateball/execution.h"
#include "plateball/fewest_impulses.h"
#include "plateball/free_motion.h"
#include "plateball/isoparallel.h"
#include "plateball/monte_carlo.h"
#include "plateball/partition.h"
#include "plateball/problem_io.h"
#include "plateball/rolling.h"
#include "plateball/so3.h"
#include "plateball/task_adapters.h"
#include "view/ghost.h"

namespace plateball::tools::view {

using nlohmann::json;

namespace {

constexpr std::size_t kMaxViewSamples = 200'000;  // page samples (a 10^6-sample simulate is thinned)
constexpr std::size_t kMaxSteps = 10'000;         // plan steps, steer impulses (the planner's limit)

Problem LoadProblem(const ResultReader& r, const ViewOptions& options);

// A library message names its own variable ("t: value 1e+298: ...", "start.state.omega[2]: value
// -1: ..."): reported with the result's field that holds it instead (`fields`: library name ->
// field); other messages pass unchanged.
template <class Make>
auto InResultFields(const ResultReader& r, const std::vector<std::pair<std::string, std::string>>& fields, Make make) {
  try {
    return make();
  } catch (const std::invalid_argument& e) {
    const std::string m = e.what();
    for (const auto& [name, field] : fields)
      if (m.rfind(name, 0) == 0 && m.size() > name.size() + 1 &&
          (m.compare(name.size(), 2, ": ") == 0 || m[name.size()] == '[' || m[name.size()] == '.'))
        throw std::invalid_argument(r.file() + ": " + field + m.substr(name.size()));
    throw;
  }
}

// The result's model; a result without one (isoparallel_solve before the output contract) takes
// the problem file's.
BallModel ModelFrom(const ResultReader& r, const ViewOptions& options) {
  if (!r.Find(r.doc(), "model") && (!options.problem_file.empty() || r.Find(r.doc(), "problem_file")))
    return LoadProblem(r, options).model;
  const json& m = r.Get(r.doc(), "", "model");
  if (r.Find(m, "alpha") && r.Find(m, "beta")) {
    const double alpha = r.Number(m, "model", "alpha"), beta = r.Number(m, "model", "beta");
    return InResultFields(
        r, {{"alpha", "model.alpha"}, {"beta", "model.beta"}}, [&] { return BallModel::FromAlphaBeta(alpha, beta); });
  }
  const double lambda = r.Number(m, "model", "lambda");
  return InResultFields(r, {{"lambda", "model.lambda"}}, [&] { return BallModel::FromLambda(lambda); });
}

IntegrationOptions IntegrationFrom(const ResultReader& r) {
  IntegrationOptions o;
  if (const json* i = r.Find(r.doc(), "integration")) {
    if (r.Find(*i, "absolute_tolerance")) o.absolute_tolerance = r.Number(*i, "integration", "absolute_tolerance");
    if (r.Find(*i, "relative_tolerance")) o.relative_tolerance = r.Number(*i, "integration", "relative_tolerance");
  }
  return InResultFields(r,
                        {{"absolute_tolerance", "integration.absolute_tolerance"},
                         {"relative_tolerance", "integration.relative_tolerance"}},
                        [&] {
                          if (const std::string bad = o.Validate(); !bad.empty()) throw std::invalid_argument(bad);
                          return o;
                        });
}

AngleState AnglesFrom(const ResultReader& r, const json& at, const std::string& where) {
  return {r.Number(at, where, "theta"), r.Number(at, where, "phi"), r.Number(at, where, "psi")};
}

double MaxEntry(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) { return (a - b).cwiseAbs().maxCoeff(); }

// One free arc from `start` over [0, duration]: `m` samples at duration * i / m, i < m, appended
// to `out`; returns the state at the end of the arc.
MotionSample AppendArc(const BallModel& model,
                       const FreeMotionStart& start,
                       double t0,
                       double duration,
                       int m,
                       const IntegrationOptions& integration,
                       ViewData* out) {
  const FreeMotion motion(model, start, integration);
  for (int i = 0; i < m; ++i) {
    const MotionSample s = motion.At(duration * i / m);
    out->t.push_back(t0 + s.t);
    out->x.push_back(s.x);
    out->A.push_back(s.A);
  }
  return motion.At(duration);
}

// The sum of the arcs' durations (from the result itself, so that the samples per arc, which are
// proportional to duration / total, add up to about `samples` whatever the file claims).
double TotalDuration(const ResultReader& r, const json& list, const std::string& list_field) {
  double total = 0.0;
  for (std::size_t k = 0; k < list.size(); ++k) {
    const std::string where = list_field + "[" + std::to_string(k) + "]";
    const double duration = r.Number(list[k], where, "duration");
    // 0 is an arc that ends where it begins: the stop at the goal (steer --stop-at-goal).
    if (!(duration >= 0)) r.Fail(where + ".duration", FormatNumber(duration), "must be >= 0");
    total += duration;
  }
  if (!(total > 0 && std::isfinite(total)))
    r.Fail(list_field + "[].duration", FormatNumber(total), "the durations must add up to a finite time > 0");
  return total;
}

int ArcSamples(double duration, double total, int samples) {
  if (duration == 0) return 0;  // no time passes: the arc adds no sample (times must increase)
  if (!(total > 0)) return 4;
  return std::clamp(static_cast<int>(std::ceil(samples * (duration / total))), 4, samples);
}

void AppendFinal(double t, const Eigen::Vector2d& x, const Eigen::Matrix3d& A, ViewData* out) {
  out->t.push_back(t);
  out->x.push_back(x);
  out->A.push_back(A);
}

// ---------------------------------------------------------------- simulate

// The result's samples as they are (their A(t) is the library's), with re-simulated samples
// inserted between them (FreeMotion from the result's initial state) so that there are at least
// options.samples of them.
void BuildSimulate(const ResultReader& r, const ViewOptions& options, ViewData* out) {
  const json& doc = r.doc();
  const json& samples = r.Array(doc, "", "samples", 2, kMaxSamples);
  const AngleState angles = AnglesFrom(r, r.Get(doc, "", "initial_angles"), "initial");
  const FreeMotion motion = FreeMotion::FromAngles(ModelFrom(r, options),
                                                   angles,
                                                   r.Number(doc, "", "initial_mu"),
                                                   r.Vector2(doc, "", "initial_x0"),
                                                   r.Rotation(doc, "", "initial_orientation"),
                                                   IntegrationFrom(r));
  const std::size_t n = samples.size();
  const std::size_t stride = (n + kMaxViewSamples - 1) / kMaxViewSamples;  // thin a huge result
  const int insert = n >= static_cast<std::size_t>(options.samples)
                         ? 0
                         : static_cast<int>((static_cast<std::size_t>(options.samples) + n - 2) / (n - 1)) - 1;
  double previous_t = 0.0;
  for (std::size_t i = 0; i < n; i += stride) {
    const std::string where = "samples[" + std::to_string(i) + "]";
    const double t = r.Number(samples[i], where, "sample_t");
    if (i > 0 && !(t > previous_t)) r.Fail(where + ".t", FormatNumber(t), "sample times must increase");
    for (int j = 1; i > 0 && j <= insert; ++j) {
      const MotionSample s = motion.At(previous_t + (t - previous_t) * j / (insert + 1));
      AppendFinal(s.t, s.x, s.A, out);
    }
    const Eigen::Matrix3d A = r.Rotation(samples[i], where, "sample_orientation");
    out->resimulation_mismatch = std::max(out->resimulation_mismatch, MaxEntry(motion.At(t).A, A));
    AppendFinal(t, r.Vector2(samples[i], where, "sample_x"), A, out);
    previous_t = t;
  }
  out->facts.push_back({"period T", FormatNumber(motion.Period())});
  out->facts.push_back({"drift per period", FormatNumber(motion.DriftPerPeriod().norm())});
}

// ---------------------------------------------------------------- plan, isoparallel

// The impulsive trajectory of a plan (the steps of `plateball plan` or of an isoparallel plan):
// each free arc re-integrated from its impulse, starting where the result says the previous arc
// ended (x_end, orientation_impulsive), so the page's A at every impulse is the result's.
struct PlanSteps {
  std::vector<double> t;                   // impulse times, then the end time
  std::vector<Eigen::Vector2d> p;          // p(tau_k), then the path's end point
  std::vector<Eigen::Matrix3d> A_planned;  // A(tau_k) rolling along the path, k = 0..n
};

PlanSteps BuildPlanTrajectory(const ResultReader& r,
                              const json& steps,
                              const std::string& steps_field,
                              const ViewOptions& options,
                              ViewData* out) {
  const BallModel model = ModelFrom(r, options);
  const IntegrationOptions integration = IntegrationFrom(r);
  const json& doc = r.doc();
  Eigen::Vector2d x = r.Vector2(doc, "", "initial_x0");
  const AngleState angles0 = AnglesFrom(r, r.Get(doc, "", "initial_angles"), "initial");
  Eigen::Matrix3d A =
      AlignOrientationToAxis(r.Rotation(doc, "", "initial_orientation"), StateFromAngles(angles0, 1.0, model).z);
  const double total = TotalDuration(r, steps, steps_field);
  PlanSteps plan;
  plan.A_planned.push_back(A);
  double t = 0.0;
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const json& s = steps[k];
    const std::string where = steps_field + "[" + std::to_string(k) + "]";
    // t_impulse is the sum of the earlier durations (impulse_planner.h): summed here, so times increase.
    const double duration = r.Number(s, where, "duration");
    FreeMotionStart start;
    start.state.z = StateFromAngles(AnglesFrom(r, r.Get(s, where, "angles_before"), where), 1.0, model).z;
    start.state.omega = r.Vector3(s, where, "omega_after_impulse");
    start.x0 = x;
    start.A0 = AlignOrientationToAxis(A, start.state.z);
    out->impulses.push_back({t, x, r.Vector3(s, where, "plate_velocity_change")});
    plan.t.push_back(t);
    plan.p.push_back(r.Vector2(s, where, "p_begin"));
    const std::string x_field = k == 0 ? "initial.x0" : steps_field + "[" + std::to_string(k - 1) + "].x_end";
    const MotionSample end = InResultFields(
        r,
        {{"t", where + ".duration"}, {"start.state.omega", where + ".omega_after_impulse"}, {"start.x0", x_field}},
        [&] {
          return AppendArc(model, start, t, duration, ArcSamples(duration, total, options.samples), integration, out);
        });
    x = r.Vector2(s, where, "x_end");
    A = r.Rotation(s, where, "orientation_impulsive");
    plan.A_planned.push_back(r.Rotation(s, where, "orientation_planned"));
    out->resimulation_mismatch = std::max(out->resimulation_mismatch, MaxEntry(end.A, A));
    t += duration;
  }
  AppendFinal(t, x, A, out);
  plan.t.push_back(t);
  plan.p.push_back(x);
  return plan;
}

// ---------------------------------------------------------------- the problem file

Problem LoadProblem(const ResultReader& r, const ViewOptions& options) {
  std::string file = options.problem_file;
  if (file.empty()) {
    const json* f = r.Find(r.doc(), "problem_file");
    if (!f || !f->is_string())
      r.Fail("problem.file",
             f ? ValueText(*f) : "(missing)",
             "the planned path is not in the result: give the problem file with --problem FILE");
    file = f->get<std::string>();
    const std::filesystem::path beside = std::filesystem::path(r.file()).parent_path() / file;
    if (!std::filesystem::exists(file) && std::filesystem::exists(beside)) file = beside.string();
  }
  return ReadProblemFile(file);
}

// `steer`'s setup as the tool makes it: along the plan section's path, else along the shortest
// isoparallel path (solved again: the result does not carry it).
ExactArrivalSetup SteerSetup(const Problem& p) {
  if (p.plan || !p.isoparallel) return ExactArrivalSetupFor(p);
  const IsoparallelSetup iso = IsoparallelSetupFor(p);
  const IsoparallelSummary solved = SolveIsoparallel(iso.problem, iso.options);
  if (!solved.IsSolutionUsable()) throw std::runtime_error("isoparallel reference: " + solved.BriefReport());
  return ExactArrivalSetupFor(p, solved.Shortest());
}

void AddPlanned(std::vector<Eigen::Vector2d> polyline, const PlanSteps& plan, ViewData* out) {
  const Polyline path(std::move(polyline));
  BuildGhost(path, plan.t, plan.p, plan.A_planned, out);
  out->planned = path.points;
}

// ---------------------------------------------------------------- steer

// Where a steer result starts and the path its ghost follows: the exact-arrival reference, or
// for the fewest-impulse search (which has none) the straight line from the start to the goal.
struct SteerStart {
  Eigen::Vector2d x0;
  Eigen::Matrix3d A0;
  double mu = 1.0;
  std::vector<Eigen::Vector2d> reference;
};

SteerStart SteerStartOf(const ResultReader& r, const Problem& problem) {
  if (r.Find(r.doc(), "fewest_impulses")) {
    const FewestImpulsesSetup setup = FewestImpulsesSetupFor(problem);
    const FewestImpulsesProblem& f = setup.problem;
    return {f.x0, f.A0, f.mu, {f.x0, f.orientation_only ? f.x0 : f.x1}};
  }
  const ExactArrivalSetup setup = SteerSetup(problem);
  return {setup.problem.x0, setup.problem.A0, setup.problem.mu, SamplePath(setup.problem.reference)};
}

// An array of strings of the result's rig object (limit names, violation lines).
std::vector<std::string> Strings(const ResultReader& r,
                                 const json& at,
                                 const std::string& where,
                                 const std::string& concept_name) {
  const json& list = r.Array(at, where, concept_name, 0, kMaxSteps);
  std::vector<std::string> out;
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (!list[i].is_string())
      r.Fail(where + "." + r.fields().Paths(concept_name).front().get<std::string>() + "[" + std::to_string(i) + "]",
             ValueText(list[i]),
             "must be a string");
    out.push_back(list[i].get<std::string>());
  }
  return out;
}

bool Boolean(const ResultReader& r, const json& at, const std::string& where, const std::string& concept_name) {
  const json& j = r.Get(at, where, concept_name);
  if (!j.is_boolean())
    r.Fail(
        where + "." + r.fields().Paths(concept_name).front().get<std::string>(), ValueText(j), "must be true or false");
  return j.get<bool>();
}

// The rig the page draws: the problem's limits around the stroke's origin x0 and, when the result
// carries it, the verdict of its independent replay check (exact_output.h RigJson).
ViewRig RigOf(const ResultReader& r, const RigLimits& limits, const Eigen::Vector2d& x0) {
  ViewRig rig;
  rig.limits = limits;
  rig.stroke_origin = x0;
  const json* result = r.Find(r.doc(), "rig");
  if (!result) return rig;
  if (!result->is_object()) r.Fail("rig", ValueText(*result), "must be an object (the rig's verdict)");
  const json& check = r.Get(*result, "rig", "rig_check");
  if (!check.is_object()) r.Fail("rig.check", ValueText(check), "must be an object (the replay check)");
  rig.checked = true;
  rig.passed = Boolean(r, check, "rig.check", "rig_passed");
  const double samples = r.Number(check, "rig.check", "rig_samples");
  if (!(samples >= 0 && std::floor(samples) == samples && samples <= 1e15))
    r.Fail("rig.check.samples", FormatNumber(samples), "must be an integer >= 0");
  rig.samples = static_cast<long long>(samples);
  const json& margins = r.Get(check, "rig.check", "rig_margins");
  if (!margins.is_object()) r.Fail("rig.check.margins", ValueText(margins), "must be an object of numbers");
  for (const auto& [name, value] : margins.items()) {
    if (!value.is_number() || !std::isfinite(value.get<double>()))
      r.Fail("rig.check.margins." + name, ValueText(value), "must be a finite number");
    rig.margins.emplace_back(name, value.get<double>());
  }
  rig.violations = Strings(r, check, "rig.check", "rig_violations");
  rig.active = Strings(r, *result, "rig", "rig_active");
  rig.blocking = Strings(r, *result, "rig", "rig_blocking");
  rig.constrained = Boolean(r, *result, "rig", "rig_constrained");
  const json& objective = r.Get(*result, "rig", "rig_objective");
  if (!objective.is_string()) r.Fail("rig.objective", ValueText(objective), "must be a string");
  rig.objective = objective.get<std::string>();
  return rig;
}

void BuildSteer(const ResultReader& r, const ViewOptions& options, ViewData* out) {
  const Problem problem = LoadProblem(r, options);
  const SteerStart begin = SteerStartOf(r, problem);  // reference; start state when the result lacks it
  const json& doc = r.doc();
  const BallModel model = ModelFrom(r, options);
  const IntegrationOptions integration = ExactArrivalOptions{}.integration;  // as the solver's rollouts
  const double mu = r.Find(doc, "initial_mu") ? r.Number(doc, "", "initial_mu") : begin.mu;
  const json& impulses = r.Array(doc, "", "impulses", 1, kMaxSteps);
  const double total = TotalDuration(r, impulses, "impulses");
  Eigen::Matrix3d A = r.Find(doc, "initial_orientation") ? r.Rotation(doc, "", "initial_orientation") : begin.A0;
  PlanSteps keys;
  double t = 0.0;
  Eigen::Vector2d x = begin.x0;
  for (std::size_t k = 0; k < impulses.size(); ++k) {
    const json& e = impulses[k];
    const std::string where = "impulses[" + std::to_string(k) + "]";
    AngleState a = AnglesFrom(r, r.Get(e, where, "angles_before"), where);
    a.psi += r.Number(e, where, "delta_psi");
    FreeMotionStart start;
    start.state = StateFromAngles(a, mu, model);
    start.x0 = r.Vector2(e, where, "impulse_x");
    start.A0 = AlignOrientationToAxis(A, start.state.z);
    // t_impulse is the sum of the earlier durations (exact_arrival.h): summed here, so times increase.
    const double duration = r.Number(e, where, "duration");
    out->impulses.push_back({t, start.x0, r.Vector3(e, where, "plate_velocity_change")});
    keys.t.push_back(t);
    // The planned pass point; the fewest search plans none (its ghost passes the impulse points).
    keys.p.push_back(r.Find(e, "impulse_p") ? r.Vector2(e, where, "impulse_p") : start.x0);
    const MotionSample end =
        AppendArc(model, start, t, duration, ArcSamples(duration, total, options.samples), integration, out);
    A = end.A;
    x = end.x;
    t += duration;
  }
  AppendFinal(t, x, A, out);
  out->resimulation_mismatch = MaxEntry(A,
                                        r.Find(doc, "arrival_orientation") ? r.Rotation(doc, "", "arrival_orientation")
                                                                           : r.Rotation(doc, "", "goal_orientation"));
  keys.t.push_back(t);
  keys.p.push_back(begin.reference.back());
  keys.A_planned.push_back(begin.A0);
  AddPlanned(begin.reference, keys, out);
  out->goal = r.Vector2(doc, "", "goal");
  out->has_goal = true;
  if (!problem.rig.Empty() || r.Find(doc, "rig")) out->rig = RigOf(r, problem.rig, begin.x0);
}

// ---------------------------------------------------------------- montecarlo

constexpr long long kMaxSpreadTrials = 6000;  // trials re-run for the spread, over all cells
// Impulses executed for the spread, over all cells (trials x cells x n): an edited result asking
// for n = 10^4 re-runs a few trials instead of 6000 x 10^4 impulses (minutes to an hour).
constexpr double kMaxSpreadImpulses = 2e5;

// A cell's error model from the result's options.scenarios[i].errors.
ErrorModel ErrorsFrom(const ResultReader& r, const json& errors, const std::string& where) {
  ErrorModel e;
  const std::pair<const char*, double ErrorModel::*> members[] = {
      {"error_impulse_magnitude", &ErrorModel::impulse_magnitude},
      {"error_impulse_angle", &ErrorModel::impulse_angle},
      {"error_timing", &ErrorModel::timing},
      {"error_energy_loss", &ErrorModel::energy_loss},
      {"error_lambda", &ErrorModel::lambda},
      {"error_observation", &ErrorModel::observation}};
  for (const auto& [concept_name, member] : members) e.*member = r.Number(errors, where, concept_name);
  // Results written before finite pulses have no pulse fields: ideal impulses.
  if (r.Find(errors, "error_pulse_duration") != nullptr) {
    e.pulse_duration = r.Number(errors, where, "error_pulse_duration");
    e.pulse_causal = r.Number(errors, where, "error_pulse_causal");
  }
  // The model's own range checks name its member ("impulse_magnitude: value ..."): name the field.
  if (const std::string invalid = e.Validate(); !invalid.empty())
    throw std::invalid_argument(r.file() + ": " + where + "." + invalid);
  return e;
}

// The result's median final position error of the cell (main n, scenario, strategy), or -1.
double ResultMedian(const ResultReader& r, int n, const std::string& scenario, const std::string& strategy) {
  const json* results = r.Find(r.doc(), "mc_results");
  for (std::size_t i = 0; results && results->is_array() && i < results->size(); ++i) {
    const json& c = (*results)[i];
    const json *cn = r.Find(c, "cell_n"), *cs = r.Find(c, "cell_scenario"), *ct = r.Find(c, "cell_strategy");
    if (!(cn && cs && ct && *cn == n && *cs == scenario && *ct == strategy)) continue;
    const auto completed = c.find("completed");  // a cell where no trial completed has no median (null)
    if (completed != c.end() && completed->is_number_integer() && *completed == 0) return -1.0;
    return r.Number(c, "results[" + std::to_string(i) + "]", "cell_position_median");
  }
  return -1.0;
}

// The nominal plan as `plateball plan` would write it, read back like a plan result.
PlanSteps NominalTrajectory(const ResultReader& r,
                            const NominalPlan& nominal,
                            const ViewOptions& options,
                            ViewData* out) {
  json plan_doc = PlanSummaryToJson(nominal.plan);
  plan_doc["model"] = r.Get(r.doc(), "", "model");
  if (const json* i = r.Find(r.doc(), "integration")) plan_doc["integration"] = *i;
  const json& initial = r.Get(r.doc(), "", "initial");
  if (!initial.is_object()) r.Fail("initial", ValueText(initial), "must be an object (the initial state)");
  plan_doc["initial"] = initial;
  plan_doc["initial"]["orientation"] = ToJson(nominal.plan.A0);
  const ResultReader plan_reader(r.file() + " (nominal plan)", plan_doc, r.fields());
  return BuildPlanTrajectory(plan_reader, plan_reader.Get(plan_doc, "", "steps"), "steps", options, out);
}

// A count of a montecarlo result (trials, impulses) as the tool accepts it: an integer in
// [lo, hi]; anything else is refused (an edited file would otherwise be re-run with other counts
// and the page would claim an agreement it never checked).
long long CountIn(const ResultReader& r, double v, const std::string& field, long long lo, long long hi) {
  if (!(std::floor(v) == v && v >= static_cast<double>(lo) && v <= static_cast<double>(hi)))
    r.Fail(field, FormatNumber(v), "must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return static_cast<long long>(v);
}

// The mode of a montecarlo result's rig record ("honour", "check"), or "" without one.
std::string RigMode(const ResultReader& r) {
  const json* rig = r.Find(r.doc(), "rig");
  if (!rig) return "";
  if (!rig->is_object()) r.Fail("rig", ValueText(*rig), "must be an object (the nominal plan's rig record)");
  const json* mode = rig->contains("mode") ? &(*rig)["mode"] : nullptr;
  if (!mode || !mode->is_string() || (*mode != "honour" && *mode != "check"))
    r.Fail("rig.mode", mode ? ValueText(*mode) : "(missing)", "must be \"honour\" or \"check\"");
  return mode->get<std::string>();
}

// The plan setup `plateball montecarlo` planned: the partition of options.impulses (n), or, when
// the plan honoured a rig (its partition refined), the partition asked for: the problem's own when
// its segments are the record's segments_initial, else segments_initial spread over the pieces.
PlanSetup MonteCarloPlanSetup(const ResultReader& r, const Problem& problem, int n) {
  if (RigMode(r) != "honour") return PlanSetupFor(problem, n, "options.impulses");
  const json& rig = *r.Find(r.doc(), "rig");
  const json* asked = rig.contains("segments_initial") ? &rig["segments_initial"] : nullptr;
  if (!asked || !asked->is_number())
    r.Fail("rig.segments_initial", asked ? ValueText(*asked) : "(missing)", "must be an integer");
  const long long initial = CountIn(r, asked->get<double>(), "rig.segments_initial", 1, limits::kMaxPartitionSteps);
  const PlanSetup own = PlanSetupFor(problem);
  long long own_segments = 0;
  for (const auto& taus : MakePartition(own.problem.path, own.problem.partition, "plan.partition"))
    own_segments += static_cast<long long>(taus.size()) - 1;
  if (own_segments == initial) return own;
  const long long pieces = own.problem.path.PieceCount();
  if (initial % pieces != 0)
    r.Fail("rig.segments_initial", std::to_string(initial), "is not a partition of the problem's path");
  return PlanSetupFor(problem, static_cast<int>(initial / pieces), "rig.segments_initial");
}

// The nominal plan's motion, and the final contact points of the trials re-run with the library
// (Execute of (nominal plan, strategy, errors, seed, trial): what `plateball montecarlo` ran).
void BuildMonteCarlo(const ResultReader& r, const ViewOptions& options, ViewData* out) {
  const Problem problem = LoadProblem(r, options);
  const json& doc = r.doc();
  const json& o = r.Get(doc, "", "mc_options");
  const double n_value = r.Number(o, "options", "mc_impulses");
  const int n = static_cast<int>(CountIn(r, n_value, "options.impulses", 1, limits::kMaxPartitionSteps));
  const PlanSetup setup = MonteCarloPlanSetup(r, problem, n);
  RigNominal planned = PlanOnRig(problem, setup, RigMode(r) != "honour");
  const auto nominal =
      std::make_shared<const NominalPlan>(MakeNominalPlan(setup.problem, setup.options, std::move(planned.plan)));
  if (!nominal->plan.IsSolutionUsable()) r.Fail("options.impulses", FormatNumber(n_value), nominal->plan.BriefReport());
  if (nominal->plan.segments != n)
    r.Fail("options.impulses",
           FormatNumber(n_value),
           "the nominal plan re-planned from the problem has " + std::to_string(nominal->plan.segments) + " segments");
  if (!planned.rig.is_null())
    out->facts.push_back({"rig",
                          std::string(planned.limits_met ? "limits met" : "limits NOT met") + " (" +
                              planned.rig["mode"].get<std::string>() + ")" + planned.note});
  if (!planned.limits_met && RigMode(r) == "honour") {  // `montecarlo` refused the plan: no trial to re-run
    out->goal = nominal->goal;
    out->has_goal = true;
    out->facts.push_back({"trials re-run", "none: the nominal plan cannot meet the rig's limits (no trial ran)"});
    return;
  }
  AddPlanned(SamplePath(setup.problem.path), NominalTrajectory(r, *nominal, options, out), out);
  ExecutionOptions eo;
  eo.miss_tolerance = r.Number(o, "options", "mc_miss_tolerance");
  eo.exact_window = static_cast<int>(std::clamp(r.Number(o, "options", "mc_exact_window"), 3.0, 64.0));
  // The options' own range checks name their member ("miss_tolerance: value 0: ..."): name the field.
  if (const std::string invalid = eo.Validate(); !invalid.empty())
    throw std::invalid_argument(r.file() + ": options." + invalid);
  const json& seed = r.Get(doc, "", "seed");
  if (!seed.is_number_unsigned()) r.Fail("seed", ValueText(seed), "must be an integer in [0, 2^64 - 1]");
  const json& scenarios = r.Array(o, "options", "mc_scenarios", 1, 64);
  const json& strategies = r.Array(o, "options", "mc_strategies", 1, 3);
  const long long cells = static_cast<long long>(scenarios.size() * strategies.size());
  const long long file_trials =
      CountIn(r, r.Number(o, "options", "mc_trials"), "options.trials", 1, MonteCarloOptions::kMaxTrials);
  const long long budget_trials = std::max(1LL, static_cast<long long>(kMaxSpreadImpulses / (double(cells) * n)));
  const long long trials = std::min({std::max(1LL, kMaxSpreadTrials / cells), file_trials, budget_trials});
  double mismatch = 0.0;
  int compared = 0;  // cells whose file median and re-run median were both available
  for (std::size_t i = 0; i < scenarios.size(); ++i) {
    const std::string where = "options.scenarios[" + std::to_string(i) + "]";
    const json& name_json = r.Get(scenarios[i], where, "scenario_name");
    const std::string name = name_json.is_string() ? name_json.get<std::string>() : name_json.dump();
    for (std::size_t j = 0; j < strategies.size(); ++j) {
      ExecutionProblem ep;
      ep.nominal = nominal;
      ep.strategy = ParseExecutionStrategy(strategies[j].is_string() ? strategies[j].get<std::string>() : "",
                                           "options.strategies[" + std::to_string(j) + "]");
      ep.errors = ErrorsFrom(r, r.Get(scenarios[i], where, "scenario_errors"), where + ".errors");
      ep.seed = seed.get<std::uint64_t>();
      std::vector<Eigen::Vector2d> points;
      std::vector<double> errors;
      for (ep.trial = 0; static_cast<long long>(ep.trial) < trials; ++ep.trial) {
        const ExecutionSummary s = Execute(ep, eo);
        if (!s.IsSolutionUsable()) continue;
        points.push_back(s.x_final);
        errors.push_back(s.position_error);
      }
      const double median = ResultMedian(r, n, name, ToString(ep.strategy));
      if (median >= 0 && !errors.empty()) {
        mismatch = std::max(mismatch, std::abs(Distribute(errors).median - median));
        ++compared;
      }
      out->spread.push_back({ToString(ep.strategy) + ", " + name, std::move(points)});
    }
  }
  out->goal = nominal->goal;
  out->has_goal = true;
  out->facts.push_back(
      {"trials re-run",
       std::to_string(trials) + " per cell (Execute, seed " + seed.dump() + ")" +
           (trials == budget_trials && trials < file_trials ? ", the view's work budget of 2e5 impulses over all cells"
                                                            : "")});
  out->facts.push_back({"re-run vs file",
                        compared > 0 ? "median final position errors agree to " + FormatNumber(mismatch)
                                     : std::string("not compared: no cell has a median in both")});
}

std::string TitleOf(const ResultReader& r, const std::string& kind) {
  const json* name = r.Find(r.doc(), "problem_name");
  return (name && name->is_string() ? name->get<std::string>() + ": " : std::string()) + "plateball " + kind;
}

}  // namespace

ViewData BuildView(const ResultReader& r, const ViewOptions& options) {
  const json& doc = r.doc();
  if (!doc.is_object()) r.Fail("(document)", ValueText(doc), "a result is a JSON object");
  const json* command = r.Find(doc, "command");
  ViewData out;
  if (!command || !command->is_string())
    r.Fail("command", command ? ValueText(*command) : "(missing)", "not a result of plateball or isoparallel_solve");
  out.kind = command->get<std::string>();
  out.title = TitleOf(r, out.kind);
  if (out.kind == "simulate") {
    BuildSimulate(r, options, &out);
  } else if (out.kind == "plan") {
    const json& steps = r.Array(doc, "", "steps", 1, kMaxSteps);
    const PlanSteps plan = BuildPlanTrajectory(r, steps, "steps", options, &out);
    AddPlanned(SamplePath(PlanSetupFor(LoadProblem(r, options)).problem.path), plan, &out);
  } else if (out.kind == "isoparallel") {
    const json& steps = r.Array(doc, "", "steps", 1, kMaxSteps);
    const PlanSteps plan = BuildPlanTrajectory(r, steps, "plan.steps", options, &out);
    std::vector<Eigen::Vector2d> path;
    const json& pts = r.Array(doc, "", "optimal_path", 2, kMaxPoints);
    for (std::size_t i = 0; i < pts.size(); ++i) {
      Eigen::Vector2d p;
      if (!pts[i].is_array() || pts[i].size() != 2 || !pts[i][0].is_number() || !pts[i][1].is_number())
        r.Fail("optimal_path[" + std::to_string(i) + "]", ValueText(pts[i]), "must be [x, y]");
      path.push_back({pts[i][0].get<double>(), pts[i][1].get<double>()});
    }
    // The optimal path's samples through a C^2 spline, sampled densely for the ghost's rolling.
    AddPlanned(
        SamplePath(InResultFields(r, {{"points", "optimal_path"}}, [&] { return Path({SmoothCurve::Samples(path)}); })),
        plan,
        &out);
    out.goal = r.Vector2(doc, "", "goal");
    out.has_goal = true;
  } else if (out.kind == "steer") {
    BuildSteer(r, options, &out);
  } else if (out.kind == "montecarlo") {
    BuildMonteCarlo(r, options, &out);
  } else {
    r.Fail("command", ValueText(*command), "the view shows simulate, plan, isoparallel, steer and montecarlo results");
  }
  if (const json* report = r.Find(doc, "report"); report && report->is_string())
    out.facts.insert(out.facts.begin(), {"report", report->get<std::string>()});
  return out;
}

namespace {
json Flat(const std::vector<Eigen::Vector2d>& v) {
  json a = json::array();
  for (const auto& p : v) {
    a.push_back(p.x());
    a.push_back(p.y());
  }
  return a;
}
// Unit quaternions (w, x, y, z), consecutive ones in the same hemisphere (shortest slerp).
json Quaternions(const std::vector<Eigen::Matrix3d>& rotations) {
  json a = json::array();
  Eigen::Quaterniond previous(1, 0, 0, 0);
  for (const Eigen::Matrix3d& m : rotations) {
    Eigen::Quaterniond q(m);
    q.normalize();
    if (q.coeffs().dot(previous.coeffs()) < 0) q.coeffs() = -q.coeffs();
    for (const double c : {q.w(), q.x(), q.y(), q.z()}) a.push_back(c);
    previous = q;
  }
  return a;
}
json ShapeToJson(const PlateShape& shape) {
  if (const auto* disk = std::get_if<DiskShape>(&shape))
    return json{{"type", "disk"}, {"center", {disk->center.x(), disk->center.y()}}, {"radius", disk->radius}};
  json vertices = json::array();
  for (const Eigen::Vector2d& v : std::get<PolygonShape>(shape).vertices) vertices.push_back({v.x(), v.y()});
  return json{{"type", "polygon"}, {"vertices", vertices}};
}
// The page's rig object (web/rig_layers.js): the shapes in ball radii, and the verdict with the
// margins as [name, value] pairs (names from the data never become object keys of the page).
json RigToJson(const ViewRig& rig) {
  const RigLimits& l = rig.limits;
  json j{{"clearance", l.clearance}, {"x0", {rig.stroke_origin.x(), rig.stroke_origin.y()}}};
  if (l.plate) j["plate"] = ShapeToJson(*l.plate);
  json obstacles = json::array();
  for (const PlateShape& o : l.obstacles) obstacles.push_back(ShapeToJson(o));
  j["obstacles"] = obstacles;
  if (l.stroke) j["stroke"] = {l.stroke->x(), l.stroke->y()};
  if (rig.checked) {
    json margins = json::array();
    for (const auto& [name, value] : rig.margins) margins.push_back(json::array({name, value}));
    j["check"] = json{{"passed", rig.passed},
                      {"samples", rig.samples},
                      {"margins", margins},
                      {"violations", rig.violations},
                      {"active", rig.active},
                      {"blocking", rig.blocking},
                      {"constrained", rig.constrained},
                      {"objective", rig.objective}};
  }
  return j;
}
}  // namespace

json ViewDataToJson(const ViewData& d) {
  json j{{"kind", d.kind},
         {"title", d.title},
         {"t", d.t},
         {"x", Flat(d.x)},
         {"q", Quaternions(d.A)},
         {"planned", Flat(d.planned)},
         {"resimulation_mismatch", d.resimulation_mismatch}};
  json facts = json::array();
  for (const auto& [label, value] : d.facts) facts.push_back(json::array({label, value}));
  j["facts"] = facts;
  if (!d.ghost_x.empty()) {
    json err = json::array();
    for (std::size_t i = 0; i < d.A.size(); ++i) err.push_back(RotationAngle(d.A[i], d.ghost_A[i]));
    j["ghost"] = json{{"x", Flat(d.ghost_x)}, {"q", Quaternions(d.ghost_A)}, {"error", err}};
  }
  json spread = json::array();
  for (const auto& [label, points] : d.spread) spread.push_back(json{{"label", label}, {"x", Flat(points)}});
  j["spread"] = spread;
  json impulses = json::array();
  for (const ViewImpulse& i : d.impulses)
    impulses.push_back(
        json{{"t", i.t},
             {"x", {i.x.x(), i.x.y()}},
             {"dv", {i.plate_velocity_change.x(), i.plate_velocity_change.y(), i.plate_velocity_change.z()}}});
  j["impulses"] = impulses;
  if (d.has_goal) j["goal"] = {d.goal.x(), d.goal.y()};
  if (d.rig) j["rig"] = RigToJson(*d.rig);
  return j;
}

}  // namespace plateball::tools::view
