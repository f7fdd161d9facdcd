// Error models of a real plate-ball rig: what goes wrong when a plan of section 2.3 is
// executed. The paper's conclusion expects such errors to slow the convergence of Theorem 2.6
// from O(1/n^2) to about O(1/n); execution.h and monte_carlo.h measure it. Every magnitude is
// the standard deviation of a seeded normal draw (energy_loss: a fixed fraction); zero means
// "no error of this kind", and the all-zero model reproduces the deterministic plan.
#pragma once

#include <string>

#include "plateball/export.h"

namespace plateball PLATEBALL_EXPORT {

struct ErrorModel {
  /// Relative error of the magnitude of every plate velocity change: |dv| -> |dv| (1 + e), e ~ N(0, s^2).
  double impulse_magnitude = 0.0;
  /// Direction error of every plate velocity change (rad): dv turned about e3 by a ~ N(0, s^2).
  double impulse_angle = 0.0;
  /// Timing jitter of every impulse after the first (normalised time): fired at t + j, j ~ N(0, s^2).
  double timing = 0.0;
  /// Fraction of the ball's energy lost at every impulse (a restitution sqrt(1 - energy_loss) of
  /// the speed |omega|); deterministic.
  double energy_loss = 0.0;
  /// Relative error of the ball's lambda, drawn once per trial: lambda (1 + e), e ~ N(0, s^2); the
  /// controller keeps planning with the nominal lambda.
  double lambda = 0.0;
  /// Observation noise of the state the feedback uses: contact point (per coordinate, length),
  /// theta, phi, psi (rad), orientation (a rotation vector with this deviation per component) and
  /// mu (relative); open loop observes nothing.
  double observation = 0.0;

  // Ranges (README, "Limits"): beyond them the ball leaves the local join's reach within a step.
  /// Duration (s, normalised time) of every impulse's pulse: a constant plate force over
  /// [t_k - d/2, t_k + d/2] (or [t_k, t_k + d] with pulse_causal = 1) instead of an instant jump
  /// (docs/rig.md, "Finite pulses"); deterministic. 0 is the ideal impulse.
  double pulse_duration = 0.0;
  /// 1: the pulses start at the impulse times (causal); 0: they are centred on them.
  double pulse_causal = 0.0;

  static constexpr double kMaxImpulseMagnitude = 0.5;
  static constexpr double kMaxImpulseAngle = 0.5;
  static constexpr double kMaxTiming = 0.1;
  static constexpr double kMaxEnergyLoss = 0.5;
  static constexpr double kMaxLambda = 0.1;
  static constexpr double kMaxObservation = 0.1;
  static constexpr double kMaxPulseDuration = 10.0;

  /// Empty when every magnitude is finite and in [0, its maximum] and pulse_causal is 0 or 1; else
  /// names field and value.
  std::string Validate() const;
  /// True when every magnitude is 0 (the nominal execution, no errors).
  bool IsZero() const;
};

/// "none", or the non-zero magnitudes as KEY=VALUE joined by commas, in field order
/// (e.g. "impulse_magnitude=0.001,timing=0.0001"); ParseErrorModel reads it back.
std::string ToString(const ErrorModel& model);

/// Reads "KEY=VALUE[,KEY=VALUE...]" (keys: the field names above; "none" or "" is the zero model).
/// Throws std::invalid_argument naming the key (ErrorModelKeyField) and the value for an unknown
/// key, a repeated key, a value that is not a number or one out of its range.
ErrorModel ParseErrorModel(const std::string& text, const std::string& field = "noise");

/// The name of KEY of the error model given as `field`, as the user spelled it: "noise.timing" for
/// a field, "--noise timing" for a command-line option's KEY=VALUE list (`field` ending in a word
/// that starts with "--", e.g. "command line: --noise").
std::string ErrorModelKeyField(const std::string& field, const std::string& key);

}  // namespace PLATEBALL_EXPORT
