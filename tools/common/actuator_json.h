// The actuator's command of one impulse, as every result with per-impulse records writes it
// (`plan`, `steer`, `isoparallel`, `isoparallel_solve --out`, `rig export`): the plate impulse J of
// PlateImpulseFor (Newton-Euler of ball and plate, docs/rig.md), the contacts' friction impulses,
// and for a pulse of a given duration its mean force and the friction it needs (PulseForcesFor).
// Units: SI (N s, N m s, m/s, N, N m, m) from the problem's ball.physical; without it (a bare
// lambda fixes no masses) the values are null and "reason" says why.
#pragma once

#include <CLI/CLI.hpp>
#include <Eigen/Core>
#include <string>
#include <vector>

#include "common/json_output.h"
#include "plateball/actuator_command.h"
#include "plateball/problem.h"

namespace plateball::tools {

/// What the command line asks of the actuator's records. duration 0: no pulse (the records hold
/// the impulses only). static_friction / torsional_friction 0: not given (nothing is checked).
struct ActuatorRequest {
  PulseOptions pulse;
  bool has_pulse = false;  ///< a pulse duration was given (pulse.duration)
};

/// What a command's JSON writer needs for the actuator's records of its impulses.
struct ActuatorContext {
  const Problem& problem;
  ActuatorRequest request;
  std::string prefix;  ///< the impulses' path in the document ("plan." in an isoparallel result)
};

/// --pulse-duration D, --static-friction MU, --torsional-friction ELL, --preload N of a subcommand.
class ActuatorOptions {
 public:
  /// Adds the options to `app`. The friction options and --preload need --pulse-duration or, with
  /// `pulse_error` (an option the subcommand adds itself, exclusive with --pulse-duration), that one.
  void Add(CLI::App& app, CLI::Option* pulse_error = nullptr);
  /// The request; throws std::invalid_argument "--OPTION: value V: what is wrong" for bad values.
  ActuatorRequest Request() const;

 private:
  double duration_ = 0.0, static_friction_ = 0.0, torsional_friction_ = 0.0, preload_ = 0.0;
  CLI::Option* duration_opt_ = nullptr;
  CLI::Option* pulse_error_opt_ = nullptr;
  std::vector<CLI::Option*> extras_;  ///< --static-friction, --torsional-friction, --preload
};

/// The record of one impulse that changes omega by `delta_omega` while the symmetry axis is `z`:
///   {"plate_impulse": J, "plate_velocity_jump": 2 r delta_omega x e3 (m/s),
///    "top_contact_impulse", "bottom_contact_impulse", "torsional_impulse",
///    "reason": null or why the impulses are null,
///    "pulse": null or {"pulse_duration", "mean_force", "top_normal_load", "bottom_normal_load",
///              "top_tangential_force", "bottom_tangential_force", "torsional_torque",
///              "sliding_friction_needed" (null: infinite, a contact without normal load),
///              "torsional_friction_needed", "slides", "spins"},
///    "pulse_reason": null or why "pulse" is null}.
/// With a friction coefficient given that the pulse's force exceeds, throws std::invalid_argument
/// "--static-friction: value MU: impulse `where` would slip: ..." (or --torsional-friction: spin).
Json ActuatorJson(const Problem& problem,
                  const Eigen::Vector3d& z,
                  const Eigen::Vector3d& delta_omega,
                  const ActuatorRequest& request,
                  const std::string& where);

/// With a pulse duration D: each impulse's pulse (D long around its time) must fit the flight to the
/// next impulse, the last one's the flight to `final_time` (an impulse at the end, a stop, is exempt).
/// Throws std::invalid_argument "--pulse-duration: value D: longer than the flight of F s after impulse
/// PREFIX[K]: ..." otherwise. `times` increase.
void CheckPulseFlights(const std::vector<double>& times,
                       double final_time,
                       const ActuatorRequest& request,
                       const std::string& list);

/// ActuatorJson of an impulse given by its angles and energy before it (z from StateFromAngles).
Json ActuatorJsonFromAngles(const Problem& problem,
                            const AngleState& angles_before,
                            double mu_before,
                            const Eigen::Vector3d& delta_omega,
                            const ActuatorRequest& request,
                            const std::string& where);

}  // namespace plateball::tools
