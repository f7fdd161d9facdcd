// The impulsive approximation of an isoparallel optimal path (section 2.2, Figure 7): the optimal
// path becomes a planned path of the path-following planner (impulse_planner.h, section 2.3).
#pragma once

#include <Eigen/Core>

#include "plateball/ball_model.h"
#include "plateball/ball_state.h"
#include "plateball/export.h"
#include "plateball/impulse_planner.h"
#include "plateball/isoparallel.h"
#include "plateball/path.h"

namespace plateball PLATEBALL_EXPORT {

/// The optimal path as an analytic planned path: p(tau) = x(tau), tau = arc length in
/// [0, length], with the closed-form tangent and x'' = kappa (e3 x x').
Path OptimalPath(const IsoparallelSolution& solution);

/// Initial angles of the ball: the start orientation fixes the symmetry axis z = A0 e3, so
/// theta = acos(z3) and phi = atan2(z2, z1) (phi = 0 at the poles: A0 = I gives theta = 0, which
/// the chart-free dynamics handles); psi is free (the problem's initial.psi).
AngleState InitialAnglesFromOrientation(const Eigen::Matrix3d& A0, double psi);

/// What is asked: the ball at the start of an optimal path and the number of impulses.
struct IsoparallelPlanProblem {
  BallModel model = BallModel::FromLambda(1.0);
  double psi = 0.0;                                  ///< initial psi (theta and phi come from A0 e3)
  double mu = 1.0;                                   ///< energy level, eq. (9), > 0
  Eigen::Matrix3d A0 = Eigen::Matrix3d::Identity();  ///< start orientation (a rotation)
  IsoparallelSolution solution;                      ///< the optimal path to follow
  int impulses = 12;                                 ///< segments of equal arc length, >= 1
};

/// The impulsive approximation with problem.impulses segments of equal arc length (impulses at
/// p(tau_k), k = 0..n-1). The ball starts at the solution's start with orientation A0 (its third
/// column defines theta, phi), the given psi and energy mu. Throws std::invalid_argument naming
/// the field for impulses < 1, invalid mu or psi, a non-rotation A0; an integration failure
/// (options.integration) is a status.
PlanSummary PlanOptimalPath(const IsoparallelPlanProblem& problem, const PlanOptions& options = {});

}  // namespace PLATEBALL_EXPORT
