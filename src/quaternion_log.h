// Internal: the logarithm of a rotation given as a quaternion, the one formula behind LogSO3
// (so3.cc) and the shape scan's logarithms (chord_residual.h: TraceLogSO3, and the scan's
// quaternion tables).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>

namespace plateball::internal {

/// The rotation vector of q's rotation, q of any positive norm (both ratios below are scale-free):
/// with the sign making w >= 0, Log = 2 atan2(|v|, w) v / |v|, valid at every angle up to pi;
/// 2 v / w where |v| < 1e-12 w (the angle to round-off).
inline Eigen::Vector3d QuaternionLog(const Eigen::Quaterniond& q) {
  const double w = std::abs(q.w());
  const Eigen::Vector3d v = q.w() < 0.0 ? Eigen::Vector3d(-q.vec()) : Eigen::Vector3d(q.vec());
  const double s = v.norm();
  if (s < 1e-12 * w) return (2.0 / w) * v;
  return (2.0 * std::atan2(s, w) / s) * v;
}

}  // namespace plateball::internal
