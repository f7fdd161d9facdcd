// The rig-limits side of the fewest-impulse search (fewest_search.h) and the description of a
// count's row. With limits, an exact arrival found by the free search is admitted as it is when it
// meets them, else handed to the constrained exact arrival (constrained_arrival.h, total time
// minimised) as its start; either counts only when the independent replay (CheckRigLimits)
// passes, and while none does the closest feasible arrival and the limits blocking it are kept.
// The row of a count reports its impulses (placed on the rig's tick grid), totals, errors and,
// with limits, its active limits and replay check.
#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "constrained_arrival.h"
#include "exact_chain.h"
#include "fewest_search.h"
#include "plateball/ball_state.h"
#include "plateball/exact_arrival.h"
#include "plateball/plate_impulse.h"

namespace plateball::internal::fewest {

// SLSQP evaluations of one constrained run in the search. A run that arrives within the limits
// takes far fewer (at most about 50 on docs/benchmarks.md's T12); one still going beyond this is
// wandering outside the limits, and the search tries the count's further arrivals instead.
constexpr int kSearchEvaluations = 64;

// The constrained exact arrival of count n (constrained_arrival.h) at the problem's mu: the
// limits in the problem's time unit, the total time minimised, the pass points of the deviation
// the straight line x0 -> x1 cut into n equal parts.
internal::ConstrainedSetup ConstrainedFor(const Search& s, int n) {
  const FewestImpulsesProblem& p = *s.problem;
  internal::ConstrainedSetup cs;
  cs.lambda = p.model.lambda();
  cs.n = n;
  cs.start = s.start;
  cs.x1 = p.x1;
  cs.A1 = p.A1;
  for (int k = 0; k <= n; ++k) cs.planned.push_back(p.x0 + (p.x1 - p.x0) * (static_cast<double>(k) / n));
  cs.limits = p.limits;
  cs.physical = p.physical;
  cs.objective = ArrivalObjective::kTotalTime;
  cs.start_at_rest = p.start_at_rest;
  cs.stop_at_goal = p.stop_at_goal;
  cs.integration = s.options->integration;
  cs.jacobian_integration = s.options->search_integration;
  cs.position_tolerance = s.options->position_tolerance;
  cs.orientation_tolerance = s.options->orientation_tolerance;
  cs.max_evaluations = kSearchEvaluations;
  return cs;
}

// The impulses of u (rolled into `nodes`), the stop with stop_at_goal, on the grid with `ticks`;
// returns the total time.
double Impulses(const Search& s,
                const Eigen::VectorXd& u,
                const std::vector<ChainNode>& nodes,
                const std::vector<long long>& ticks,
                std::vector<ExactImpulse>* plan,
                std::optional<ExactImpulse>* stop) {
  const FewestImpulsesProblem& p = *s.problem;
  const int n = static_cast<int>(u.size() / 2);
  *plan = internal::ReportImpulses(p.model, p.mu, nodes, u, p.start_at_rest);
  stop->reset();
  if (p.stop_at_goal) *stop = internal::StopImpulse(p.model, p.mu, nodes.back(), u.tail(n).sum());
  for (std::size_t k = 0; k < ticks.size(); ++k) (k < plan->size() ? (*plan)[k] : **stop).tick = ticks[k];
  return internal::PlaceOnGrid(p.limits.tick, plan, stop, u.tail(n).sum());
}

// The independent check of an arrival against the limits (CheckRigLimits: a FreeMotion replay).
RigCheck CheckArrival(const Search& s,
                      const Eigen::VectorXd& u,
                      const std::vector<ChainNode>& nodes,
                      const std::vector<long long>& ticks) {
  ExactArrivalSummary summary;
  Impulses(s, u, nodes, ticks, &summary.impulses, &summary.stop);
  return CheckRigLimits(ReplayProblemFor(*s.problem, static_cast<int>(u.size() / 2)), summary);
}

// Sum of |J| with the physical parameters, else of the plate velocity changes, over the impulses.
double TotalImpulse(const FewestImpulsesProblem& p,
                    const std::vector<ExactImpulse>& plan,
                    const std::optional<ExactImpulse>& stop) {
  double sum = 0.0;
  const auto add = [&](const ExactImpulse& e) {
    if (!p.physical) {
      sum += e.plate_velocity_change.norm();
      return;
    }
    const Eigen::Vector3d z = StateFromAngles(e.angles_before, p.mu, p.model).z;
    sum += PlateImpulseFor(*p.physical, z, e.delta_omega).plate.norm();
  };
  for (const ExactImpulse& e : plan) add(e);
  if (stop) add(*stop);
  return sum;
}

// The row of count n from its best parameters.
void Describe(const Search& s, const CountBest& best, FewestImpulsesCount* row) {
  const FewestImpulsesProblem& p = *s.problem;
  const Eigen::VectorXd& u = best.u;
  const std::vector<ChainNode>& nodes = best.nodes;
  const int n = static_cast<int>(u.size() / 2);
  row->total_time = Impulses(s, u, nodes, best.ticks, &row->plan, &row->stop);
  if (!row->reached) row->stop.reset();
  row->path_length = internal::ChainPathLength(p.model.lambda(), nodes, u, s.options->integration);
  const Eigen::Matrix<double, 5, 1> r = internal::ArrivalResidual(nodes.back(), p.x1, p.A1);
  row->position_error = s.conditions == 5 ? r.head<2>().norm() : 0.0;
  row->orientation_error = r.tail<3>().norm();
  row->x_final = nodes.back().x;
  row->A_final = nodes.back().A;
  row->total_impulse = TotalImpulse(p, row->plan, row->stop);
  double deviation = 0.0;
  for (int k = 1; k < n; ++k)
    deviation +=
        (row->plan[static_cast<std::size_t>(k)].position - (p.x0 + (p.x1 - p.x0) * (static_cast<double>(k) / n)))
            .squaredNorm();
  row->deviation = std::sqrt(deviation);
  if (!s.limited) return;
  row->blocking = row->reached ? std::vector<std::string>{} : best.blocking;
  if (!row->reached) return;
  row->active = internal::ActiveLimits(ConstrainedFor(s, n), u);
  if (p.limits.tick > 0) row->active.push_back("tick");
  row->check = CheckArrival(s, u, nodes, best.ticks);
}

// Keeps u (rolled into `nodes`) as the count's closest feasible arrival while none is within the
// limits, when it is closer than the one kept.
void KeepClosestFeasible(const Search& s,
                         const Eigen::VectorXd& u,
                         const std::vector<long long>& ticks,
                         const std::vector<std::string>& blocking,
                         CountBest* best) {
  if (std::isfinite(best->time)) return;
  std::vector<ChainNode> nodes;
  const Eigen::VectorXd r = Evaluate(s, u, s.options->integration, &nodes, nullptr);
  if (best->feasible_closest && !(r.norm() < best->closest)) return;
  best->feasible_closest = true;
  best->closest = r.norm();
  best->u = u;
  best->nodes = nodes;
  best->ticks = ticks;
  best->blocking = blocking;
}

// Constrained solves per count that may fail before its further arrivals are no longer tried
// under the limits (each failure costs a full SLSQP run and its closest feasible arrival).
constexpr int kMaxFailedSolves = 2;

// An exact arrival u under the limits: kept unchanged when it meets them (without a tick), else
// the constrained solver's arrival from it; either counts only when the independent check passes.
void Admit(const Search& s,
           const Eigen::VectorXd& u,
           const std::vector<ChainNode>& nodes,
           FewestImpulsesCount* row,
           CountBest* best) {
  internal::ConstrainedSetup cs = ConstrainedFor(s, row->impulses);
  cs.closest_arrival = s.closest_wanted && !std::isfinite(best->time);  // else KeepClosestFeasible keeps nothing
  Eigen::VectorXd v = u;
  std::vector<ChainNode> v_nodes = nodes;
  std::vector<long long> ticks;
  if (!(cs.limits.tick == 0 && internal::MeetsLimits(cs, u))) {
    if (best->failed >= kMaxFailedSolves) return;
    internal::ConstrainedOutcome c;
    ++s.summary->constrained_solves;
    try {
      c = internal::SolveConstrainedArrival(cs, u);
    } catch (const std::invalid_argument&) {  // fewer free unknowns (with the grid) than conditions
      std::vector<std::string> broken = internal::ActiveLimits(cs, u);
      if (cs.limits.tick > 0) broken.push_back("tick");
      KeepClosestFeasible(s, u, {}, broken, best);
      return;
    }
    s.summary->evaluations += c.evaluations;
    *s.rollouts += c.rollouts;
    if (!c.arrived) {
      ++best->failed;
      if (c.feasible) KeepClosestFeasible(s, c.u, c.ticks, c.blocking, best);
      return;
    }
    v = c.u;
    ticks = c.ticks;
    Evaluate(s, v, s.options->integration, &v_nodes, nullptr);
  }
  if (!CheckArrival(s, v, v_nodes, ticks).passed) return;
  ++row->within_limits;
  Consider(v, v_nodes, ticks, best);
}

}  // namespace plateball::internal::fewest
