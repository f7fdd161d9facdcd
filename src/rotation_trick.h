// Internal: the rotation trick of section 2.2 (docs/paper_notes.md, "Isoparallel: the rotation
// trick"), used by the solver (src/isoparallel/) and by the certificate (certify/vocabulary.cc).
// A path from x0 whose chord is c is turned about the vertical by B = RotationZ(beta),
// beta = arg(x1 - x0) - arg(c), so that it ends on the goal's direction; rolling along the turned
// path gives B Q B^-1, and the residual against the target rotation A1 A0^-1 is
// Log((A1 A0^-1)^-1 B Q B^-1).
#pragma once

#include <Eigen/Core>
#include <cmath>

#include "plateball/so3.h"

namespace plateball::internal {

/// beta = goal_angle - arg(chord): the turn that points the chord at the goal.
inline double ChordTurn(double goal_angle, const Eigen::Vector2d& chord) {
  return goal_angle - std::atan2(chord.y(), chord.x());
}

/// Log(target^-1 B q B^-1) with B = RotationZ(beta) (target = A1 A0^-1, q the path's rolling).
inline Eigen::Vector3d RotationTrickResidual(const Eigen::Matrix3d& target, double beta, const Eigen::Matrix3d& q) {
  const Eigen::Matrix3d b = RotationZ(beta);
  return LogSO3(target.transpose() * b * q * b.transpose());
}

}  // namespace plateball::internal
