// Internal: the rotation trick's residual (rotation_trick.h) in the form the shape scan evaluates
// it at many node pairs (isoparallel/shape_scan.cc, ScanShape): B = RotationZ(beta), beta = arg(x1 - x0) -
// arg(chord), with its cos and sin straight from the normalised chord (no atan2, no sincos), the
// turn applied as column combinations, the logarithm by the quaternion's trace route, and exact
// trace tests that a residual exceeds the scan's bound (LogNormBound: no logarithm there).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstddef>

#include "plateball/so3.h"
#include "quaternion_log.h"

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
  return QuaternionLog({w, f * (r(2, 1) - r(1, 2)), f * (r(0, 2) - r(2, 0)), f * (r(1, 0) - r(0, 1))});
}

/// B's angle beta = arg(x1 - x0) - arg(chord) as cos and sin, from the normalised chord (cos(g - a)
/// = cos g cos a + sin g sin a: no atan2, no sincos); a zero chord turns by the goal angle.
inline GoalDirection ChordTurnDirection(const GoalDirection& goal, const Eigen::Vector2d& chord) {
  const double n = chord.norm();
  const double ca = n > 0.0 ? chord.x() / n : 1.0, sa = n > 0.0 ? chord.y() / n : 0.0;
  return {goal.c * ca + goal.s * sa, goal.s * ca - goal.c * sa};
}

/// ChordResidual's rotation before the logarithm: target^-1 B q B^-1, given target^T and the goal's
/// direction; a zero chord turns by the goal angle (atan2(0, 0) = 0).
inline Eigen::Matrix3d ChordRotation(const Eigen::Matrix3d& target_t,
                                     const GoalDirection& goal,
                                     const Eigen::Vector2d& chord,
                                     const Eigen::Matrix3d& q) {
  const GoalDirection beta = ChordTurnDirection(goal, chord);
  const double c = beta.c, s = beta.s;
  Eigen::Matrix3d g;  // target^T B
  g.col(0) = c * target_t.col(0) + s * target_t.col(1);
  g.col(1) = c * target_t.col(1) - s * target_t.col(0);
  g.col(2) = target_t.col(2);
  const Eigen::Matrix3d h = g * q;
  Eigen::Matrix3d r;  // h B^T
  r.col(0) = c * h.col(0) - s * h.col(1);
  r.col(1) = s * h.col(0) + c * h.col(1);
  r.col(2) = h.col(2);
  return r;
}

/// RotationTrickResidual(target, ChordTurn(goal angle, chord), q) = Log(target^-1 B q B^-1).
inline Eigen::Vector3d ChordResidual(const Eigen::Matrix3d& target_t,
                                     const GoalDirection& goal,
                                     const Eigen::Vector2d& chord,
                                     const Eigen::Matrix3d& q) {
  return TraceLogSO3(ChordRotation(target_t, goal, chord, q));
}

/// ChordRotation in quaternions: target^-1 B q B^-1 given target's conjugate and q as quaternions.
/// B q B^-1 keeps q's scalar and turns its vector by B (about e3), straight from cos and sin of
/// beta (no half angles): 4 + 16 multiplications instead of ChordRotation's 51.
inline Eigen::Quaterniond ChordQuaternion(const Eigen::Quaterniond& target_conj,
                                          const GoalDirection& goal,
                                          const Eigen::Vector2d& chord,
                                          const Eigen::Quaterniond& q) {
  const GoalDirection beta = ChordTurnDirection(goal, chord);
  const double c = beta.c, s = beta.s;
  const Eigen::Quaterniond turned(q.w(), c * q.x() - s * q.y(), s * q.x() + c * q.y(), q.z());
  return target_conj * turned;
}

/// Exact tests, from traces only (no logarithm), that |TraceLogSO3(a)| or the interpolation
/// |t TraceLogSO3(a) + (1 - t) TraceLogSO3(b)| (any t in [0, 1]) exceeds `bound` (the shape scan
/// stores such a residual as +infinity: its search starts only read residuals up to the bound).
/// Angles from traces: cos theta = (tr a - 1) / 2, and phi, the angle of a^T b, from tr(a^T b).
/// While theta_a + theta_b + phi < 2 pi, the geodesic from a to b keeps its angle below
/// (theta_a + theta_b + phi) / 2 < pi, where Log is smooth with |dLog| <= (theta / 2) / sin(theta / 2)
/// <= pi / 2; so |Log a - Log b| <= pi phi / 2 and the interpolation's norm is at least
/// t theta_a + (1 - t) theta_b - 2 t (1 - t) pi phi / 2 >= min(theta_a, theta_b) - pi phi / 4. Tiers of
/// phi <= phi_k then ask theta in [bound + pi phi_k / 4, pi - phi_k / 2], each end with a margin
/// of kMargin rad (far above the round-off of a computed rotation's trace there).
class LogNormBound {
 public:
  explicit LogNormBound(double bound) : single_(1.0 + 2.0 * std::cos(bound + kMargin)) {
    for (std::size_t k = 0; k < kTiers; ++k) {
      const double phi = kPhi[k];
      tiers_[k] = {1.0 + 2.0 * std::cos(phi),
                   1.0 + 2.0 * std::cos(bound + M_PI * phi / 4 + kMargin),
                   1.0 + 2.0 * std::cos(M_PI - phi / 2 - kMargin)};
    }
  }
  /// |TraceLogSO3(a)| > bound for sure.
  bool Exceeds(const Eigen::Matrix3d& a) const { return a.trace() < single_; }
  /// The same for a quaternion's rotation (trace 4 w^2 / |q|^2 - 1).
  bool Exceeds(const Eigen::Quaterniond& a) const { return Trace(a) < single_; }
  /// |t TraceLogSO3(a) + (1 - t) TraceLogSO3(b)| > bound for sure, for every t in [0, 1].
  bool InterpolationExceeds(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) const {
    const double ta = a.trace(), tb = b.trace();
    if (!(ta < single_ && tb < single_)) return false;
    return TiersExceed(ta, tb, a.cwiseProduct(b).sum());  // tr(a^T b)
  }
  /// The same for two quaternions' rotations (tr(a^T b) = 4 (a.b)^2 / (|a|^2 |b|^2) - 1).
  bool InterpolationExceeds(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) const {
    const double ta = Trace(a), tb = Trace(b);
    if (!(ta < single_ && tb < single_)) return false;
    const double d = a.coeffs().dot(b.coeffs());
    return TiersExceed(ta, tb, 4.0 * d * d / (a.squaredNorm() * b.squaredNorm()) - 1.0);
  }

 private:
  static double Trace(const Eigen::Quaterniond& q) { return 4.0 * q.w() * q.w() / q.squaredNorm() - 1.0; }
  bool TiersExceed(double ta, double tb, double tab) const {
    for (const Tier& tier : tiers_)
      if (tab >= tier.trace_phi) return std::max(ta, tb) <= tier.trace_low && std::min(ta, tb) >= tier.trace_high;
    return false;
  }
  static constexpr double kMargin = 1e-6;
  static constexpr std::size_t kTiers = 6;
  static constexpr double kPhi[kTiers] = {0.05, 0.1, 0.2, 0.35, 0.5, 0.7};
  struct Tier {
    double trace_phi = 0.0;   // tr(a^T b) >= it: phi <= phi_k
    double trace_low = 0.0;   // tr <= it: theta >= bound + pi phi_k / 4 + margin
    double trace_high = 0.0;  // tr >= it: theta <= pi - phi_k / 2 - margin
  };
  double single_;
  Tier tiers_[kTiers];
};

}  // namespace plateball::internal
