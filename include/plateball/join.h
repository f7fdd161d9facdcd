// Joining two close points with one energy-preserving impulse (section 2.1, "Joining two close
// points", Lemma 2.1).
#pragma once

#include <Eigen/Core>
#include <string>

#include "plateball/ball_model.h"
#include "plateball/ball_state.h"
#include "plateball/export.h"
#include "plateball/field_list.h"
#include "plateball/impulse.h"
#include "plateball/integration_options.h"

namespace plateball PLATEBALL_EXPORT {

/// How a join ended.
enum class JoinStatus {
  kNotRun,                   ///< default: no join was run
  kConverged,                ///< x_s(t) = target to the residual tolerance, t in the local range
  kTargetEqualsStart,        ///< target == x0: t = 0 and any delta psi; nothing to join
  kTargetBeyondLocalRadius,  ///< the unique small-t solution of Lemma 2.1 was not found
                             ///< (t > K1 |x - x0|, degenerate Jacobian or no convergence):
                             ///< a global reach (reach.h) is needed
  kIntegrationFailure,       ///< the ODE integration failed (step bound exceeded)
};
/// The value's word as the tools write it in their JSON output and messages.
std::string ToString(JoinStatus status);

struct JoinOptions {
  /// Accept when |x_s(t) - target| <= this.
  double residual_tolerance = 1e-12;
  /// Levenberg-Marquardt iterations (each integrates the motion and its s-derivative once).
  int max_iterations = 30;
  /// K1 of Lemma 2.1 used for the local-branch test t <= K1 |x - x0|, as a multiple of
  /// 1 / v_min with v_min = MinimumContactSpeed(mu, model) (every short arc has t ~ d/|x'| with
  /// |x'| >= v_min; see docs/paper_notes.md, "Joining close points").
  double local_time_factor = 2.0;
  IntegrationOptions integration;
  /// Empty when valid, else names the field, the value and the bound: residual_tolerance in
  /// [1e-15, 1e-3], then the ranges of the field list, then the integration's.
  std::string Validate() const;

  /// The field list (field_list.h): the Python attributes and the ranges Validate() checks.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(PLATEBALL_FIELD(residual_tolerance, "accept when |x_s(t) - target| <= this"),
             PLATEBALL_FIELD(max_iterations, "Levenberg-Marquardt iterations").Counts(1, 10000),
             PLATEBALL_FIELD(local_time_factor, "K1 of Lemma 2.1 for the local-branch test, times 1 / v_min")
                 .Closed(1.0, 1000.0),
             PLATEBALL_FIELD(integration, "tolerances and step bound of the integrations"));
  }
};

/// What is asked (Lemma 2.1): the ball just before the impulse at x0, and the point to reach.
struct JoinProblem {
  BallModel model = BallModel::FromLambda(1.0);
  AngleState start;                                  ///< (theta, phi, psi) before the impulse
  double mu = 1.0;                                   ///< energy level, eq. (9), > 0
  Eigen::Vector2d x0 = Eigen::Vector2d::Zero();      ///< contact point at the impulse
  Eigen::Vector2d target = Eigen::Vector2d::Zero();  ///< the close point to reach
};

/// The answer of Join, with what was asked. A default-constructed summary says "not run".
struct JoinSummary {
  // What was asked.
  AngleState start;  ///< (theta, phi, psi) just before the impulse
  double mu = 0.0;
  Eigen::Vector2d x0 = Eigen::Vector2d::Zero();
  Eigen::Vector2d target = Eigen::Vector2d::Zero();

  JoinStatus status = JoinStatus::kNotRun;
  std::string message = "not run";  ///< why, when not kConverged (empty when converged)
  double delta_psi = 0.0;           ///< s of Lemma 2.1, in (-pi, pi]
  double t = 0.0;                   ///< time of flight, >= 0
  double residual = 0.0;            ///< |x_s(t) - target|
  /// Quasi-Newton steps on rollouts (and Levenberg-Marquardt iterations, where those fail); 0 when
  /// the first rollout (at the guess refined on the Taylor model of a short arc) was already
  /// within the tolerance.
  int iterations = 0;
  /// |x - target| at the first point rolled out: the velocity-ellipse guess (27)-(28), refined on
  /// a Taylor model of x(s, t) (t sqrt(mu) <= 0.2: checked there; up to 3: as the guess, when the
  /// model's Newton steps converge).
  double initial_guess_residual = 0.0;
  double time_limit = 0.0;  ///< K1 |target - x0|: the local branch has t <= this
  /// |det J| / (|J_s| |J_t|) at the solution: sine of the angle between dx/ds and dx/dt
  /// (0 = degenerate polar coordinates). dx/ds is the Taylor model's (to ~1e-6) when iterations = 0.
  double jacobian_conditioning = 0.0;

  Impulse impulse;                                    ///< the impulse at x0 (delta omega, plate velocity change)
  BallState state_after;                              ///< (z, omega) on arrival at the target, before any next impulse
  AngleState angles_after;                            ///< canonical angles on arrival
  Eigen::Vector2d x_after = Eigen::Vector2d::Zero();  ///< contact point on arrival (~ target)

  /// True when the status gives a result that may be used.
  bool IsSolutionUsable() const { return status == JoinStatus::kConverged; }
  /// One line: the status, the message and the main numbers.
  std::string BriefReport() const;
};

/// The least speed |x'| = |omega| of any state of energy mu: sqrt(mu / max(1, lambda)) (the
/// smaller semi-axis of the velocity ellipse (27) over all theta).
double MinimumContactSpeed(double mu, const BallModel& model);

/// Lemma 2.1: find (s, t), t >= 0, such that the free motion from (theta, phi, psi + s) at x0
/// reaches `target` at time t. Solved by Levenberg-Marquardt (Ceres TinySolver) on the 2x2
/// residual x_s(t) - target, with the exact Jacobian: dx/dt = x'(t) = (omega_2, -omega_1) and
/// dx/ds from the variational equations integrated with the motion (dopri5). Initial guess from
/// the velocity ellipse (27)-(28): x'_s(0) pointing at the target, t = |target - x0| / |x'_s(0)|.
/// Throws std::invalid_argument (naming the field) for non-finite input, mu <= 0 or invalid options.
/// A chart-free start state enters through AnglesFromState (ball_state.h).
JoinSummary Join(const JoinProblem& problem, const JoinOptions& options = {});

}  // namespace PLATEBALL_EXPORT
