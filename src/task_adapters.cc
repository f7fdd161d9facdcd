#include "plateball/task_adapters.h"

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <variant>

#include "check.h"
#include "partition_internal.h"

namespace plateball {
namespace {

// Every library message starts with its field (check.h, "FIELD: value V: ..."), so the caller's
// field is a path prefix: "radius: value 0: ..." -> "plan.path.radius: value 0: ...".
std::string Prefixed(const std::string& field, const std::string& message) { return field + "." + message; }

template <class Make>
auto Named(const std::string& field, Make make) {
  try {
    return make();
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(Prefixed(field, e.what()));
  }
}

[[noreturn]] void ThrowMissing(const Problem& problem, const std::string& section, const std::string& what) {
  internal::ThrowInvalid(problem.source + ": " + section, "(missing)", what);
}

const PlanTask& RequirePlan(const Problem& problem) {
  if (!problem.plan) ThrowMissing(problem, "plan", "the problem has no plan task");
  return *problem.plan;
}

const IsoparallelTask& RequireIsoparallel(const Problem& problem) {
  if (!problem.isoparallel) ThrowMissing(problem, "isoparallel", "the problem has no isoparallel section");
  return *problem.isoparallel;
}

void RequireStartOnPath(const Problem& problem, const Path& path) {
  const double size = std::max(1.0, path.Length());
  if ((problem.x0 - path.StartPoint()).norm() <= 1e-9 * size) return;
  auto pair = [](const Eigen::Vector2d& v) {
    return "(" + internal::FormatNumber(v.x()) + ", " + internal::FormatNumber(v.y()) + ")";
  };
  internal::ThrowInvalid(problem.source + ": initial.x0",
                         pair(problem.x0),
                         "must equal the path start p(tau_0) = " + pair(path.StartPoint()));
}

PlanOptions PlanOptionsFor(const Problem& problem) {
  PlanOptions o;
  o.integration = problem.integration;
  o.join.integration = problem.integration;
  return o;
}

}  // namespace

SmoothCurve CurveFromSpec(const PathSpec& spec, const std::string& field) {
  struct Make {
    SmoothCurve operator()(const LineSpec& l) const { return SmoothCurve::Line(l.from, l.to); }
    SmoothCurve operator()(const CircleSpec& c) const {
      return SmoothCurve::Circle(c.center, c.radius, c.tau_begin, c.tau_end);
    }
    SmoothCurve operator()(const EllipseSpec& e) const {
      return SmoothCurve::Ellipse(e.center, e.semi_axes, e.rotation, e.tau_begin, e.tau_end);
    }
    SmoothCurve operator()(const LemniscateSpec& m) const {
      return SmoothCurve::Lemniscate(m.center, m.scale, m.rotation, m.tau_begin, m.tau_end);
    }
    SmoothCurve operator()(const SineSpec& w) const {
      return SmoothCurve::Sine(w.from, w.rotation, w.length, w.amplitude, w.wavelength);
    }
    SmoothCurve operator()(const SamplesSpec& m) const { return SmoothCurve::Samples(m.points); }
    SmoothCurve operator()(const PiecewiseSpec&) const { throw std::logic_error("not a smooth curve"); }
  };
  if (std::holds_alternative<PiecewiseSpec>(spec.shape))
    internal::ThrowInvalid(field + ".type", "\"piecewise\"", "not a single smooth curve here (pieces may not nest)");
  return Named(field, [&] { return std::visit(Make{}, spec.shape); });
}

Path PathFromSpec(const PathSpec& spec, const std::string& field) {
  const auto* pw = std::get_if<PiecewiseSpec>(&spec.shape);
  if (pw == nullptr) return Path({CurveFromSpec(spec, field)});
  if (pw->pieces.empty())
    internal::ThrowInvalid(field + ".pieces (count)", 0, "a piecewise path needs at least one piece");
  std::vector<SmoothCurve> pieces;
  for (std::size_t i = 0; i < pw->pieces.size(); ++i)
    pieces.push_back(CurveFromSpec(pw->pieces[i], field + ".pieces[" + std::to_string(i) + "]"));
  return Named(field, [&] { return Path(std::move(pieces)); });
}

std::vector<PartitionRule> PartitionFromSpec(const PartitionSpec& spec, const Path& path, const std::string& field) {
  if (std::holds_alternative<ExplicitTaus>(spec) && path.PieceCount() != 1)
    internal::ThrowInvalid(field + ".taus (pieces)",
                           path.PieceCount(),
                           "explicit partitions are for single-piece paths; use a uniform type for piecewise paths");
  return {spec};
}

FreeMotion FreeMotionFor(const Problem& problem) {
  return FreeMotion::FromAngles(
      problem.model, problem.initial, problem.mu, problem.x0, problem.A0, problem.integration);
}

JoinSetup JoinSetupFor(const Problem& problem, const Eigen::Vector2d& target) {
  JoinSetup s;
  s.problem = JoinProblem{problem.model, problem.initial, problem.mu, problem.x0, target};
  s.options.integration = problem.integration;
  return s;
}

ReachSetup ReachSetupFor(const Problem& problem, const Eigen::Vector2d& target) {
  ReachSetup s;
  s.problem.model = problem.model;
  s.problem.start = problem.initial;
  s.problem.mu = problem.mu;
  s.problem.x0 = problem.x0;
  s.problem.A0 = problem.A0;
  s.problem.target = target;
  if (problem.reach) s.options.horizon_periods = problem.reach->horizon_periods;
  s.options.integration = problem.integration;
  return s;
}

PlanSetup PlanSetupFor(const Problem& problem, int n, const std::string& n_field) {
  const PlanTask& task = RequirePlan(problem);
  PlanSetup s;
  s.problem.model = problem.model;
  s.problem.initial = problem.initial;
  s.problem.mu = problem.mu;
  s.problem.A0 = problem.A0;
  s.problem.path = PathFromSpec(task.path, problem.source + ": plan.path");
  PartitionSpec spec = task.partition;
  if (n > 0) {
    if (auto* u = std::get_if<UniformParameter>(&spec))
      u->n = n;
    else if (auto* a = std::get_if<UniformArcLength>(&spec))
      a->n = n;
    else
      internal::ThrowInvalid(n_field, n, "not allowed with an explicit partition (plan.partition.type explicit)");
  }
  const std::string field = problem.source + ": plan.partition";
  s.problem.partition = PartitionFromSpec(spec, s.problem.path, field);
  // Checked here, where the fields are known: n too small for a closed path names the n given.
  internal::MakePartition(s.problem.path, s.problem.partition, field, n > 0 ? n_field : std::string());
  s.problem.energy_changes = task.energy_changes;
  RequireStartOnPath(problem, s.problem.path);
  s.options = PlanOptionsFor(problem);
  return s;
}

ConvergenceSetup ConvergenceSetupFor(const Problem& problem,
                                     const std::vector<int>& ns,
                                     const std::string& ns_field,
                                     bool timings) {
  const PlanTask& task = RequirePlan(problem);
  ConvergenceSetup s;
  const std::string list_field = ns.empty() ? problem.source + ": plan.converge_n" : ns_field;
  if (!ns.empty()) {
    ValidatePartitionSizes(ns, ns_field);
    s.problem.ns = ns;
  } else if (!task.converge_n.empty()) {
    ValidatePartitionSizes(task.converge_n, list_field);
    s.problem.ns = task.converge_n;
  }
  if (const auto* e = std::get_if<ExplicitTaus>(&task.partition))
    internal::ThrowInvalid(ns.empty() ? problem.source + ": plan.partition.taus (count)" : ns_field,
                           ns.empty() ? static_cast<double>(e->taus.size()) : ns.front(),
                           "a convergence study varies n: it needs a uniform partition, not an explicit one");
  PlanSetup plan = PlanSetupFor(problem);
  // Each n of the study, named by its entry (the default list has no entries to name).
  for (std::size_t i = 0; i < s.problem.ns.size() && (!ns.empty() || !task.converge_n.empty()); ++i) {
    PartitionRule rule = task.partition;
    if (auto* u = std::get_if<UniformParameter>(&rule)) u->n = s.problem.ns[i];
    if (auto* a = std::get_if<UniformArcLength>(&rule)) a->n = s.problem.ns[i];
    internal::MakePartition(
        plan.problem.path, {rule}, problem.source + ": plan.partition", list_field + "[" + std::to_string(i) + "]");
  }
  s.problem.plan = std::move(plan.problem);
  s.options.plan = std::move(plan.options);
  s.options.timings = timings;
  return s;
}

IsoparallelSetup IsoparallelSetupFor(const Problem& problem) {
  const IsoparallelTask& task = RequireIsoparallel(problem);
  IsoparallelSetup s;
  s.problem.start = task.start;
  s.problem.goal = task.goal;
  s.problem.start_orientation = task.start_orientation;
  s.problem.goal_orientation = task.goal_orientation;
  s.options = task.solver;
  s.options.seed = problem.seed;
  s.options.integration = problem.integration;
  return s;
}

IsoparallelPlanSetup IsoparallelPlanSetupFor(const Problem& problem,
                                             const IsoparallelSolution& solution,
                                             int impulses) {
  const IsoparallelTask& task = RequireIsoparallel(problem);
  IsoparallelPlanSetup s;
  s.problem.model = problem.model;
  s.problem.psi = problem.initial.psi;
  s.problem.mu = problem.mu;
  s.problem.A0 = task.start_orientation;
  s.problem.solution = solution;
  s.problem.impulses = impulses > 0 ? impulses : task.impulses;
  s.options = PlanOptionsFor(problem);
  return s;
}

namespace {

const SteerTask& RequireSteer(const Problem& problem) {
  if (!problem.steer) ThrowMissing(problem, "steer", "the problem has no steer section");
  return *problem.steer;
}

ExactArrivalOptions ExactOptionsFor(const Problem& problem) {
  ExactArrivalOptions o;
  o.warm_start = PlanOptionsFor(problem);
  return o;
}

void SetImpulses(int impulses, const std::string& n_field, ExactArrivalProblem* p) {
  if (impulses == 0) return;
  if (impulses < 3 || impulses > kMaxExactImpulses)
    internal::ThrowInvalid(
        n_field,
        impulses,
        "must be in [3, " + std::to_string(kMaxExactImpulses) + "] (2n unknowns for the 5 arrival conditions)");
  p->impulses = impulses;
}

// The file's rig section, the steer section's objective and the masses behind the impulse bounds.
void SetRig(const Problem& problem, ExactArrivalProblem* p) {
  p->limits = problem.rig;
  if (problem.steer) p->objective = problem.steer->objective;
  p->physical = problem.physical;
}

}  // namespace

ExactArrivalSetup ExactArrivalSetupFor(const Problem& problem, int impulses, const std::string& n_field) {
  const SteerTask& steer = RequireSteer(problem);
  const PlanTask& task = RequirePlan(problem);
  ExactArrivalSetup s;
  s.problem.model = problem.model;
  s.problem.initial = problem.initial;
  s.problem.mu = problem.mu;
  s.problem.A0 = problem.A0;
  s.problem.x0 = problem.x0;
  s.problem.reference = PathFromSpec(task.path, problem.source + ": plan.path");
  RequireStartOnPath(problem, s.problem.reference);
  s.problem.x1 = steer.goal;
  s.problem.A1 = steer.goal_orientation;
  s.problem.impulses = steer.impulses;
  s.problem.start_at_rest = steer.start_at_rest;
  s.problem.stop_at_goal = steer.stop_at_goal;
  SetImpulses(impulses, n_field, &s.problem);
  SetRig(problem, &s.problem);
  s.options = ExactOptionsFor(problem);
  return s;
}

ExactArrivalSetup ExactArrivalSetupFor(const Problem& problem,
                                       const IsoparallelSolution& solution,
                                       int impulses,
                                       const std::string& n_field) {
  const IsoparallelTask& task = RequireIsoparallel(problem);
  const IsoparallelPlanSetup plan = IsoparallelPlanSetupFor(problem, solution);
  ExactArrivalSetup s;
  s.problem.model = plan.problem.model;
  s.problem.initial = InitialAnglesFromOrientation(plan.problem.A0, plan.problem.psi);
  s.problem.mu = plan.problem.mu;
  s.problem.A0 = plan.problem.A0;
  s.problem.x0 = solution.start;
  s.problem.reference = OptimalPath(solution);
  s.problem.x1 = problem.steer ? problem.steer->goal : task.goal;
  s.problem.A1 = problem.steer ? problem.steer->goal_orientation : task.goal_orientation;
  s.problem.impulses = problem.steer ? problem.steer->impulses : std::max(3, task.impulses);
  s.problem.start_at_rest = problem.steer && problem.steer->start_at_rest;
  s.problem.stop_at_goal = problem.steer && problem.steer->stop_at_goal;
  SetImpulses(impulses, n_field, &s.problem);
  SetRig(problem, &s.problem);
  s.options = ExactOptionsFor(problem);
  return s;
}

FewestImpulsesSetup FewestImpulsesSetupFor(const Problem& problem) {
  const SteerTask& steer = RequireSteer(problem);
  FewestImpulsesSetup s;
  s.problem.model = problem.model;
  s.problem.mu = problem.mu;
  if (problem.isoparallel && !problem.plan) {
    s.problem.A0 = problem.isoparallel->start_orientation;
    s.problem.initial = InitialAnglesFromOrientation(s.problem.A0, problem.initial.psi);
    s.problem.x0 = problem.isoparallel->start;
  } else {
    s.problem.A0 = problem.A0;
    s.problem.initial = problem.initial;
    s.problem.x0 = problem.x0;
  }
  s.problem.x1 = steer.goal;
  s.problem.A1 = steer.goal_orientation;
  s.problem.start_at_rest = steer.start_at_rest;
  s.problem.stop_at_goal = steer.stop_at_goal;
  const SteerTask::Fewest f = steer.fewest.value_or(SteerTask::Fewest{});
  s.problem.orientation_only = f.orientation_only;
  s.options.max_impulses = f.max_impulses;
  s.options.starts = f.starts;
  s.options.pareto_counts = f.pareto_counts;
  s.options.max_total_time = f.max_total_time;
  s.problem.limits = problem.rig;
  s.problem.physical = problem.physical;
  return s;
}

}  // namespace plateball
