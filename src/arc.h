// Internal: free-motion arcs between impulses, integrated directly from (z, K) over a short time
// (no period is built), and the start data of an arc after an impulse. Used by the join (with
// s-sensitivities), the reach and the planner (with the orientation).
#pragma once

#include <Eigen/Core>
#include <array>

#include "kinematics.h"
#include "plateball/ball_state.h"
#include "plateball/integration_options.h"

namespace plateball::internal {

/// Everything the free motion after the impulse psi -> psi + s depends on: the axis z0 (unchanged
/// by the impulse), the conserved vector K(s) (kinematics.h) and dK/ds (exact, from ceres::Jet).
struct ReachDirection {
  double s = 0.0;
  Eigen::Vector3d z0 = Eigen::Vector3d::UnitZ();
  Eigen::Vector2d k = Eigen::Vector2d::Zero();
  Eigen::Vector2d dk_ds = Eigen::Vector2d::Zero();
};
/// What does not depend on the impulse s: the axis z0, the velocity ellipse (a, b) and the trig
/// of phi. Built once per start so that each direction costs one sine and one cosine.
struct ImpulseBasis {
  Eigen::Vector3d z0 = Eigen::Vector3d::UnitZ();
  double a = 0.0, b = 0.0, cos_phi = 1.0, sin_phi = 0.0, phi = 0.0, psi = 0.0, lambda = 1.0;
};
ImpulseBasis MakeImpulseBasis(const AngleState& start, double mu, double lambda);
/// The direction of the impulse s: K(s) = K(omega_h(theta, phi, psi + s)) and dK/ds.
ReachDirection DirectionFor(const ImpulseBasis& basis, double s);
/// The same with cos w, sin w of w = phi - (psi + s) already at hand (no sine computed).
ReachDirection DirectionFromTrig(const ImpulseBasis& basis, double s, double cos_w, double sin_w);
/// The same from the angles (angles already reduced).
ReachDirection DirectionFor(const AngleState& start, double mu, double lambda, double s);

/// Result of integrating one arc of the free motion over [0, t] from the axis z0 and momentum K.
struct ArcEnd {
  Eigen::Vector3d z;                              ///< axis at t (renormalised)
  Eigen::Vector2d dx = Eigen::Vector2d::Zero();   ///< x(t) - x(0)
  Eigen::Matrix3d phi = Eigen::Matrix3d::Identity();  ///< A(t) A(0)^-1 (when asked)
  /// max |x'| over the arc: at the accepted steps plus the largest change between neighbours.
  double max_speed = 0.0;
  /// max |x''| = |omega_h'| over the arc, estimated the same way.
  double max_acceleration = 0.0;
  int steps = 0;
};

/// Integrates (z, x, Phi) over [0, t] (t >= 0) with dopri5. Throws std::runtime_error on failure.
ArcEnd IntegrateArc(double lambda, const Eigen::Vector3d& z0, const Eigen::Vector2d& k, double t,
                    const IntegrationOptions& options);

/// x'' = d/dt (omega_2, -omega_1) at (z, K): the contact-point acceleration.
Eigen::Vector2d ContactAcceleration(double lambda, const Eigen::Vector3d& z, const Eigen::Vector2d& k);
/// omega_h (= (-x'_2, x'_1)) and x'' at (z[3], k[2]) together, x'' by differentiating OmegaFromZK by
/// hand along z' = omega x z (one evaluation of omega_h for the speed and the acceleration).
void ContactVelocityAndAcceleration(double lambda, const double* z, const double* k, double* w, double* acc);

}  // namespace plateball::internal
