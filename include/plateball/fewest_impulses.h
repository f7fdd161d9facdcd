// Fewest impulses: the smallest number n of impulses that brings the ball from
// a start state (rolling, or at rest) to a goal position x1 and orientation A1 exactly, found by
// a systematic search, with the trade-off between n and the total time / path length.
//
// The impulses are those of exact_arrival.h: impulse k at time t_0 + ... + t_{k-1} turns psi by
// s_k (k = 0 at the start), then the ball rolls freely for t_k > 0. From rest the first impulse is
// energy-changing (0 -> mu) and chooses the direction of the first arc in the same way. Energy-
// changing impulses that scale omega do not change the path on the plate nor the reorientation
// along it (impulse.h: the time is only rescaled), so they cannot lower the count: the search is
// over (s_k, t_k) at the problem's mu, and energy-changing impulses appear where they do
// something, at a start from rest and at the optional stop at the goal.
//
// Conditions: x(T) = x1 (two) and LogSO3(A1^T A(T)) = 0 (three) on 2n unknowns; with
// `orientation_only` the position is free (three conditions). For lambda = 1 the arcs are
// straight rolls and the classical constructions (Hammersley 1983) give any orientation with two
// rolls and any position and orientation with three.
//
// The search, for n = 1, 2, ..., max_impulses in turn: `starts` deterministic starts per n (a
// Halton sequence over the directions s_k in [-pi, pi) and the flight times, total time in
// [0.1, 0.9] of the window (0, max_total_time]), each refined by Levenberg-Marquardt on the arrival
// conditions in (s_k, log t_k) with the exact Jacobian (src/exact_chain.h), then polished to the
// tolerances with 1e-14 rollouts (Newton steps with fresh exact Jacobians). A count with 2n >= m
// unknowns that no start reached continues with more Halton starts, up to `adaptive_starts` in
// all, and when count n + 1 arrives it is tried once more by continuation: along the arrival
// manifold of count n + 1 one flight is shrunk towards zero (projected descent of log t_k), the
// two impulses around it are merged into one (their turns of psi add) and the n-impulse point is
// refined like a start. The fewest count is the first n for which a start arrives within the
// window; a smaller count is reported with the closest arrival its starts reached.
//
// What is proved. A reached count is proved reachable (the arrival is re-integrated). A count
// with 2n < m (m = 5 conditions, 3 with orientation_only) is impossible for a generic goal: the
// goals that n impulses reach are the image of a 2n-dimensional parameter set under a smooth map,
// a set of measure zero (Sard) — `kGenericallyImpossible`; a particular goal may still lie in it
// (a goal made by one impulse, or Figure 7's two straight rolls). Every other count that did not
// arrive is only `kNotFound`. So a fewest count n with 2(n - 1) < m is the fewest for a generic
// goal (`minimal_for_generic_goal`): n = 3 with five conditions, n = 2 with three. The Pareto
// table's times are the shortest FOUND per count, not proved shortest: per count the arrival of
// shortest total time among those found, shortened further along the arrival manifold
// (projected descent of T); count n + 1 is first seeded by count n's arrival with its longest
// flight split by a zero impulse, so the times do not grow with the count. A count stops after
// `arrivals_per_count` arrivals.
//
// Under a rig's limits (`limits`, rig_limits.h). Every exact arrival the search finds is a
// candidate: one that meets every limit (at sample nodes and dense points, without a tick) is kept
// unchanged; any other, and every arrival with a tick, is taken through the constrained solver
// (SLSQP with the arrival as equalities and the limits as inequalities, minimising the total time,
// times snapped to the tick grid) from it. A count is reached only when a candidate arrives exactly
// within the limits AND the independent replay check (CheckRigLimits: FreeMotion, 64 samples per
// flight) passes; the row keeps that check. The shortening along the arrival manifold is kept only
// when the shortened arrival still meets the limits (and never with a tick). A count with exact
// arrivals but none within the limits is not reached: its verdict is kNotFound (kGenericallyImpossible
// when 2n < m), its row the closest feasible arrival of the constrained solver with the limits that
// block it. With a tick, a count whose free unknowns (n turns, + 1 for the last flight without a
// stop) are fewer than m is kGenericallyImpossible: each of the countably many choices of grid
// times leaves a null set of goals. Limits that every candidate meets change nothing: the summary is the one without
// them, bit for bit. When no count is reached within the limits but some count arrives without them, the status is
// kLimitsNotMet naming the blocking limits.
//
// The objective "fewest" (ArrivalObjective::kFewest) is this search: the fewest count reached; ties
// within that count (several arrivals) are broken by the shortest total time found, then by the
// order of discovery (the split seed, the Halton starts in order, the continuation).
#pragma once

#include <Eigen/Core>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "plateball/ball_model.h"
#include "plateball/ball_state.h"
#include "plateball/exact_arrival.h"
#include "plateball/export.h"
#include "plateball/field_list.h"
#include "plateball/integration_options.h"
#include "plateball/rig_limits.h"
#include "plateball/start_state.h"

namespace plateball PLATEBALL_EXPORT {

enum class FewestImpulsesStatus {
  kNotRun,    ///< default: nothing was solved
  kFound,     ///< an exact arrival with `fewest` impulses (and none with fewer within the search)
  kNotFound,  ///< no count up to max_impulses arrived within the search (closest arrival reported)
  /// With limits: some count arrives exactly, but none within the limits (blocking limits named,
  /// closest feasible arrival per count reported).
  kLimitsNotMet,
};
/// The value's word as the tools write it in their JSON output and messages.
std::string ToString(FewestImpulsesStatus status);

/// What is known of one impulse count after the search (see the header comment, "What is proved").
enum class FewestCountVerdict {
  kReached,  ///< an arrival within the window was found and re-integrated
  /// 2n < conditions, or with a rig tick fewer free unknowns than conditions (n turns, + 1 for the
  /// last flight without a stop; the grid times are countably many): no generic goal is reachable (Sard)
  kGenericallyImpossible,
  kNotFound,  ///< 2n >= conditions and no start arrived: not found, NOT proved impossible
};
/// "reached", "generically_impossible" or "not_found", as in the JSON.
std::string ToString(FewestCountVerdict verdict);

/// What is asked: the ball's start state (StartState: model, initial, mu, A0, x0) and the goal.
struct FewestImpulsesProblem : StartState {
  bool start_at_rest = false;                        ///< the ball is at rest at the start (first impulse 0 -> mu)
  bool stop_at_goal = false;                         ///< one more impulse at the goal brings omega to zero
  Eigen::Vector2d x1 = Eigen::Vector2d::UnitX();     ///< goal position (ignored with orientation_only)
  Eigen::Matrix3d A1 = Eigen::Matrix3d::Identity();  ///< goal orientation
  bool orientation_only = false;                     ///< only the orientation is prescribed (three conditions)
  /// The rig's limits (rig_limits.h; needs the goal position: not with orientation_only); empty: none.
  RigLimits limits;
  /// The masses behind the impulse bounds (limits.max_plate_impulse, limits.max_force) and the
  /// total impulse sum |J| of the Pareto table; without them the table sums the plate velocity changes.
  std::optional<PhysicalParameters> physical;
};

struct FewestImpulsesOptions {
  static constexpr int kMaxImpulses = 20;
  static constexpr int kMaxStarts = 10000;
  static constexpr int kMaxIterations = 10000;
  static constexpr double kMaxTotalTime = 1e6;  ///< the largest search window
  int max_impulses = 6;                         ///< largest count searched, in [1, kMaxImpulses]
  int pareto_counts = 3;       ///< rows of the Pareto table from the fewest count up, in [1, kMaxImpulses]
  int starts = 24;             ///< starts per count, in [1, kMaxStarts]
  int arrivals_per_count = 4;  ///< a count stops after this many arrivals, in [1, kMaxStarts]
  /// Starts in all (the first `starts` included) for a count with 2n >= conditions that no start
  /// reached, in [0, kMaxStarts]; at most `starts` are tried when smaller.
  int adaptive_starts = 256;
  /// Search window: total time T <= max_total_time (> 0); 0 chooses 1.5 (|x1 - x0| + angle(A0, A1) +
  /// 2 pi) / sqrt(mu): one and a half times the time to roll the distance, the turn and a full turn
  /// at the speed sqrt(mu). Starts take total times in [0.1, 0.9] of the window.
  double max_total_time = 0.0;
  int max_iterations = 15;               ///< Levenberg-Marquardt iterations per start, in [1, kMaxIterations]
  double position_tolerance = 1e-12;     ///< |x(T) - x1| to reach
  double orientation_tolerance = 1e-10;  ///< rad
  IntegrationOptions integration{1e-14, 1e-14, 2'000'000};       ///< final rollouts
  IntegrationOptions search_integration{1e-8, 1e-8, 2'000'000};  ///< rollouts + Jacobians of the search
  /// Called on the calling thread before each start of the search with the count n being searched
  /// and the starts tried so far in all counts; may throw to abandon the search (the exception
  /// propagates out of SolveFewestImpulses). Empty: no calls.
  std::function<void(int n, int starts)> progress;

  /// Empty when the options are valid; else a message naming the field and its value (the ranges
  /// of the field list, then the two integrations').
  std::string Validate() const;

  /// The field list (field_list.h): the Python attributes and the ranges Validate() checks.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(
        PLATEBALL_FIELD(max_impulses, "largest impulse count searched").Counts(1, kMaxImpulses),
        PLATEBALL_FIELD(pareto_counts, "rows of the Pareto table from the fewest count up").Counts(1, kMaxImpulses),
        PLATEBALL_FIELD(starts, "starts per count").Counts(1, kMaxStarts),
        PLATEBALL_FIELD(arrivals_per_count, "a count stops after this many arrivals").Counts(1, kMaxStarts),
        PLATEBALL_FIELD(adaptive_starts, "starts in all for a count with 2n >= conditions that no start reached")
            .Counts(0, kMaxStarts),
        PLATEBALL_FIELD(max_total_time, "search window: total time T <= max_total_time")
            .NonNegative(kMaxTotalTime, "0: automatic"),
        PLATEBALL_FIELD(max_iterations, "Levenberg-Marquardt iterations per start").Counts(1, kMaxIterations),
        PLATEBALL_FIELD(position_tolerance, "|x(T) - x1| to reach").Positive(),
        PLATEBALL_FIELD(orientation_tolerance, "|LogSO3(A1^T A(T))| to reach (rad)").Positive(),
        PLATEBALL_FIELD(integration, "tolerances and step bound of the final rollouts"),
        PLATEBALL_FIELD(search_integration, "tolerances and step bound of the search's rollouts and Jacobians"));
  }
};

/// One count n of the search (a row of the Pareto table when it arrived).
struct FewestImpulsesCount {
  int impulses = 0;      ///< n
  int starts = 0;        ///< starts tried
  int arrived = 0;       ///< starts that arrived exactly within the window
  bool reached = false;  ///< arrived > 0
  FewestCountVerdict verdict = FewestCountVerdict::kNotFound;
  /// The arrival was found by continuation from count n + 1 (a flight shrunk to zero).
  bool by_continuation = false;
  /// The arrival of shortest total time FOUND (when reached; not proved shortest), else the
  /// closest arrival found.
  std::vector<ExactImpulse> plan;
  std::optional<ExactImpulse> stop;  ///< with stop_at_goal, when reached
  double total_time = 0.0;           ///< T = sum t_k
  double path_length = 0.0;          ///< length of the contact point's path on the plate
  double position_error = 0.0;       ///< |x(T) - x1| (0 with orientation_only)
  double orientation_error = 0.0;    ///< |LogSO3(A1^T A(T))|, rad
  Eigen::Vector2d x_final = Eigen::Vector2d::Zero();
  Eigen::Matrix3d A_final = Eigen::Matrix3d::Identity();
  Eigen::VectorXd parameters;  ///< (delta psi_0..n-1, t_0..n-1) of `plan`
  /// Sum over the impulses (start and stop included) of |J| with the physical parameters, else of
  /// the plate velocity change |2 delta omega x e3|.
  double total_impulse = 0.0;
  /// sqrt(sum_{k=1}^{n-1} |x_k - (x0 + k (x1 - x0) / n)|^2): the interior impulse points against
  /// the straight line x0 -> x1 cut into n equal parts (exact_arrival.h's deviation for that line).
  double deviation = 0.0;
  // With limits:
  int within_limits = 0;              ///< arrivals that met the limits (reached = within_limits > 0)
  std::vector<std::string> active;    ///< limits active at the row's arrival (when reached)
  std::vector<std::string> blocking;  ///< not reached: limits active at the closest feasible arrival
  std::optional<RigCheck> check;      ///< when reached: the independent replay check (passed)
};

/// A default-constructed summary says "not run".
struct FewestImpulsesSummary {
  FewestImpulsesStatus status = FewestImpulsesStatus::kNotRun;
  std::string message = "not run";
  int fewest = 0;  ///< the fewest count (0 when not found, or found when the start meets the goal)
  /// Every count below `fewest` is kGenericallyImpossible: `fewest` is the fewest for a generic
  /// goal. false: a smaller count is only kNotFound (or nothing was found).
  bool minimal_for_generic_goal = false;
  std::vector<FewestImpulsesCount> counts;  ///< every count searched, n = 1, 2, ... in order
  double max_total_time = 0.0;              ///< the window used
  std::string searched;                     ///< what was searched, in words
  int rollouts = 0;                         ///< trajectories integrated
  bool limited = false;                     ///< the problem had limits: rows are reached only within them
  int constrained_solves = 0;               ///< constrained solver runs (candidates that needed it)
  int evaluations = 0;                      ///< SLSQP evaluations of those runs
  std::vector<std::string> blocking;        ///< kLimitsNotMet: the limits that blocked the counts that arrived

  /// True when the status gives a result that may be used.
  bool IsSolutionUsable() const { return status == FewestImpulsesStatus::kFound; }
  /// The row of the fewest count (nullptr when not found).
  const FewestImpulsesCount* Fewest() const;
  /// One line: the status, the message and the main numbers.
  std::string BriefReport() const;
};

/// Searches the fewest impulses. Throws std::invalid_argument naming the field for invalid input;
/// a goal not reached within the search is the status kNotFound with the closest arrival per count.
FewestImpulsesSummary SolveFewestImpulses(const FewestImpulsesProblem& problem,
                                          const FewestImpulsesOptions& options = {});

/// The same problem as an exact-arrival problem with the found impulses (for ReplayExactArrival
/// and CheckRigLimits, with the problem's limits and physical parameters): the reference is the
/// straight line x0 -> x1 (x0 -> x0 + e1 when they coincide).
ExactArrivalProblem ReplayProblemFor(const FewestImpulsesProblem& problem, int impulses);

}  // namespace PLATEBALL_EXPORT
