#include "plateball/finite_pulse.h"

#include <array>
#include <string>

#include "check.h"
#include "dynamics.h"
#include "kinematics.h"

namespace plateball {
namespace {
using State = std::array<double, 7>;  // z[3], x[2], K[2]

struct ForcedRhs {
  double lambda;
  double rate[2];  // K' over the segment
  void operator()(const State& y, State& dy, double /*t*/) const {
    double w[2];
    internal::OmegaFromZK(y.data(), y.data() + 5, lambda, w);
    internal::ZxRhs(y.data(), w, dy.data(), dy.data() + 3);
    dy[5] = rate[0];
    dy[6] = rate[1];
  }
};

void CheckPulses(const std::vector<Pulse>& pulses, double t0, double t1) {
  double previous_end = t0;
  for (std::size_t i = 0; i < pulses.size(); ++i) {
    const std::string field = "pulses[" + std::to_string(i) + "]";
    const Pulse& p = pulses[i];
    internal::RequirePositive(field + ".duration", p.duration);
    internal::RequireFinite(field + ".impulse", p.impulse);
    if (!(p.start >= previous_end))
      internal::ThrowInvalid(field + ".start", p.start,
                             "must be >= " + internal::FormatNumber(previous_end) +
                                 " (the start time or the previous pulse's end: pulses may not overlap)");
    previous_end = p.start + p.duration;
    if (previous_end > t1)
      internal::ThrowInvalid(field + ".start", p.start, "the pulse ends after the final time " + internal::FormatNumber(t1));
  }
}

void Segment(ForcedRhs rhs, const Eigen::Vector2d& rate, State& y, double from, double to,
             const IntegrationOptions& options) {
  rhs.rate[0] = rate.x();
  rhs.rate[1] = rate.y();
  if (to > from) internal::IntegrateAdaptive(rhs, y, from, to, 0.01 * (to - from), options);
}
}  // namespace

Eigen::Vector2d MomentumRate(const PhysicalParameters& p, const Eigen::Vector3d& force) {
  internal::ThrowIfInvalid(p.Validate());
  internal::RequireFinite(std::string("force"), force);
  // 2 r e3 x F = 2 r (-F_y, F_x, 0).
  return 2.0 * p.radius * Eigen::Vector2d(-force.y(), force.x()) /
         (p.inertia_1 + p.EffectiveMass() * p.radius * p.radius);
}

PulsedState RunPulsed(const PhysicalParameters& p, const PulsedState& initial, double t0, double t1,
                      const std::vector<Pulse>& pulses, const IntegrationOptions& options) {
  internal::ThrowIfInvalid(p.Validate());
  internal::ThrowIfInvalid(options.Validate());
  internal::RequireFinite("t0", t0);
  internal::RequireFinite("t1", t1);
  if (t1 < t0) internal::ThrowInvalid("t1", t1, "must be >= t0 = " + internal::FormatNumber(t0));
  CheckPulses(pulses, t0, t1);
  const ForcedRhs rhs{BallModel::FromPhysical(p).lambda(), {0.0, 0.0}};
  State y{initial.z.x(), initial.z.y(), initial.z.z(), initial.x.x(), initial.x.y(), initial.k.x(), initial.k.y()};
  double t = t0;
  for (const Pulse& pulse : pulses) {
    Segment(rhs, Eigen::Vector2d::Zero(), y, t, pulse.start, options);
    t = pulse.start + pulse.duration;
    Segment(rhs, MomentumRate(p, pulse.impulse / pulse.duration), y, pulse.start, t, options);
  }
  Segment(rhs, Eigen::Vector2d::Zero(), y, t, t1, options);
  PulsedState out;
  out.z = Eigen::Vector3d(y[0], y[1], y[2]);
  out.x = Eigen::Vector2d(y[3], y[4]);
  out.k = Eigen::Vector2d(y[5], y[6]);
  return out;
}

}  // namespace plateball
