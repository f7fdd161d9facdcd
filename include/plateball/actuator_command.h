// The force an actuator applies over a pulse of finite duration to give the upper plate the impulse of
// `PlateImpulseFor`, and the friction the two contacts need meanwhile (docs/rig.md). Units: those of
// `PhysicalParameters`, read as SI (kg, m, s) since gravity enters through the contacts' normal loads.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "plateball/ball_model.h"
#include "plateball/export.h"
#include "plateball/plate_impulse.h"

namespace plateball PLATEBALL_EXPORT {

/// The pulse and the contacts: what turns an impulse into a force and a friction demand.
struct PulseOptions {
  double duration = 1e-3;    ///< delta (s) > 0: the pulse's length; the mean force is J / delta
  double preload = 0.0;      ///< extra normal force (N) >= 0 pressing the upper plate on the ball
  double gravity = 9.80665;  ///< g (m/s^2) > 0 (standard gravity)
  /// mu_s >= 0, the static friction coefficient of both contacts; 0 means not given (nothing is
  /// checked, the least coefficient needed is still reported).
  double static_friction = 0.0;
  /// ell >= 0 (m), the torsional friction: a contact with normal load N resists a torque about the
  /// vertical up to ell N (MuJoCo's torsional coefficient). 0 means not given.
  double torsional_friction = 0.0;

  /// Empty when valid; otherwise "pulse.FIELD: value V: what is wrong".
  std::string Validate() const;
};

/// The mean forces of one pulse and the friction they need (forces in N, torques in N m).
struct PulseForces {
  Eigen::Vector3d mean_force = Eigen::Vector3d::Zero();  ///< J / delta on the upper plate
  double top_normal_load = 0.0;                          ///< M_plate g + preload
  double bottom_normal_load = 0.0;                       ///< top load + M_ball g
  double top_tangential_force = 0.0;                     ///< |top_contact| / delta
  double bottom_tangential_force = 0.0;                  ///< |bottom_contact| / delta
  double torsional_torque = 0.0;                         ///< |torsion| / delta, shared by the two contacts
  /// The least mu_s with which neither contact slides: max over contacts of tangential / normal.
  /// +inf when a contact carries a tangential force without a normal load (a massless, unloaded plate).
  double sliding_friction_needed = 0.0;
  /// The least ell (m) with which the ball does not spin: torque / (top + bottom normal load).
  double torsional_friction_needed = 0.0;
  bool slides = false;  ///< static_friction given and below sliding_friction_needed
  bool spins = false;   ///< torsional_friction given and below torsional_friction_needed
};

/// The mean forces of a pulse giving `impulse` over `options.duration`. Throws std::invalid_argument
/// naming the field for invalid parameters or options.
PulseForces PulseForcesFor(const PhysicalParameters& physical,
                           const PlateImpulse& impulse,
                           const PulseOptions& options);

/// Where a pulse lies relative to its impulse time t_k.
enum class PulseAlignment {
  kCentred,  ///< [t_k - delta/2, t_k + delta/2]
  kCausal,   ///< [t_k, t_k + delta]
};

/// "centred" or "causal".
const char* PulseAlignmentName(PulseAlignment alignment);

/// Empty when the pulses of duration `duration` at the increasing impulse times `times` fit in
/// [0, final_time] without overlapping; otherwise a message naming the first pulse at fault
/// ("impulses[K].time: value T: ..."), e.g. a pulse longer than its flight.
std::string CheckPulseSchedule(const std::vector<double>& times,
                               double final_time,
                               double duration,
                               PulseAlignment alignment);

}  // namespace PLATEBALL_EXPORT
