#include "connect.h"

#include <cmath>

#include "kinematics.h"

namespace plateball::internal {

JoinSummary ConnectPoints(const BallModel& model,
                          const AngleState& angles,
                          double mu,
                          const Eigen::Vector2d& x0,
                          const Eigen::Vector2d& target,
                          const JoinOptions& options,
                          const ReachOptions* reach_fallback,
                          bool* reached_globally,
                          JoinCarry* carry) {
  if (reached_globally != nullptr) *reached_globally = false;
  JoinSummary join = JoinValidated(model, angles, mu, x0, target, options, carry);
  if (join.status != JoinStatus::kTargetBeyondLocalRadius || reach_fallback == nullptr) return join;

  ReachProblem problem;
  problem.model = model;
  problem.start = angles;
  problem.mu = mu;
  problem.x0 = x0;
  problem.target = target;
  ReachOptions reach_options = *reach_fallback;
  reach_options.integration = options.integration;
  const ReachSummary reach = Reach(problem, reach_options);
  if (reach.status == ReachStatus::kNumericalFailure) {
    join.status = JoinStatus::kIntegrationFailure;
    join.message = "local join: " + join.message + "; fallback " + reach.BriefReport();
    return join;
  }
  if (!reach.IsSolutionUsable()) {
    join.message = "local join: " + join.message + "; fallback " + reach.BriefReport();
    return join;
  }
  const ReachSolution& e = reach.Earliest();
  JoinSummary out = join;
  out.status = JoinStatus::kConverged;
  out.message = "beyond the local radius; connected by " + reach.BriefReport();
  out.delta_psi = WrapPi(e.delta_psi);  // the join's convention, (-pi, pi]
  out.t = e.t;
  out.residual = e.residual;
  out.iterations = reach.refine_iterations;
  out.jacobian_conditioning = 0.0;  // not computed by Reach (its solutions are transversal)
  out.impulse = e.impulse;
  out.state_after = e.end.state;
  out.angles_after = e.end.angles;
  out.x_after = e.end.x;
  if (reached_globally != nullptr) *reached_globally = true;
  return out;
}

}  // namespace plateball::internal
