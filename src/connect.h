// Internal: the one place where the planner connects two consecutive partition points. It tries
// the local join of Lemma 2.1; when the target is beyond the local radius and a fallback is
// given, the global reach of reach.h connects the points with its earliest solution.
#pragma once

#include <Eigen/Core>

#include "plateball/ball_model.h"
#include "plateball/ball_state.h"
#include "plateball/join.h"
#include "plateball/reach.h"

namespace plateball::internal {

/// What a caller joining many similar pairs (the planner) carries from join to join.
struct JoinCarry {
  /// false: angles_after of a converged join is left unset (its atan2 saved for a caller that
  /// integrates the arc itself).
  bool end_angles = true;
  /// The rollouts' step (join.cc: equal Fehlberg 7(8) steps of about this length): the last
  /// join's on return, tried first by the next (0: start from the first guess's t).
  double step = 0.0;
};

/// Join (join.h) for input already validated by the caller: options valid, mu > 0, finite
/// points, angles reduced (|angle| <= pi or canonical). The planner checks all of it once.
/// carry: see JoinCarry (nullptr: a join on its own).
JoinSummary JoinValidated(const BallModel& model,
                          const AngleState& start_reduced,
                          double mu,
                          const Eigen::Vector2d& x0,
                          const Eigen::Vector2d& target,
                          const JoinOptions& options,
                          JoinCarry* carry = nullptr);

/// The planner's input is validated once (PlanImpulses); the join is JoinValidated.
/// `reach_fallback` == nullptr: the local join only. Otherwise a kTargetBeyondLocalRadius join is
/// retried with Reach (earliest solution, converted to a JoinSummary with status kConverged and
/// a message saying so); *reached_globally (when given) tells which one answered. carry: as
/// JoinValidated's.
JoinSummary ConnectPoints(const BallModel& model,
                          const AngleState& angles,
                          double mu,
                          const Eigen::Vector2d& x0,
                          const Eigen::Vector2d& target,
                          const JoinOptions& options,
                          const ReachOptions* reach_fallback = nullptr,
                          bool* reached_globally = nullptr,
                          JoinCarry* carry = nullptr);

}  // namespace plateball::internal
