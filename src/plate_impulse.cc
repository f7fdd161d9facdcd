#include "plateball/plate_impulse.h"

#include <Eigen/Geometry>
#include <cmath>

#include "check.h"

namespace plateball {
namespace {
// A unit axis and a horizontal jump up to rounding: z from the angles has |z| = 1 to ~1e-16, and
// delta_omega = (delta v0) z - delta u has a vertical part of rounding size.
constexpr double kUnitTolerance = 1e-9;

void RequireUnitAxis(const Eigen::Vector3d& z) {
  if (!z.allFinite() || std::abs(z.norm() - 1.0) > kUnitTolerance)
    internal::ThrowInvalid("z", z.norm(), "|z| must be 1 (the ball's symmetry axis)");
}

void RequireHorizontal(const Eigen::Vector3d& delta_omega) {
  if (!delta_omega.allFinite()) internal::ThrowInvalid("delta_omega", delta_omega.norm(), "must be finite");
  if (std::abs(delta_omega.z()) > kUnitTolerance * (1.0 + delta_omega.norm()))
    internal::ThrowInvalid("delta_omega[2]", delta_omega.z(), "must be 0: the ball does not spin about the vertical");
}
}  // namespace

PlateImpulse PlateImpulseFor(const PhysicalParameters& p,
                             const Eigen::Vector3d& z,
                             const Eigen::Vector3d& delta_omega) {
  internal::ThrowIfInvalid(p.Validate());
  RequireUnitAxis(z);
  RequireHorizontal(delta_omega);
  const Eigen::Vector3d e3 = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d w(delta_omega.x(), delta_omega.y(), 0.0);
  const Eigen::Vector3d i_w = p.inertia_1 * w + (p.inertia_3 - p.inertia_1) * z.dot(w) * z;
  const Eigen::Vector3d a(
      i_w.x() + p.ball_mass * p.radius * p.radius * w.x(), i_w.y() + p.ball_mass * p.radius * p.radius * w.y(), 0.0);
  const Eigen::Vector3d dv = p.radius * w.cross(e3);  // the centre's velocity change
  PlateImpulse out;
  out.top_contact = a.cross(e3) / (2.0 * p.radius);  // solves 2 r e3 x Q = a for horizontal Q
  out.plate_velocity_change = 2.0 * dv;
  out.plate = out.top_contact + p.plate_mass * out.plate_velocity_change;
  out.bottom_contact = p.ball_mass * dv - out.top_contact;
  out.torsion = i_w.z();
  return out;
}

}  // namespace plateball
