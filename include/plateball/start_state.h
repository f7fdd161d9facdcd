// The ball at the start of a motion, as every problem that starts a ball asks for it: the ball
// model, the angles (theta, phi, psi), the energy mu, the orientation A0 and the contact point
// x0. The problem structs derive from it (ExactArrivalProblem, FewestImpulsesProblem, Problem;
// PlanProblem from StartMotion, its start point being its path's start), so the fields, their
// defaults and their documentation are written here once.
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "plateball/ball_model.h"
#include "plateball/ball_state.h"
#include "plateball/export.h"

namespace plateball PLATEBALL_EXPORT {

/// The ball at the start, without its contact point: model, angles, energy and orientation.
struct StartMotion {
  BallModel model = BallModel::FromLambda(1.0);
  /// (theta, phi, psi) at the start; psi is the reference of delta psi_0 when the ball starts from rest.
  AngleState initial{M_PI / 3, 0.4, 0.1};
  double mu = 1.0;  ///< energy, eq. (9), > 0 (kept by every energy-preserving impulse)
  /// Start orientation R_WB. The solvers rotate it minimally so that A0 e3 = z, the axis of the
  /// angles `initial` (AlignOrientationToAxis, FreeMotion::FromAngles).
  Eigen::Matrix3d A0 = Eigen::Matrix3d::Identity();
};

/// The ball at the start with its contact point x0 on the plate.
struct StartState : StartMotion {
  Eigen::Vector2d x0 = Eigen::Vector2d::Zero();  ///< start contact point p_WC
};

}  // namespace PLATEBALL_EXPORT
