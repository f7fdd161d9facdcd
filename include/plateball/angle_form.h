// The paper's angle form of the free motion, eqs. (19)-(21), with the contact point from
// (25)-(26). It is singular at theta = 0, pi (the chart of (12)-(14) is), so the library
// integrates the chart-free form (free_motion.h); this form is kept as the independent check of
// it (docs/paper_notes.md, "Chart-free form and its check").
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "plateball/ball_model.h"
#include "plateball/ball_state.h"
#include "plateball/export.h"
#include "plateball/integration_options.h"

namespace plateball PLATEBALL_EXPORT {

/// How an angle-form integration ended.
enum class AngleFormStatus {
  kCompleted,    ///< every requested time was reached
  kReachedPole,  ///< |sin theta| fell below the threshold (or theta crossed 0 or pi): stopped
  kStepLimit,    ///< IntegrationOptions::max_steps exceeded
  kFailed,       ///< non-finite state or step-size underflow
};
/// The value's word as the tools write it in their JSON output and messages.
std::string ToString(AngleFormStatus status);

struct AngleFormOptions {
  IntegrationOptions integration;
  /// The integration stops with kReachedPole once |sin theta| < pole_threshold: near the poles
  /// the right-hand sides of (20)-(21) grow like 1/sin(theta) and the chart is useless there.
  double pole_threshold = 1e-6;
  /// Empty when valid, else a message naming the field and the value.
  std::string Validate() const;
};

/// One sample of the angle-form solution.
struct AngleFormSample {
  double t = 0.0;
  AngleState angles;  ///< as integrated (continuous in t, not canonicalised)
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
};

struct AngleFormResult {
  AngleFormStatus status = AngleFormStatus::kCompleted;
  /// Time at which the integration stopped (the last requested time when kCompleted).
  double t_reached = 0.0;
  /// One sample per requested time reached (a prefix of the requested times).
  std::vector<AngleFormSample> samples;
  /// The state at t_reached (useful when stopped early).
  AngleFormSample last;
  std::string message;
  long steps = 0;  ///< accepted steps
};

/// Right-hand side of (19)-(21) and (25)-(26): d/dt of (theta, phi, psi) and x at energy mu.
/// Requires sin(theta) != 0.
void AngleFormDerivative(
    const AngleState& s, double mu, const BallModel& model, AngleState* d_angles, Eigen::Vector2d* d_x);

/// Integrates (19)-(21) and (25)-(26) from (angles, x0) at t = 0, energy mu > 0, reporting the
/// given non-decreasing times >= 0. Never hangs: a pole (also a start on a pole) or the step
/// limit ends it with a status. Throws std::invalid_argument (naming the field) for non-finite
/// input, mu <= 0, negative or unordered times or invalid options.
AngleFormResult IntegrateAngleForm(const BallModel& model,
                                   const AngleState& angles,
                                   double mu,
                                   const Eigen::Vector2d& x0,
                                   const std::vector<double>& times,
                                   const AngleFormOptions& options = {});

}  // namespace PLATEBALL_EXPORT
