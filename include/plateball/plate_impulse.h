// What the upper plate's actuator must give for an impulse of the ball: Newton-Euler of the ball and
// the upper plate as two bodies under the rolling constraints (docs/paper_notes.md, "The upper plate's
// effective mass" and "The actuator's impulse").
#pragma once

#include <Eigen/Core>

#include "plateball/ball_model.h"
#include "plateball/export.h"

namespace plateball PLATEBALL_EXPORT {

/// The impulses of one instantaneous change delta_omega of the ball's angular velocity, in the units of
/// `PhysicalParameters` (N s and N m s for SI input). Horizontal vectors have third component 0.
struct PlateImpulse {
  /// J: the impulse the actuator gives the upper plate. It depends on the ball's orientation (through
  /// its inertia about z), not only on the plate's velocity change.
  Eigen::Vector3d plate = Eigen::Vector3d::Zero();
  /// The horizontal impulse the upper plate gives the ball at the top contact (friction).
  Eigen::Vector3d top_contact = Eigen::Vector3d::Zero();
  /// The horizontal impulse the lower plate gives the ball at the bottom contact (friction).
  Eigen::Vector3d bottom_contact = Eigen::Vector3d::Zero();
  /// The vertical angular impulse the contacts give the ball so that it does not spin (torsional
  /// friction, shared between the two contacts in a proportion the rigid model leaves open).
  double torsion = 0.0;
  /// The plate's velocity change 2 r delta_omega x e3.
  Eigen::Vector3d plate_velocity_change = Eigen::Vector3d::Zero();
};

/// The impulses that change the angular velocity by `delta_omega` (horizontal: no spin before or after)
/// while the symmetry axis is `z` (a unit vector). Throws std::invalid_argument naming the field for
/// invalid parameters, a z that is not a unit vector, or a delta_omega that is not finite and horizontal.
///
/// The angular impulse about the lower contact (where the lower plate's impulse has no moment) and the
/// plate's momentum give, with Q = top_contact:
///   2 r e3 x Q = [I delta_omega]_h + M_ball r^2 delta_omega,
///   J = Q + M_plate 2 r delta_omega x e3,   G = M_ball r delta_omega x e3 - Q,
///   torsion = [I delta_omega]_3 = (I3 - I1) (z . delta_omega) z_3,   I = I1 + (I3 - I1) z z^T.
PlateImpulse PlateImpulseFor(const PhysicalParameters& physical,
                             const Eigen::Vector3d& z,
                             const Eigen::Vector3d& delta_omega);

}  // namespace PLATEBALL_EXPORT
