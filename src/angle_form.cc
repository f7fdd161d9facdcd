#include "plateball/angle_form.h"

#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "check.h"
#include "dynamics.h"

namespace plateball {
namespace {

using AngleY = std::array<double, 5>;  // theta, phi, psi, x1, x2

struct AngleRhs {
  double lambda;
  double b;  // sqrt(mu)
  void operator()(const AngleY& y, AngleY& dy, double /*t*/) const {
    const double st = std::sin(y[0]), ct = std::cos(y[0]);
    const double sp = std::sin(y[1]), cp = std::cos(y[1]);
    const double w = y[1] - y[2];
    const double sw = std::sin(w), cw = std::cos(w);
    const double a = b / std::sqrt(lambda * st * st + ct * ct);
    const double cot = ct / st;
    dy[0] = -b * sw;                     // (19)
    dy[1] = -a * cot * cw;               // (20)
    dy[2] = (b - a) * cot * cw;          // (21)
    dy[3] = a * cw * sp - b * sw * cp;   // (25)
    dy[4] = -a * cw * cp - b * sw * sp;  // (26)
  }
};

AngleFormSample MakeSample(double t, const AngleY& y) {
  AngleFormSample s;
  s.t = t;
  s.angles = {y[0], y[1], y[2]};
  s.x = {y[3], y[4]};
  return s;
}

}  // namespace

std::string ToString(AngleFormStatus status) {
  switch (status) {
    case AngleFormStatus::kCompleted:
      return "completed";
    case AngleFormStatus::kReachedPole:
      return "reached_pole";
    case AngleFormStatus::kStepLimit:
      return "step_limit";
    case AngleFormStatus::kFailed:
      return "failed";
  }
  return "unknown";
}

std::string AngleFormOptions::Validate() const {
  const std::string err = integration.Validate();
  if (!err.empty()) return err;
  if (!(std::isfinite(pole_threshold) && pole_threshold > 0 && pole_threshold < 1))
    return internal::InvalidValueMessage("pole_threshold", pole_threshold, "must be in (0, 1)");
  return {};
}

void AngleFormDerivative(
    const AngleState& s, double mu, const BallModel& model, AngleState* d_angles, Eigen::Vector2d* d_x) {
  internal::RequirePositive("mu", mu);
  if (std::sin(s.theta) == 0.0)
    internal::ThrowInvalid("theta", s.theta, "the angle form (19)-(21) is singular at the poles");
  const AngleRhs rhs{model.lambda(), std::sqrt(mu)};
  const AngleY y{s.theta, s.phi, s.psi, 0.0, 0.0};
  AngleY dy{};
  rhs(y, dy, 0.0);
  if (d_angles) *d_angles = {dy[0], dy[1], dy[2]};
  if (d_x) *d_x = {dy[3], dy[4]};
}

AngleFormResult IntegrateAngleForm(const BallModel& model,
                                   const AngleState& angles,
                                   double mu,
                                   const Eigen::Vector2d& x0,
                                   const std::vector<double>& times,
                                   const AngleFormOptions& options) {
  internal::ThrowIfInvalid(options.Validate());
  internal::RequireFinite("theta", angles.theta);
  internal::RequireFinite("phi", angles.phi);
  internal::RequireFinite("psi", angles.psi);
  internal::RequirePositive("mu", mu);
  internal::RequireFinite("x0", x0);
  for (std::size_t i = 0; i < times.size(); ++i) {
    const std::string field = "times[" + std::to_string(i) + "]";
    internal::RequireFinite(field, times[i]);
    if (times[i] < 0) internal::ThrowInvalid(field, times[i], "times must be >= 0");
    if (i > 0 && times[i] < times[i - 1]) internal::ThrowInvalid(field, times[i], "times must be non-decreasing");
  }

  const AngleRhs rhs{model.lambda(), std::sqrt(mu)};
  AngleY y{angles.theta, angles.phi, angles.psi, x0.x(), x0.y()};
  AngleFormResult result;
  double t = 0.0;
  result.last = MakeSample(t, y);
  auto at_pole = [&](double s) { return std::abs(s) < options.pole_threshold; };
  double sin_prev = std::sin(y[0]);
  std::size_t next = 0;
  // Times equal to 0 are reported even when the start is on a pole (the chart gives the state).
  while (next < times.size() && times[next] == 0.0) result.samples.push_back(MakeSample(0.0, y)), ++next;
  if (at_pole(sin_prev)) {
    result.status = AngleFormStatus::kReachedPole;
    result.message = "start on a pole: |sin theta| = " + std::to_string(std::abs(sin_prev)) + " < pole_threshold";
    return result;
  }
  // |theta'| = b |sin w| <= b and the distance from theta to the nearest pole is >= |sin theta|,
  // so a chunk of length 0.5 |sin theta| / b cannot reach a pole: the poles are approached
  // geometrically (a few dozen chunks from O(1) to the threshold) and never stepped over.
  double dt = 0.01 / rhs.b;
  long chunks = 0;
  double t_accepted = t;  // time of the last accepted step (y is in place there when a step throws)
  IntegrationOptions chunk_options = options.integration;
  try {
    for (; next < times.size(); ++next) {
      const double target = times[next];
      while (t < target && result.status == AngleFormStatus::kCompleted) {
        const double sn = std::sin(y[0]);
        if (at_pole(sn) || (sn > 0) != (sin_prev > 0)) {
          result.status = AngleFormStatus::kReachedPole;
          result.message =
              "|sin theta| = " + std::to_string(std::abs(sn)) + " < pole_threshold at t = " + std::to_string(t);
          break;
        }
        sin_prev = sn;
        // One budget for the whole integration: chunks plus accepted steps <= max_steps.
        chunk_options.max_steps = options.integration.max_steps - result.steps - ++chunks;
        if (chunk_options.max_steps < 1)
          throw internal::StepLimitError(
              "angle form exceeded max_steps = " + std::to_string(options.integration.max_steps) +
              " at t = " + std::to_string(t));
        const double t_end = std::min(target, t + 0.5 * std::abs(sn) / rhs.b);
        internal::IntegrateAdaptive(rhs, y, t, t_end, dt, chunk_options, [&](double tt, const AngleY&) {
          ++result.steps;
          if (tt < t_end) dt = tt - t_accepted;  // the last step is clipped to t_end: keep the natural one
          t_accepted = tt;
        });
        t = t_end;
      }
      if (result.status != AngleFormStatus::kCompleted) break;
      result.samples.push_back(MakeSample(target, y));
    }
  } catch (const internal::StepLimitError& e) {
    result.status = AngleFormStatus::kStepLimit;
    result.message = e.what();
    t = t_accepted;
  } catch (const std::runtime_error& e) {
    result.status = AngleFormStatus::kFailed;
    result.message = e.what();
    t = t_accepted;
  }
  result.t_reached = t;
  result.last = MakeSample(t, y);
  return result;
}

}  // namespace plateball
