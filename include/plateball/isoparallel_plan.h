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

/// The impulsive approximation with `impulses` segments of equal arc length (impulses at
/// p(tau_k), k = 0..n-1). The ball starts at the solution's start with orientation A0 (its third
/// column defines theta, phi), the given psi and energy mu. Throws std::invalid_argument naming
/// the field for impulses < 1, invalid mu or psi, a non-rotation A0.
PlanSummary PlanOptimalPath(const BallModel& model, double psi, double mu, const Eigen::Matrix3d& A0,
                            const IsoparallelSolution& solution, int impulses, const PlanOptions& options = {});

}  // namespace plateball
