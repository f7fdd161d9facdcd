// The search of SolveFewestImpulses (fewest_impulses.h), shared by its two sources: the free
// search of each count (starts, Levenberg-Marquardt, Newton polish, shortening, continuation to
// fewer impulses) in fewest_impulses.cc, and the rig-limits side with the description of a
// count's row (the constrained arrival, the independent replay check, the row's totals) in
// fewest_limits.cc.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "constrained_arrival.h"
#include "exact_chain.h"
#include "plateball/fewest_impulses.h"

namespace plateball::internal::fewest {

// The fixed data of the search.
struct Search {
  const FewestImpulsesProblem* problem = nullptr;
  const FewestImpulsesOptions* options = nullptr;
  ChainNode start;
  double max_total_time = 0.0;
  int conditions = 5;  // 3 with orientation_only
  int* rollouts = nullptr;
  int* starts = nullptr;                     // starts tried in all counts, for the progress hook
  bool limited = false;                      // the problem has limits (rows are reached only within them)
  FewestImpulsesSummary* summary = nullptr;  // for the constrained solver's counters
  bool closest_wanted = true;                // a count's closest feasible arrival is reported (not in a continuation)
};

// The best of a count so far: the arrival of shortest total time, else the closest point.
struct CountBest {
  double time = std::numeric_limits<double>::infinity();
  double closest = std::numeric_limits<double>::infinity();
  Eigen::VectorXd u;
  std::vector<ChainNode> nodes;
  std::vector<long long> ticks;  // with a rig tick: the grid index of every impulse (and the stop)
  // With limits, while no arrival within them: u is the closest feasible arrival (or an exact
  // arrival the grid cannot hold), `blocking` the limits that stop it.
  bool feasible_closest = false;
  std::vector<std::string> blocking;
  int failed = 0;  // constrained solves of the count that did not arrive
};

// Rolls u at `integration`; with `jac` also the Jacobian of the conditions (m x 2n).
Eigen::VectorXd Evaluate(const Search& s,
                         const Eigen::VectorXd& u,
                         const IntegrationOptions& integration,
                         std::vector<ChainNode>* nodes,
                         Eigen::MatrixXd* jac);

// Keeps the arrival u (on the grid `ticks` with a rig tick) if it is the shortest of the count so
// far; an equal time keeps the earlier one.
void Consider(const Eigen::VectorXd& u,
              const std::vector<ChainNode>& nodes,
              const std::vector<long long>& ticks,
              CountBest* best);

// The constrained exact arrival of count n (constrained_arrival.h) at the problem's mu.
ConstrainedSetup ConstrainedFor(const Search& s, int n);

// The independent check of an arrival against the limits (CheckRigLimits: a FreeMotion replay).
RigCheck CheckArrival(const Search& s,
                      const Eigen::VectorXd& u,
                      const std::vector<ChainNode>& nodes,
                      const std::vector<long long>& ticks);

// Sum of |J| with the physical parameters, else of the plate velocity changes, over the impulses.
double TotalImpulse(const FewestImpulsesProblem& p,
                    const std::vector<ExactImpulse>& plan,
                    const std::optional<ExactImpulse>& stop);

// The row of count n from its best parameters.
void Describe(const Search& s, const CountBest& best, FewestImpulsesCount* row);

// An exact arrival u under the limits: kept unchanged when it meets them (without a tick), else
// the constrained solver's arrival from it; either counts only when the independent check passes.
void Admit(const Search& s,
           const Eigen::VectorXd& u,
           const std::vector<ChainNode>& nodes,
           FewestImpulsesCount* row,
           CountBest* best);

}  // namespace plateball::internal::fewest
