// Internal: the rotation trick's residual (rotation_trick.h) in the form the shape scan evaluates
// it at many node pairs (isoparallel.cc, ScanShape): B = RotationZ(beta), beta = arg(x1 - x0) -
// arg(chord), with its cos and sin straight from the normalised chord (no atan2, no sincos), the
// turn applied as column combinations, and the logarithm by the quaternion's trace route.
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "plateball/so3.h"

namespace plateball::internal {

/// The goal's direction arg(x1 - x0) as cos and sin.
struct GoalDirection {
  double c = 1.0, s = 0.0;
};

/// Log of a rotation: for trace > 0 (angle below 2 pi / 3) from the quaternion w = sqrt(1 + tr) / 2,
/// v = vee(R - R^T) / (4 w), Log = 2 atan2(|v|, w) v / |v| (LogSO3's route with Eigen's first
/// branch and without the renormalisation, which cancels in the ratio); LogSO3 beyond.
inline Eigen::Vector3d TraceLogSO3(const Eigen::Matrix3d& r) {
  const double tr = r.trace();
  if (!(tr > 0.0)) return LogSO3(r);
  const double w = 0.5 * std::sqrt(1.0 + tr), f = 0.25 / w;
  const Eigen::Vector3d v(f * (r(2, 1) - r(1, 2)), f * (r(0, 2) - r(2, 0)), f * (r(1, 0) - r(0, 1)));
  const double s = v.norm();
  if (s < 1e-12) return 2.0 * v;
  return (2.0 * std::atan2(s, w) / s) * v;
}

/// RotationTrickResidual(target, ChordTurn(goal angle, chord), q) = Log(target^-1 B q B^-1), given
/// target^T and the goal's direction; a zero chord turns by the goal angle (atan2(0, 0) = 0).
inline Eigen::Vector3d ChordResidual(const Eigen::Matrix3d& target_t, const GoalDirection& goal,
                                     const Eigen::Vector2d& chord, const Eigen::Matrix3d& q) {
  const double n = chord.norm();
  const double ca = n > 0.0 ? chord.x() / n : 1.0, sa = n > 0.0 ? chord.y() / n : 0.0;
  const double c = goal.c * ca + goal.s * sa, s = goal.s * ca - goal.c * sa;  // cos, sin of beta
  Eigen::Matrix3d g;  // target^T B
  g.col(0) = c * target_t.col(0) + s * target_t.col(1);
  g.col(1) = c * target_t.col(1) - s * target_t.col(0);
  g.col(2) = target_t.col(2);
  const Eigen::Matrix3d h = g * q;
  Eigen::Matrix3d r;  // h B^T
  r.col(0) = c * h.col(0) - s * h.col(1);
  r.col(1) = s * h.col(0) + c * h.col(1);
  r.col(2) = h.col(2);
  return TraceLogSO3(r);
}

}  // namespace plateball::internal
