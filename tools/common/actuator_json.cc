#include "common/actuator_json.h"

#include <cmath>
#include <stdexcept>

#include "common/invalid_input.h"
#include "common/number_format.h"
#include "plateball/ball_state.h"
#include "plateball/plate_impulse.h"

namespace plateball::tools {
namespace {

constexpr const char* kNeedsPhysical = "needs ball.physical: a bare lambda fixes no masses";
constexpr const char* kNeedsDuration = "no pulse duration given (--pulse-duration or --pulse-error)";

// A finite number, else null (JSON has no infinity).
Json FiniteOrNull(double v) { return std::isfinite(v) ? Json(v) : Json(nullptr); }

void RequireNonNegative(const std::string& option, double v, const char* unit) {
  if (!(std::isfinite(v) && v >= 0))
    ThrowInvalidInput(option, FormatNumber(v), std::string("must be finite and >= 0 ") + unit);
}

Json PulseJson(const PulseForces& f, const PulseOptions& o) {
  return Json{{"pulse_duration", o.duration},
              {"mean_force", ToJson(f.mean_force)},
              {"top_normal_load", f.top_normal_load},
              {"bottom_normal_load", f.bottom_normal_load},
              {"top_tangential_force", f.top_tangential_force},
              {"bottom_tangential_force", f.bottom_tangential_force},
              {"torsional_torque", f.torsional_torque},
              {"sliding_friction_needed", FiniteOrNull(f.sliding_friction_needed)},
              {"torsional_friction_needed", f.torsional_friction_needed},
              {"slides", f.slides},
              {"spins", f.spins}};
}

// Too little friction for the pulse's force is invalid input naming the option and the impulse.
void ThrowIfSlips(const PulseForces& f, const PulseOptions& o, const std::string& where) {
  if (f.slides)
    ThrowInvalidInput(CommandLineField("--static-friction"),
                      FormatNumber(o.static_friction),
                      "impulse " + where + " would slip: its pulse of " + FormatNumber(o.duration) +
                          " s needs mu_s >= " + FormatNumber(f.sliding_friction_needed));
  if (f.spins)
    ThrowInvalidInput(CommandLineField("--torsional-friction"),
                      FormatNumber(o.torsional_friction),
                      "impulse " + where + " would spin: its pulse of " + FormatNumber(o.duration) +
                          " s needs ell >= " + FormatNumber(f.torsional_friction_needed) + " m");
}

}  // namespace

void ActuatorOptions::Add(CLI::App& app, CLI::Option* pulse_error) {
  duration_opt_ = app.add_option("--pulse-duration",
                                 duration_,
                                 "report each impulse's pulse of this duration (s): mean force and the friction it "
                                 "needs (with ball.physical; default: no pulse)");
  if (pulse_error) duration_opt_->excludes(pulse_error);
  CLI::Option* mu = app.add_option("--static-friction",
                                   static_friction_,
                                   "mu_s of both contacts: an impulse whose pulse needs more is invalid input");
  CLI::Option* ell = app.add_option("--torsional-friction",
                                    torsional_friction_,
                                    "ell (m) of both contacts (torque per normal force): an impulse whose pulse "
                                    "needs more is invalid input");
  CLI::Option* preload =
      app.add_option("--preload", preload_, "extra normal force (N) pressing the upper plate on the ball (default 0)");
  extras_ = {mu, ell, preload};
  pulse_error_opt_ = pulse_error;
}

ActuatorRequest ActuatorOptions::Request() const {
  ActuatorRequest r;
  RequireNonNegative("--static-friction", static_friction_, "");
  RequireNonNegative("--torsional-friction", torsional_friction_, "m");
  RequireNonNegative("--preload", preload_, "N");
  r.pulse.static_friction = static_friction_;
  r.pulse.torsional_friction = torsional_friction_;
  r.pulse.preload = preload_;
  const bool pulse = duration_opt_->count() > 0 || (pulse_error_opt_ && pulse_error_opt_->count() > 0);
  for (const CLI::Option* opt : extras_)
    if (opt->count() > 0 && !pulse)
      ThrowInvalidInput(CommandLineField(opt->get_name()),
                        opt->as<std::string>(),
                        std::string("needs --pulse-duration") + (pulse_error_opt_ ? " or --pulse-error" : ""));
  if (duration_opt_ && duration_opt_->count() > 0) {
    if (!(std::isfinite(duration_) && duration_ > 0))
      ThrowInvalidInput(CommandLineField("--pulse-duration"), FormatNumber(duration_), "must be finite and > 0 s");
    r.pulse.duration = duration_;
    r.has_pulse = true;
  }
  return r;
}

Json ActuatorJson(const Problem& problem,
                  const Eigen::Vector3d& z,
                  const Eigen::Vector3d& delta_omega,
                  const ActuatorRequest& request,
                  const std::string& where) {
  if (!problem.physical) {
    return Json{{"plate_impulse", nullptr},
                {"plate_velocity_jump", nullptr},
                {"top_contact_impulse", nullptr},
                {"bottom_contact_impulse", nullptr},
                {"torsional_impulse", nullptr},
                {"reason", kNeedsPhysical},
                {"pulse", nullptr},
                {"pulse_reason", kNeedsPhysical}};
  }
  // The records' delta_omega is horizontal up to rounding; the vertical part is not commanded.
  const Eigen::Vector3d dw(delta_omega.x(), delta_omega.y(), 0.0);
  const PlateImpulse imp = PlateImpulseFor(*problem.physical, z, dw);
  Json j{{"plate_impulse", ToJson(imp.plate)},
         {"plate_velocity_jump", ToJson(imp.plate_velocity_change)},
         {"top_contact_impulse", ToJson(imp.top_contact)},
         {"bottom_contact_impulse", ToJson(imp.bottom_contact)},
         {"torsional_impulse", imp.torsion},
         {"reason", nullptr},
         {"pulse", nullptr},
         {"pulse_reason", kNeedsDuration}};
  if (request.has_pulse) {
    const PulseForces f = PulseForcesFor(*problem.physical, imp, request.pulse);
    ThrowIfSlips(f, request.pulse, where);
    j["pulse"] = PulseJson(f, request.pulse);
    j["pulse_reason"] = nullptr;
  }
  return j;
}

void CheckPulseFlights(const std::vector<double>& times,
                       double final_time,
                       const ActuatorRequest& request,
                       const std::string& list) {
  if (!request.has_pulse) return;
  const double d = request.pulse.duration;
  for (std::size_t k = 0; k < times.size(); ++k) {
    const bool last = k + 1 == times.size();
    const double flight = (last ? final_time : times[k + 1]) - times[k];
    if (last && flight <= 0) continue;  // an impulse at the end (a stop)
    if (d > flight)
      ThrowInvalidInput(
          CommandLineField("--pulse-duration"),
          FormatNumber(d),
          "longer than the flight of " + FormatNumber(flight) + " s after impulse " + list + "[" + std::to_string(k) +
              "]: " + (last ? "its pulse would run past the end" : "its pulse would overlap the next one's"));
  }
}

Json ActuatorJsonFromAngles(const Problem& problem,
                            const AngleState& angles_before,
                            double mu_before,
                            const Eigen::Vector3d& delta_omega,
                            const ActuatorRequest& request,
                            const std::string& where) {
  // z does not depend on the energy; a ball at rest (mu 0) has the same axis.
  const Eigen::Vector3d z = StateFromAngles(angles_before, mu_before > 0 ? mu_before : 1.0, problem.model).z;
  return ActuatorJson(problem, z, delta_omega, request, where);
}

}  // namespace plateball::tools
