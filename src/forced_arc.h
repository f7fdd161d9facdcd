// Internal: the motion while K changes at a constant rate (a pulse of constant plate force,
// include/plateball/finite_pulse.h), with the orientation; t may be negative (flying back).
#pragma once

#include <Eigen/Core>

#include "plateball/integration_options.h"

namespace plateball::internal {

struct ForcedArcEnd {
  Eigen::Vector3d z;                                  ///< axis at t
  Eigen::Vector2d dx = Eigen::Vector2d::Zero();       ///< x(t) - x(0)
  Eigen::Matrix3d phi = Eigen::Matrix3d::Identity();  ///< A(t) A(0)^-1
  Eigen::Vector2d k = Eigen::Vector2d::Zero();        ///< K(t) = K(0) + k_rate t
};

/// z' = omega x z, x' = omega x e3, A' = hat(omega) A, K' = k_rate, omega_h from (z, K).
ForcedArcEnd IntegrateForcedArc(double lambda,
                                const Eigen::Vector3d& z0,
                                const Eigen::Vector2d& k0,
                                const Eigen::Vector2d& k_rate,
                                double t,
                                const IntegrationOptions& options);

}  // namespace plateball::internal
