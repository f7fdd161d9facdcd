// Internal: the seeded draws of one execution trial under an ErrorModel (error_model.h), shared by
// Execute's simulated rig and the controller's closed-loop tests so that both see the same errors
// for the same (seed, trial). The normal draws of impulse k use the counters k * kSlots + slot; the
// trial's lambda one more.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>

#include "counter_random.h"
#include "plateball/error_model.h"
#include "plateball/so3.h"

namespace plateball::internal {

enum ExecutionSlot {
  kMagnitude,
  kAngle,
  kTiming,
  kObsX,
  kObsY,
  kObsTheta,
  kObsPhi,
  kObsPsi,
  kObsMu,
  kObsRot,
  kSlots = 16
};
constexpr std::uint64_t kLambdaCounter = 0xffffffffULL;

class ExecutionNoise {
 public:
  ExecutionNoise(const ErrorModel& errors, std::uint64_t seed, std::uint64_t trial)
      : errors_(errors), random_(seed, trial) {}
  /// sigma times the normal draw of (impulse k, slot); 0 without drawing when sigma is 0.
  double Draw(int k, int slot, double sigma) const {
    return sigma == 0.0 ? 0.0 : sigma * random_.Normal(static_cast<std::uint64_t>(k) * kSlots + slot);
  }
  /// The trial's true lambda: nominal (1 + e), e ~ N(0, errors.lambda^2).
  double TrueLambda(double nominal) const { return nominal * (1.0 + errors_.lambda * random_.Normal(kLambdaCounter)); }
  /// The commanded jump of impulse k as the plate gives it: turned about e3 and scaled.
  Eigen::Vector3d PerturbImpulse(int k, const Eigen::Vector3d& delta_omega) const {
    Eigen::Vector3d d = delta_omega;
    if (errors_.impulse_angle != 0.0) d = RotationZ(Draw(k, kAngle, errors_.impulse_angle)) * d;
    if (errors_.impulse_magnitude != 0.0) d *= 1.0 + Draw(k, kMagnitude, errors_.impulse_magnitude);
    return d;
  }
  /// The speed factor of the restitution after an impulse: sqrt(1 - energy_loss).
  double Restitution() const { return std::sqrt(1.0 - errors_.energy_loss); }

 private:
  ErrorModel errors_;
  CounterRandom random_;
};

}  // namespace plateball::internal
