// Task adapters: the one mapping from a problem file (problem.h, the I/O layer) to each solver's
// problem and options. The tools, the tests, the benchmarks and the fuzz harnesses all call
// these, so that what a test checks is what a tool runs. Every adapter throws
// std::invalid_argument naming the file (problem.source) and the field when the file lacks the
// task or a value does not fit the solver.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "plateball/convergence.h"
#include "plateball/exact_arrival.h"
#include "plateball/export.h"
#include "plateball/fewest_impulses.h"
#include "plateball/free_motion.h"
#include "plateball/impulse_planner.h"
#include "plateball/isoparallel.h"
#include "plateball/isoparallel_plan.h"
#include "plateball/join.h"
#include "plateball/partition.h"
#include "plateball/path.h"
#include "plateball/problem.h"
#include "plateball/reach.h"

namespace plateball PLATEBALL_EXPORT {

/// The planned path of a PathSpec, validating every field; messages name `field`.key
/// (e.g. "plan.path.radius").
Path PathFromSpec(const PathSpec& spec, const std::string& field = "path");
/// A single smooth curve from a PathSpec whose type is not "piecewise".
SmoothCurve CurveFromSpec(const PathSpec& spec, const std::string& field = "path");
/// The partition rules of a file's partition for `path` (explicit taus: single-piece paths only).
std::vector<PartitionRule> PartitionFromSpec(const PartitionSpec& spec,
                                             const Path& path,
                                             const std::string& field = "partition");

/// What a task adapter makes of a problem file: the solver's problem and options, ready for its
/// solve call (one type for every task; the aliases below name each).
template <class ProblemT, class OptionsT>
struct TaskSetup {
  ProblemT problem;
  OptionsT options;
};

/// `simulate`: the free motion from the initial state, with the file's integration options.
FreeMotion FreeMotionFor(const Problem& problem);

using JoinSetup = TaskSetup<JoinProblem, JoinOptions>;
/// `join`: from the initial state at x0 to `target` (integration options from the file).
JoinSetup JoinSetupFor(const Problem& problem, const Eigen::Vector2d& target);

using ReachSetup = TaskSetup<ReachProblem, ReachOptions>;
/// `reach`: from the initial state at x0 to `target`; horizon from the reach section (when
/// present), seed and integration options from the file.
ReachSetup ReachSetupFor(const Problem& problem, const Eigen::Vector2d& target);

using PlanSetup = TaskSetup<PlanProblem, PlanOptions>;
/// `plan`: the plan section. `n` > 0 replaces the n of a uniform partition (an explicit one
/// rejects it, naming `n_field`). Requires problem.x0 == the path's start point.
PlanSetup PlanSetupFor(const Problem& problem, int n = 0, const std::string& n_field = "n");

using ConvergenceSetup = TaskSetup<ConvergenceProblem, ConvergenceOptions>;
/// `converge`: the plan section with the partition sizes `ns` (checked with
/// ValidatePartitionSizes, messages naming `ns_field`), else plan.converge_n, else 16 ... 1024.
/// An explicit partition has no n to vary: rejected, naming `ns_field` when ns were given.
ConvergenceSetup ConvergenceSetupFor(const Problem& problem,
                                     const std::vector<int>& ns = {},
                                     const std::string& ns_field = "ns",
                                     bool timings = false);

/// The options: the file's solver section, seed and integration section.
using IsoparallelSetup = TaskSetup<IsoparallelProblem, IsoparallelOptions>;
/// `isoparallel_solve`: the isoparallel section.
IsoparallelSetup IsoparallelSetupFor(const Problem& problem);

using IsoparallelPlanSetup = TaskSetup<IsoparallelPlanProblem, PlanOptions>;
/// The impulsive approximation of `solution` with the file's ball, psi, mu, start orientation,
/// impulse count (`impulses` > 0 overrides it) and integration section.
IsoparallelPlanSetup IsoparallelPlanSetupFor(const Problem& problem,
                                             const IsoparallelSolution& solution,
                                             int impulses = 0);

using ExactArrivalSetup = TaskSetup<ExactArrivalProblem, ExactArrivalOptions>;
/// `steer` along the plan section's path: the file's ball, initial state, x0 (= the path's start),
/// the steer section's goal and impulse count (`impulses` > 0 overrides it, naming `n_field`).
ExactArrivalSetup ExactArrivalSetupFor(const Problem& problem,
                                       int impulses = 0,
                                       const std::string& n_field = "impulses");
/// `steer` / `isoparallel_solve --exact` along an isoparallel optimal path: ball, psi, mu and
/// start orientation as IsoparallelPlanSetupFor; goal and impulse count from the steer section
/// when present, else the isoparallel section's goal, goal orientation and impulses.
ExactArrivalSetup ExactArrivalSetupFor(const Problem& problem,
                                       const IsoparallelSolution& solution,
                                       int impulses = 0,
                                       const std::string& n_field = "impulses");

using FewestImpulsesSetup = TaskSetup<FewestImpulsesProblem, FewestImpulsesOptions>;
/// `plateball steer` on a file whose steer section asks for the fewest impulses: the ball, mu,
/// start (the isoparallel section's start and start orientation when the file has one and no
/// plan, else the initial section's x0 and orientation), the steer section's goal, start at rest,
/// stop at the goal and `fewest` settings (defaults when absent), the rig section's limits and the
/// physical ball's masses.
FewestImpulsesSetup FewestImpulsesSetupFor(const Problem& problem);

}  // namespace PLATEBALL_EXPORT
