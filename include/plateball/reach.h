// Reaching distant points (section 2.3, last remark, and Figure 8): find every energy-preserving
// impulse delta_psi = s and time t > 0 such that the free motion from (theta, phi, psi + s) at x0
// passes through a target point at time t, for t up to a horizon of several periods.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "plateball/ball_model.h"
#include "plateball/ball_state.h"
#include "plateball/export.h"
#include "plateball/field_list.h"
#include "plateball/free_motion.h"
#include "plateball/impulse.h"
#include "plateball/integration_options.h"

namespace plateball PLATEBALL_EXPORT {

/// What is asked: the ball just before the impulse and the point to reach.
struct ReachProblem {
  BallModel model = BallModel::FromLambda(1.0);
  /// (theta, phi, psi) before the impulse; any real theta: (theta, phi, psi) and
  /// (-theta, phi + pi, psi) are the same physical state (ball_state.h), so the paper's
  /// theta0 = -pi/3 of Figure 8 is used as written.
  AngleState start;
  double mu = 1.0;                               ///< energy level, eq. (9), > 0
  Eigen::Vector2d x0 = Eigen::Vector2d::Zero();  ///< contact point at the impulse
  /// Orientation R_WB at the impulse (FreeMotion::FromAngles puts the start's z on its third
  /// column); only the reported end states use it.
  Eigen::Matrix3d A0 = Eigen::Matrix3d::Identity();
  Eigen::Vector2d target = Eigen::Vector2d::Zero();
};

struct ReachOptions {
  /// Solutions with 0 < t <= horizon_periods * T are enumerated (T = 2 pi / sqrt(mu)).
  double horizon_periods = 5.0;
  /// Grid of the deterministic scan: directions s in [0, 2 pi) and time steps per period of the
  /// cheap (z, x) integration (classical RK4) that tabulates x_s(t). The defaults find every
  /// solution of the standard task T3 and of the multi-solution cases in tests/reach_test.cc
  /// (checked there against an independent scan 8 times denser).
  int scan_directions = 128;
  int scan_steps_per_period = 64;
  /// A refined (s, t) is a solution when |x_s(t) - target| <= tolerance (tight integration).
  double tolerance = 1e-11;
  /// Levenberg-Marquardt iterations (Ceres TinySolver) per candidate.
  int max_refine_iterations = 30;
  /// Upper bound on the candidates refined (bounds the work for pathological inputs).
  int max_candidates = 256;
  /// Function evaluations of the NLopt global search (GN_DIRECT_L over s of the closest
  /// approach d(s) = min_t |x_s(t) - target|). It runs on every call: its minimiser is refined
  /// like a scan candidate, and it gives the closest approach when nothing reaches the target.
  int global_max_evaluations = 80;
  /// Tolerances of the tight integrations (refinement, end states).
  IntegrationOptions integration;

  /// Empty when valid; otherwise names the field, its value and the bound: horizon_periods in
  /// (0, 1e4], the ranges of the field list, the work budget, then the integration's.
  std::string Validate() const;

  /// The field list (field_list.h): the Python attributes and the ranges Validate() checks.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(
        PLATEBALL_FIELD(horizon_periods, "solutions with t up to this many periods 2 pi / sqrt(mu) are enumerated"),
        PLATEBALL_FIELD(scan_directions, "directions s of the deterministic scan").Counts(8, 100000),
        PLATEBALL_FIELD(scan_steps_per_period, "time steps per period of the scan").Counts(8, 100000),
        PLATEBALL_FIELD(tolerance, "a refined (s, t) is a solution when |x_s(t) - target| <= tolerance").Positive(),
        PLATEBALL_FIELD(max_refine_iterations, "Levenberg-Marquardt iterations per candidate").Counts(1, 1000),
        PLATEBALL_FIELD(max_candidates, "candidates refined at most").Counts(1, 100000),
        PLATEBALL_FIELD(global_max_evaluations, "function evaluations of the global search of the closest approach")
            .Counts(1, 100000),
        PLATEBALL_FIELD(integration, "tolerances and step bound of the tight integrations"));
  }
};

enum class ReachStatus {
  kNotRun,                    ///< default: no reach was run
  kSolved,                    ///< at least one solution with t <= horizon
  kUnreachableWithinHorizon,  ///< none found; closest_approach says how near the ball gets
  kNumericalFailure,          ///< an integration failed (step bound); message says where
  kTargetEqualsStart,         ///< |target - x0| <= tolerance: nothing to reach (t = 0)
};
/// The value's word as the tools write it in their JSON output and messages.
std::string ToString(ReachStatus status);

/// One way to reach the target: impulse psi -> psi + delta_psi, then free rolling for time t.
struct ReachSolution {
  double delta_psi = 0.0;  ///< s in [0, 2 pi)
  double t = 0.0;          ///< arrival time, 0 < t <= horizon
  double periods = 0.0;    ///< t / T
  double residual = 0.0;   ///< |x_s(t) - target| of the tight integration
  /// det d(x)/d(s, t) at the solution: nonzero for an isolated (transversal) solution; its sign
  /// tells on which side of a fold of the map (s, t) -> x the solution lies.
  double jacobian_determinant = 0.0;
  Impulse impulse;   ///< the energy-preserving impulse (plate velocity change included)
  MotionSample end;  ///< state on arrival (z, omega, x, A, angles, energy)
};

/// The closest the ball comes to the target over s in [0, 2 pi), t in [0, horizon].
struct ClosestApproach {
  double distance = 0.0;
  double delta_psi = 0.0;
  double t = 0.0;
};

struct ReachSummary {
  ReachProblem problem;
  double period = 0.0;   ///< T = 2 pi / sqrt(mu)
  double horizon = 0.0;  ///< horizon_periods * T
  ReachStatus status = ReachStatus::kNotRun;
  std::string message = "not run";  ///< why, for kNumericalFailure (empty otherwise once run)
  /// Distinct solutions sorted by t (earliest first).
  std::vector<ReachSolution> solutions;
  /// Filled when status is kUnreachableWithinHorizon (and, for reference, equal to the earliest
  /// solution with its residual when kSolved).
  ClosestApproach closest_approach;
  /// The paper's first guess: the s in [0, 2 pi) whose drift per period points from x0 to the
  /// target (NaN when the target is x0).
  double drift_guess_delta_psi = 0.0;
  int scan_periods_integrated = 0;  ///< cheap RK4 periods (scan and global search)
  int candidates = 0;               ///< scan candidates refined
  int refine_iterations = 0;        ///< Levenberg-Marquardt iterations, all candidates
  int tight_evaluations = 0;        ///< tight integrations of x_s(t) (with or without d/ds)
  int global_evaluations = 0;       ///< NLopt objective evaluations

  /// True when the status gives a result that may be used.
  bool IsSolutionUsable() const { return status == ReachStatus::kSolved && !solutions.empty(); }
  /// The default answer: the earliest solution. Throws std::logic_error when there is none.
  const ReachSolution& Earliest() const;
  /// One line: status, number of solutions, earliest (s, t, residual) or closest approach.
  std::string BriefReport() const;
};

/// Enumerates every (delta_psi, t) with 0 < t <= horizon that brings the contact point from x0 to
/// the target (section 2.3, last remark). Method: x_s(t) is a T-periodic motion plus a uniform
/// drift for every s (section 2.1, eqs. (25)-(26)), so one period per s is integrated and
/// repeated. A deterministic scan over a grid of s tabulates (s, t) -> x_s(t); the grid cells
/// whose image contains the target (and cells next to a fold of that map) seed a
/// Levenberg-Marquardt refinement of (s, t) (Ceres TinySolver, exact Jacobian: dx/dt is the
/// contact velocity, dx/ds comes from the variational equations); results are de-duplicated and
/// sorted by t. NLopt's global DIRECT-L search over s of the closest approach runs alongside:
/// its minimiser is refined the same way, and when nothing is found it gives the closest approach. Throws
/// std::invalid_argument (naming the field) for invalid problem or options.
ReachSummary Reach(const ReachProblem& problem, const ReachOptions& options = {});

}  // namespace PLATEBALL_EXPORT
