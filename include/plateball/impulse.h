// Impulses (section 2.1, "Modeling an impulse" and "Calculation of the instantaneous change of
// velocity of the upper plate").
#pragma once

#include <Eigen/Core>

#include "plateball/ball_model.h"
#include "plateball/ball_state.h"
#include "plateball/export.h"

namespace plateball PLATEBALL_EXPORT {

/// What an impulse does to the ball and what the upper plate must do to realise it.
struct Impulse {
  AngleState before;  ///< (theta, phi, psi) just before
  AngleState after;   ///< just after (theta, phi unchanged)
  double mu_before = 0.0;
  double mu_after = 0.0;
  Eigen::Vector3d delta_u = Eigen::Vector3d::Zero();      ///< jump of u, from (15)-(17)
  double delta_v0 = 0.0;                                  ///< jump of v0, from (18)
  Eigen::Vector3d delta_omega = Eigen::Vector3d::Zero();  ///< (delta v0) z - delta u
  /// Horizontal velocity change of the upper plate, 2 delta_omega x e3 (third component 0).
  Eigen::Vector3d plate_velocity_change = Eigen::Vector3d::Zero();
  BallState state_before;
  BallState state_after;
};

/// Energy-preserving impulse psi -> psi + delta_psi at fixed (theta, phi, mu).
/// Throws std::invalid_argument naming the field for non-finite input or mu <= 0.
Impulse EnergyPreservingImpulse(const AngleState& angles, double mu, double delta_psi, const BallModel& model);

/// Energy-changing impulse that scales |omega| by `factor` > 0 and keeps its direction: the angles
/// are unchanged, mu -> factor^2 mu, and the ball then rolls along the same path on the plate
/// (time rescaled by 1/factor), so the reorientations along it are unchanged.
Impulse EnergyChangingImpulse(const AngleState& angles, double mu, double factor, const BallModel& model);

/// Same as EnergyChangingImpulse with the target energy given: factor = sqrt(mu_after / mu).
Impulse ImpulseToEnergy(const AngleState& angles, double mu, double mu_after, const BallModel& model);

}  // namespace PLATEBALL_EXPORT
