#include "feedback_policy.h"

#include <exception>

#include "connect.h"
#include "plateball/path.h"
#include "plateball/so3.h"

namespace plateball::internal {

FeedbackPolicy::FeedbackPolicy(const NominalPlan& nominal, ExecutionStrategy strategy, const ExecutionOptions& options)
    : nominal_(nominal), strategy_(strategy), options_(options) {}

bool FeedbackPolicy::WantsExact(int k) const {
  const int remaining = impulses() - k;
  return strategy_ == ExecutionStrategy::kFeedbackExact && remaining >= 3 && remaining <= options_.exact_window;
}

// Join the observed state to the next pass point (the planner's connection).
bool FeedbackPolicy::Join(int k, const FeedbackObservation& obs, FeedbackCommand* command) {
  const PlanOptions& po = nominal_.options;
  const JoinSummary j = ConnectPoints(nominal_.model,
                                      obs.angles,
                                      obs.mu,
                                      obs.x,
                                      nominal_.pass_points[static_cast<std::size_t>(k) + 1],
                                      po.join,
                                      po.reach_fallback ? &po.reach : nullptr);
  if (!j.IsSolutionUsable()) {
    status_ =
        j.status == JoinStatus::kIntegrationFailure ? ExecutionStatus::kIntegrationFailure : ExecutionStatus::kLost;
    message_ = "impulse " + std::to_string(k) + ": " + j.BriefReport();
    return false;
  }
  *command = {j.impulse.delta_omega, j.t, j.delta_psi};
  return true;
}

// Exact re-plan of the remaining impulses from the observed state; false when it did not arrive.
bool FeedbackPolicy::SolveExact(int k, const FeedbackObservation& obs, FeedbackCommand* command) {
  ExactArrivalProblem ep;
  ep.model = nominal_.model;
  ep.initial = obs.angles;
  ep.mu = obs.mu;
  ep.A0 = ProjectToSO3(obs.A);
  ep.x0 = obs.x;
  std::vector<Eigen::Vector2d> points{obs.x};
  points.insert(points.end(), nominal_.pass_points.begin() + k + 1, nominal_.pass_points.end());
  ExactArrivalSummary sol;
  try {
    ep.reference = Path({SmoothCurve::Samples(points)});
    ep.impulses = impulses() - k;
    ep.x1 = nominal_.goal;
    ep.A1 = nominal_.goal_orientation;
    sol = SolveExactArrival(ep, options_.exact);
  } catch (const std::exception&) {
    return false;  // e.g. the observed point on top of the next pass point: no reference
  }
  if (!sol.IsSolutionUsable()) return false;
  tail_ = sol.impulses;
  tail_start_ = k;
  *command = {tail_.front().delta_omega, tail_.front().duration, tail_.front().delta_psi};
  return true;
}

bool FeedbackPolicy::Decide(int k, const FeedbackObservation& obs, bool exact_allowed, FeedbackCommand* command) {
  if (WantsExact(k) && exact_allowed) {
    if (SolveExact(k, obs, command)) {
      ++exact_solves_;
      return true;
    }
    ++exact_failures_;  // go on with the last exact plan, if any, else join
  }
  const int remaining = impulses() - k;
  if (strategy_ == ExecutionStrategy::kFeedbackExact && remaining <= options_.exact_window && !tail_.empty()) {
    const ExactImpulse& e = tail_[static_cast<std::size_t>(k - tail_start_)];
    *command = {e.delta_omega, e.duration, e.delta_psi};
    return true;
  }
  return Join(k, obs, command);
}

}  // namespace plateball::internal
