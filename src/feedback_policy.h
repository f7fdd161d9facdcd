// Internal: the feedback strategies' decision at one impulse, shared by Execute (which simulates
// the ball and the controller together) and the Controller (which a rig calls once per tick).
//   feedback        join the observed state to the next pass point (Lemma 2.1, join.h);
//   feedback_exact  while 3 ... exact_window impulses remain, re-plan the remaining impulses for
//                   exact arrival at the goal (exact_arrival.h); the last two, and any step whose
//                   re-plan does not arrive, continue the last exact solution, else join.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "plateball/ball_state.h"
#include "plateball/exact_arrival.h"
#include "plateball/execution.h"

namespace plateball::internal {

/// What the feedback sees just before impulse k (nominal lambda).
struct FeedbackObservation {
  AngleState angles;
  double mu = 0.0;
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
};

/// What it commands: the jump of the ball's angular velocity and the flight to the next impulse.
struct FeedbackCommand {
  Eigen::Vector3d delta_omega = Eigen::Vector3d::Zero();
  double duration = 0.0;
  double delta_psi = 0.0;
};

class FeedbackPolicy {
 public:
  /// `nominal` and `options` must outlive the policy; strategy is kFeedback or kFeedbackExact.
  FeedbackPolicy(const NominalPlan& nominal, ExecutionStrategy strategy, const ExecutionOptions& options);

  /// The command of impulse k (0 <= k < n) from `obs`. exact_allowed = false skips a new exact
  /// re-plan (the controller's time budget is spent) and continues the last one or joins. Returns
  /// false when the next pass point cannot be joined: status() and message() then say why.
  bool Decide(int k, const FeedbackObservation& obs, bool exact_allowed, FeedbackCommand* command);

  /// kLost or kIntegrationFailure after a failed Decide.
  ExecutionStatus status() const { return status_; }
  const std::string& message() const { return message_; }
  int exact_solves() const { return exact_solves_; }
  int exact_failures() const { return exact_failures_; }
  /// Impulses the plan has (pass points - 1).
  int impulses() const { return static_cast<int>(nominal_.pass_points.size()) - 1; }
  /// True when impulse k would be a new exact re-plan (not a join or a continued tail).
  bool WantsExact(int k) const;

 private:
  bool Join(int k, const FeedbackObservation& obs, FeedbackCommand* command);
  bool SolveExact(int k, const FeedbackObservation& obs, FeedbackCommand* command);

  const NominalPlan& nominal_;
  ExecutionStrategy strategy_;
  const ExecutionOptions& options_;
  std::vector<ExactImpulse> tail_;  // the last exact solution, from impulse tail_start_ on
  int tail_start_ = 0;
  int exact_solves_ = 0;
  int exact_failures_ = 0;
  ExecutionStatus status_ = ExecutionStatus::kCompleted;
  std::string message_;
};

}  // namespace plateball::internal
