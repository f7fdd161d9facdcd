#include "plateball/impulse.h"

#include <Eigen/Geometry>
#include <cmath>

#include "check.h"
#include "kinematics.h"

namespace plateball {
namespace internal {
Impulse ImpulseFromPhases(const AngleState& before,
                          double mu,
                          const AngleState& after,
                          double mu_after,
                          const PhaseVariables& p0,
                          const PhaseVariables& p1) {
  Impulse imp;
  imp.before = before;
  imp.after = after;
  imp.mu_before = mu;
  imp.mu_after = mu_after;
  imp.delta_u = p1.u - p0.u;
  imp.delta_v0 = p1.v0 - p0.v0;
  imp.delta_omega = imp.delta_v0 * p0.z - imp.delta_u;  // z is unchanged by the impulse
  imp.delta_omega.z() = 0.0;                            // exactly 0 by (8)
  imp.plate_velocity_change = 2.0 * imp.delta_omega.cross(Eigen::Vector3d::UnitZ());
  imp.state_before = {p0.z, p0.omega};
  imp.state_after = {p1.z, p1.omega};
  return imp;
}
}  // namespace internal

namespace {
Impulse Make(const AngleState& before, double mu, const AngleState& after, double mu_after, const BallModel& model) {
  return internal::ImpulseFromPhases(
      before, mu, after, mu_after, PhaseFromAngles(before, mu, model), PhaseFromAngles(after, mu_after, model));
}
}  // namespace

Impulse EnergyPreservingImpulse(const AngleState& angles, double mu, double delta_psi, const BallModel& model) {
  internal::RequireFinite("delta_psi", delta_psi);
  AngleState after = angles;
  after.psi += delta_psi;
  return Make(angles, mu, after, mu, model);
}

Impulse EnergyChangingImpulse(const AngleState& angles, double mu, double factor, const BallModel& model) {
  internal::RequirePositive("factor", factor);
  internal::RequirePositive("mu", mu);
  return Make(angles, mu, angles, factor * factor * mu, model);
}

Impulse ImpulseToEnergy(const AngleState& angles, double mu, double mu_after, const BallModel& model) {
  internal::RequirePositive("mu", mu);
  internal::RequirePositive("mu_after", mu_after);
  return EnergyChangingImpulse(angles, mu, std::sqrt(mu_after / mu), model);
}

}  // namespace plateball
