// Finite pulses: the forced motion of the ball between the plates while the actuator pushes the upper
// plate with a horizontal force F(t) (docs/rig.md). Rolling at both contacts and omega_3 = 0 hold as in
// the free motion. Units: those of `PhysicalParameters` (SI), time in s, omega in rad/s.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "plateball/ball_model.h"
#include "plateball/export.h"
#include "plateball/integration_options.h"

namespace plateball PLATEBALL_EXPORT {

/// dK/dt under the horizontal plate force F, for the free motion's conserved vector
/// K = omega_h + (lambda - 1) v0 z_h = L_h / (I1 + M r^2), M = M_ball + 4 M_plate, with L the angular
/// momentum of ball and plate about the lower contact. Its rate is the moment of F there:
///   dL_h/dt = 2 r e3 x F,   so   dK/dt = 2 r e3 x F / (I1 + M r^2).
/// An impulse J then changes K by 2 r e3 x J / (I1 + M r^2). Only F's horizontal part counts.
Eigen::Vector2d MomentumRate(const PhysicalParameters& physical, const Eigen::Vector3d& force);

/// A constant force impulse / duration on the upper plate over [start, start + duration].
struct Pulse {
  double start = 0.0;
  double duration = 0.0;                              ///< > 0
  Eigen::Vector3d impulse = Eigen::Vector3d::Zero();  ///< J, e.g. PlateImpulseFor(...).plate
};

/// The state of the forced motion: the symmetry axis z, the contact point x, the vector K.
struct PulsedState {
  Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  Eigen::Vector2d k = Eigen::Vector2d::Zero();
};

/// Integrates z' = omega x z, x' = omega x e3, K' = sum of the active pulses' MomentumRate from t0 to t1
/// (omega_h from (z, K) as in the free motion), segment by segment so that no step straddles a pulse's
/// edge. Pulses must lie in [t0, t1], be sorted and not overlap. Throws std::invalid_argument naming
/// the field ("pulses[K].start: value V: ...") for bad input, std::runtime_error when the integration
/// fails (step limit).
PulsedState RunPulsed(const PhysicalParameters& physical,
                      const PulsedState& initial,
                      double t0,
                      double t1,
                      const std::vector<Pulse>& pulses,
                      const IntegrationOptions& options = {});

}  // namespace PLATEBALL_EXPORT
