#include "plateball/finite_pulse.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "check.h"
#include "dynamics.h"
#include "forced_arc.h"
#include "kinematics.h"

namespace plateball {
namespace internal {
namespace {
using ForcedState = std::array<double, 16>;  // z[3], x[2], Phi[9] row-major, K[2]

struct ForcedRhs {
  double lambda;
  double rate[2];  // K'
  void operator()(const ForcedState& y, ForcedState& dy, double /*t*/) const {
    double w[2];
    OmegaFromZK(y.data(), y.data() + 14, lambda, w);
    ZxRhs(y.data(), w, dy.data(), dy.data() + 3);
    RotationRhs(w[0], w[1], y.data() + 5, dy.data() + 5);
    dy[14] = rate[0];
    dy[15] = rate[1];
  }
};
}  // namespace

ForcedArcEnd IntegrateForcedArc(double lambda,
                                const Eigen::Vector3d& z0,
                                const Eigen::Vector2d& k0,
                                const Eigen::Vector2d& k_rate,
                                double t,
                                const IntegrationOptions& options) {
  ForcedState y{};
  const FullState start = InitialFullState(z0);
  std::copy(start.begin(), start.end(), y.begin());
  y[14] = k0.x();
  y[15] = k0.y();
  const ForcedRhs rhs{lambda, {k_rate.x(), k_rate.y()}};
  if (t != 0.0) IntegrateAdaptive(rhs, y, 0.0, t, 0.01 * t, options);
  ForcedArcEnd out;
  out.z = Eigen::Vector3d(y[0], y[1], y[2]).normalized();
  out.dx = {y[3], y[4]};
  out.phi = MatrixFromRowMajor(y.data() + 5);
  out.k = {y[14], y[15]};
  return out;
}
}  // namespace internal

namespace {
void CheckPulses(const std::vector<Pulse>& pulses, double t0, double t1) {
  double previous_end = t0;
  for (std::size_t i = 0; i < pulses.size(); ++i) {
    const std::string field = "pulses[" + std::to_string(i) + "]";
    const Pulse& p = pulses[i];
    internal::RequirePositive(field + ".duration", p.duration);
    internal::RequireFinite(field + ".impulse", p.impulse);
    if (!(p.start >= previous_end))
      internal::ThrowInvalid(field + ".start",
                             p.start,
                             "must be >= " + internal::FormatNumber(previous_end) +
                                 " (the start time or the previous pulse's end: pulses may not overlap)");
    previous_end = p.start + p.duration;
    if (previous_end > t1)
      internal::ThrowInvalid(
          field + ".start", p.start, "the pulse ends after the final time " + internal::FormatNumber(t1));
  }
}

// One segment of constant K rate from `s`.
void Segment(
    double lambda, const Eigen::Vector2d& rate, double duration, const IntegrationOptions& options, PulsedState* s) {
  if (duration <= 0.0) return;
  const internal::ForcedArcEnd end = internal::IntegrateForcedArc(lambda, s->z, s->k, rate, duration, options);
  s->z = end.z;
  s->x += end.dx;
  s->k = end.k;
}
}  // namespace

Eigen::Vector2d MomentumRate(const PhysicalParameters& p, const Eigen::Vector3d& force) {
  internal::ThrowIfInvalid(p.Validate());
  internal::RequireFinite(std::string("force"), force);
  // 2 r e3 x F = 2 r (-F_y, F_x, 0).
  return 2.0 * p.radius * Eigen::Vector2d(-force.y(), force.x()) /
         (p.inertia_1 + p.EffectiveMass() * p.radius * p.radius);
}

PulsedState RunPulsed(const PhysicalParameters& p,
                      const PulsedState& initial,
                      double t0,
                      double t1,
                      const std::vector<Pulse>& pulses,
                      const IntegrationOptions& options) {
  internal::ThrowIfInvalid(p.Validate());
  internal::ThrowIfInvalid(options.Validate());
  internal::RequireFinite("t0", t0);
  internal::RequireFinite("t1", t1);
  if (t1 < t0) internal::ThrowInvalid("t1", t1, "must be >= t0 = " + internal::FormatNumber(t0));
  CheckPulses(pulses, t0, t1);
  const double lambda = BallModel::FromPhysical(p).lambda();
  PulsedState s = initial;
  double t = t0;
  for (const Pulse& pulse : pulses) {
    Segment(lambda, Eigen::Vector2d::Zero(), pulse.start - t, options, &s);
    Segment(lambda, MomentumRate(p, pulse.impulse / pulse.duration), pulse.duration, options, &s);
    t = pulse.start + pulse.duration;
  }
  Segment(lambda, Eigen::Vector2d::Zero(), t1 - t, options, &s);
  return s;
}

}  // namespace plateball
