#include "plateball/actuator_command.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "check.h"

namespace plateball {
namespace {
// Tangential over normal force, +inf for a tangential force without a normal load.
double Ratio(double tangential, double normal) {
  if (tangential == 0.0) return 0.0;
  return normal > 0.0 ? tangential / normal : std::numeric_limits<double>::infinity();
}

std::string Field(std::size_t k) { return "impulses[" + std::to_string(k) + "].time"; }
}  // namespace

std::string PulseOptions::Validate() const {
  if (!(std::isfinite(duration) && duration > 0))
    return internal::InvalidValueMessage("pulse.duration", duration, "must be finite and > 0");
  if (!(std::isfinite(preload) && preload >= 0))
    return internal::InvalidValueMessage("pulse.preload", preload, "must be finite and >= 0");
  if (!(std::isfinite(gravity) && gravity > 0))
    return internal::InvalidValueMessage("pulse.gravity", gravity, "must be finite and > 0");
  if (!(std::isfinite(static_friction) && static_friction >= 0))
    return internal::InvalidValueMessage("pulse.static_friction", static_friction, "must be finite and >= 0");
  if (!(std::isfinite(torsional_friction) && torsional_friction >= 0))
    return internal::InvalidValueMessage("pulse.torsional_friction", torsional_friction, "must be finite and >= 0");
  return {};
}

PulseForces PulseForcesFor(const PhysicalParameters& p, const PlateImpulse& impulse, const PulseOptions& o) {
  internal::ThrowIfInvalid(p.Validate());
  internal::ThrowIfInvalid(o.Validate());
  PulseForces f;
  f.mean_force = impulse.plate / o.duration;
  f.top_normal_load = p.plate_mass * o.gravity + o.preload;
  f.bottom_normal_load = f.top_normal_load + p.ball_mass * o.gravity;
  f.top_tangential_force = impulse.top_contact.norm() / o.duration;
  f.bottom_tangential_force = impulse.bottom_contact.norm() / o.duration;
  f.torsional_torque = std::abs(impulse.torsion) / o.duration;
  f.sliding_friction_needed = std::max(Ratio(f.top_tangential_force, f.top_normal_load),
                                       Ratio(f.bottom_tangential_force, f.bottom_normal_load));
  f.torsional_friction_needed = Ratio(f.torsional_torque, f.top_normal_load + f.bottom_normal_load);
  f.slides = o.static_friction > 0 && o.static_friction < f.sliding_friction_needed;
  f.spins = o.torsional_friction > 0 && o.torsional_friction < f.torsional_friction_needed;
  return f;
}

const char* PulseAlignmentName(PulseAlignment alignment) {
  return alignment == PulseAlignment::kCentred ? "centred" : "causal";
}

std::string CheckPulseSchedule(const std::vector<double>& times,
                               double final_time,
                               double duration,
                               PulseAlignment alignment) {
  if (!(std::isfinite(duration) && duration > 0))
    return internal::InvalidValueMessage("pulse.duration", duration, "must be finite and > 0");
  const double before = alignment == PulseAlignment::kCentred ? 0.5 * duration : 0.0;
  const double after = duration - before;
  for (std::size_t k = 0; k < times.size(); ++k) {
    const double t = times[k];
    if (!std::isfinite(t)) return internal::InvalidValueMessage(Field(k), t, "must be finite");
    if (t - before < 0)
      return internal::InvalidValueMessage(
          Field(k), t, "its pulse of duration " + internal::FormatNumber(duration) + " starts before time 0");
    if (t + after > final_time)
      return internal::InvalidValueMessage(Field(k),
                                           t,
                                           "its pulse of duration " + internal::FormatNumber(duration) +
                                               " ends after the final time " + internal::FormatNumber(final_time));
    if (k > 0 && t - times[k - 1] < duration)
      return internal::InvalidValueMessage(Field(k),
                                           t,
                                           "its pulse of duration " + internal::FormatNumber(duration) +
                                               " overlaps the previous one: the flight " +
                                               internal::FormatNumber(t - times[k - 1]) + " is shorter than the pulse");
  }
  return {};
}

}  // namespace plateball
