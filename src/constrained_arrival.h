// Internal: exact arrival under the limits of a rig (rig_limits.h), solved at mu = 1.
//
// The unknowns are those of exact arrival, u = (s_0..s_{n-1}, t_0..t_{n-1}); the five arrival
// conditions stay equalities and the limits become inequalities g(u) <= 0:
//   - plate, obstacles, stroke: at the contact point of every sample node, the chain with each arc
//     cut into `samples_per_arc` sub-arcs joined by zero impulses (the same motion), so that the
//     chain's exact Jacobian (exact_chain.h) differentiates every sampled point; the bounds are
//     tightened by `sampling_margin` so that the denser independent check holds between samples;
//   - the plate velocity change and |J| of every impulse, differentiated through the chain's dz, dK;
//   - the shortest interval between impulses as bounds on the flight times.
// The method is NLopt's SLSQP (sequential quadratic programming: equality and inequality
// constraints with exact gradients; Ceres has bounds only), from the free optimum, which for the
// deviation objective first takes four Gauss-Newton SQP steps (the QP of the deviation's
// Gauss-Newton model under the linearised constraints, dense_qp.h, with a line search on the L1
// merit) so that SLSQP starts near the solution and near feasibility; Newton steps on
// the arrival conditions and the violated inequalities finish a point an SLSQP run left just off
// (round-off), and a dense look adds each flight's worst missed point as a node for another run
// (an exchange method), unless the run ended far outside, which more nodes cannot mend. The impulse
// times on a tick grid are then fixed to the nearest admissible multiples and the other unknowns
// (every s_k and the last flight time) absorb the grid in a second solve. The arrival is finished
// by chord steps at the rollout tolerance. When no arrival meets the limits, the closest feasible
// arrival (least |arrival residual|^2 under the inequalities) is returned with the limits active there.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "exact_chain.h"
#include "plateball/exact_arrival.h"
#include "plateball/rig_limits.h"

namespace plateball::internal {

struct ConstrainedSetup {
  double lambda = 1.0;
  int n = 0;
  ChainNode start;
  Eigen::Vector2d x1 = Eigen::Vector2d::Zero();
  Eigen::Matrix3d A1 = Eigen::Matrix3d::Identity();
  std::vector<Eigen::Vector2d> planned;  ///< the reference's pass points p(tau_k), k = 0..n
  RigLimits limits;                      ///< in the time scale of mu = 1
  std::optional<PhysicalParameters> physical;
  ArrivalObjective objective = ArrivalObjective::kDeviation;
  bool start_at_rest = false;
  bool stop_at_goal = false;
  IntegrationOptions integration;           ///< the final rollouts (chord steps)
  IntegrationOptions jacobian_integration;  ///< the evaluations (SQP steps and SLSQP)
  double position_tolerance = 1e-12;
  double orientation_tolerance = 1e-10;
  int samples_per_arc = 4;
  double sampling_margin = 2e-3;  ///< ball radii: the sag of the path between samples
  int max_evaluations = 200;
  /// When no arrival meets the limits, search the closest feasible arrival (else the outcome is
  /// the solver's end point, `feasible` as found there).
  bool closest_arrival = true;
};

struct ConstrainedOutcome {
  Eigen::VectorXd u;
  bool arrived = false;
  bool feasible = false;
  std::vector<std::string> active;
  std::vector<std::string> blocking;
  std::vector<long long> ticks;  ///< tick index of impulse k (and of the stop), when the rig has a tick
  int evaluations = 0;
  int rollouts = 0;
};

/// True when u meets every limit but the tick at the sample nodes with the sampling margin and at
/// the dense points between them.
bool MeetsLimits(const ConstrainedSetup& setup, const Eigen::VectorXd& u);

/// True when u meets every limit (MeetsLimits), the objective is the deviation and there is no
/// tick: the free optimum is then the answer, unchanged.
bool LimitsAreSlack(const ConstrainedSetup& setup, const Eigen::VectorXd& u);

/// The limits active at u (within 1e-6 of their bound at the sample nodes, "min_interval" for a
/// flight at its lower bound), each named once.
std::vector<std::string> ActiveLimits(const ConstrainedSetup& setup, const Eigen::VectorXd& u);

/// Throws std::invalid_argument naming the field when the limits are invalid, an impulse bound
/// lacks the physical parameters, or the start x0 or the goal x1 breaks the plate, an obstacle or
/// the stroke.
void ValidateRigProblem(const RigLimits& limits,
                        const std::optional<PhysicalParameters>& physical,
                        const Eigen::Vector2d& x0,
                        const Eigen::Vector2d& x1);

/// Puts the impulse times exactly on the grid (t_impulse = tick index x tick, the flights their
/// differences) when the impulses carry tick indices; returns the total time (unchanged otherwise).
double PlaceOnGrid(double tick,
                   std::vector<ExactImpulse>* impulses,
                   std::optional<ExactImpulse>* stop,
                   double total_time);

/// The constrained solve from u0 (the free optimum). Throws std::runtime_error when an
/// integration fails and std::invalid_argument when the grid leaves fewer than five unknowns.
ConstrainedOutcome SolveConstrainedArrival(const ConstrainedSetup& setup, const Eigen::VectorXd& u0);

}  // namespace plateball::internal
