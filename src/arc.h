// Internal: free-motion arcs between impulses, integrated directly from (z, K) over a short time
// (no period is built). Used by the join (with s-sensitivities) and the planner (with the
// orientation).
#pragma once

#include <Eigen/Core>
#include <array>

#include "plateball/integration_options.h"

namespace plateball::internal {

/// Horizontal omega at (theta, phi, psi) and energy mu, and its derivative with respect to psi:
/// omega_1 = a cos(w) cos(phi) + b sin(w) sin(phi), omega_2 = a cos(w) sin(phi) - b sin(w) cos(phi)
/// with w = phi - psi (section 2.1, the formulas before (25)). The same numbers as
/// PhaseFromAngles (omega = v0 z - u with (12)-(18)).
void OmegaFromAngles(double theta, double phi, double psi, double mu, double lambda, Eigen::Vector2d* omega,
                     Eigen::Vector2d* domega_dpsi);

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

}  // namespace plateball::internal
