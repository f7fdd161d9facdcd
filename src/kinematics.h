// Internal: the kinematics kernel. Every formula of the chart-free dynamics (docs/paper_notes.md,
// /work/shared/design/dynamics.md) and of the angle chart that more than one solver needs is
// written here once. Templated on the scalar where ceres::Jet gives exact derivatives.
//
//   z       = (sin th cos ph, sin th sin ph, cos th)                         (12)-(14)
//   omega_h = a cos(w) e_r(ph) - b sin(w) e_phi(ph) rotated, w = ph - psi  (section 2.1, (25)-(26))
//   K       = omega_h + (lambda - 1) v0 z_h,  v0 = <omega_h, z_h>           (conserved)
//   omega_h = K - (lambda - 1) v0 z_h,  v0 = <K, z_h> / (z3^2 + lambda |z_h|^2)
//   z'      = omega x z,  x' = omega x e3 = (omega_2, -omega_1)
//   A'      = hat(omega) A  (free motion: omega(z, K); rolling along a curve: omega = e3 x p')
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "check.h"
#include "plateball/ball_state.h"
#include "plateball/impulse.h"

namespace plateball::internal {

constexpr double kTwoPi = 2.0 * M_PI;

// ---------------------------------------------------------------------------------------------
// Angles on the circle.

/// a reduced to (-pi, pi].
inline double WrapPi(double a) {
  if (a > -M_PI && a <= M_PI) return a;  // what remainder returns there, without its cost
  a = std::remainder(a, kTwoPi);         // [-pi, pi]
  return a <= -M_PI ? a + kTwoPi : a;
}

/// a reduced to [0, 2 pi).
inline double WrapTwoPi(double a) {
  double r = std::fmod(a, kTwoPi);
  if (r < 0) r += kTwoPi;
  return r >= kTwoPi ? 0.0 : r;
}

/// Distance of a and b on the circle, in [0, pi].
inline double CircularDistance(double a, double b) { return std::abs(std::remainder(a - b, kTwoPi)); }

/// Beyond this magnitude an angle has no significant digit left modulo 2 pi (the spacing of
/// doubles near 1e15 is 0.125).
constexpr double kMaxAngleMagnitude = 1e15;

/// One reduction of an angle at a public boundary: finite, |a| <= 1e15 (else an error naming the
/// field `prefix`.`name`), and reduced to [-pi, pi] (unchanged when already there). A psi of 1e6
/// loses about 1e-10 in the reduction; every later formula then works on a small angle at full
/// precision. The field name is built only for the error (this runs on every join).
inline double ReduceAngle(double a, const char* prefix, const char* name) {
  if (std::abs(a) <= M_PI) return a;
  const std::string field = std::string(prefix) + "." + name;
  RequireFinite(field, a);
  if (std::abs(a) > kMaxAngleMagnitude)
    ThrowInvalid(field, a, "an angle beyond 1e15 in magnitude has no significant digits left modulo 2 pi");
  return std::remainder(a, kTwoPi);
}

/// ReduceAngle on theta, phi and psi (fields `prefix`.theta, ...). The state is the same.
inline AngleState ReduceAngles(const char* prefix, const AngleState& s) {
  return {ReduceAngle(s.theta, prefix, "theta"), ReduceAngle(s.phi, prefix, "phi"), ReduceAngle(s.psi, prefix, "psi")};
}

// ---------------------------------------------------------------------------------------------
// The angle chart.

/// z = A e3 from (theta, phi), eqs. (12)-(14).
inline Eigen::Vector3d AxisFromAngles(double theta, double phi) {
  const double st = std::sin(theta);
  return {st * std::cos(phi), st * std::sin(phi), std::cos(theta)};
}

/// The sines and cosines of theta, phi and w = phi - psi: what the angle chart (12)-(18) needs.
struct AngleTrig {
  double sin_theta, cos_theta, sin_phi, cos_phi, sin_w, cos_w;
};
/// The trig of the chart at (theta, phi, psi), each sine and cosine once.
inline AngleTrig TrigFromAngles(const AngleState& s) {
  const double w = s.phi - s.psi;
  return {std::sin(s.theta), std::cos(s.theta), std::sin(s.phi), std::cos(s.phi), std::sin(w), std::cos(w)};
}
/// SemiAxisA (ball_state.h) from sin(theta) and cos(theta) already at hand.
inline double SemiAxisFromTrig(double sin_theta, double cos_theta, double mu, double lambda) {
  return std::sqrt(mu / (lambda * sin_theta * sin_theta + cos_theta * cos_theta));
}
/// PhaseFromAngles (ball_state.h, eqs. (12)-(18)) from the trig already at hand, unchecked: a
/// caller that has it (the join: the start's and, after the impulse, that of w) saves the sines
/// and cosines and the boundary checks.
PhaseVariables PhaseFromTrig(const AngleTrig& trig, double mu, double lambda);
/// The impulse (impulse.h) between two states of the same axis given by their phase variables.
Impulse ImpulseFromPhases(const AngleState& before,
                          double mu,
                          const AngleState& after,
                          double mu_after,
                          const PhaseVariables& p0,
                          const PhaseVariables& p1);

/// Horizontal angular velocity on the velocity ellipse of semi-axes (a, b) at the azimuth phi
/// (cp = cos phi, sp = sin phi) and the phase w = phi - psi (cw = cos w, sw = sin w), section 2.1:
///   omega_1 = a cos(w) cos(phi) + b sin(w) sin(phi), omega_2 = a cos(w) sin(phi) - b sin(w) cos(phi)
/// so that x' = (omega_2, -omega_1) is eqs. (25)-(26). Passing (sw, -cw) for (cw, sw) gives
/// d omega / d psi (= -d omega / d w).
template <typename T>
inline void OmegaHOnEllipse(double a, double b, double cp, double sp, const T& cw, const T& sw, T* w) {
  w[0] = a * cw * cp + b * sw * sp;
  w[1] = a * cw * sp - b * sw * cp;
}

/// Horizontal angular velocity at (theta, phi, psi) and energy mu: OmegaHOnEllipse with the
/// semi-axes of SemiAxisA. Templated on the scalar of psi so that ceres::Jet gives d omega / d psi.
template <typename T>
inline void OmegaHFromAngles(double theta, double phi, const T& psi, double mu, double lambda, T* w) {
  using std::cos;
  using std::sin;
  const T wv = phi - psi;
  OmegaHOnEllipse(SemiAxisA(theta, mu, lambda), std::sqrt(mu), std::cos(phi), std::sin(phi), T(cos(wv)), T(sin(wv)), w);
}

/// The least contact speed |x'| at energy mu: sqrt(mu / max(1, lambda)) (|x'|^2 = |omega|^2 =
/// mu + (1 - lambda) v0^2 with lambda v0^2 <= mu; docs/paper_notes.md, the constant K^1).
inline double MinimumContactSpeed(double mu, double lambda) { return std::sqrt(mu / std::max(1.0, lambda)); }

// ---------------------------------------------------------------------------------------------
// The conserved vector K and the chart-free right-hand side.

/// K = omega_h + (lambda - 1) v0 z_h for the axial spin v0 = <omega, z> (lambda may be a
/// ceres::Jet: identify differentiates the impulses with respect to it).
template <typename T, typename Z, typename L>
inline void MomentumFromOmega(const Z* z, const T* w, const T& v0, const L& lambda, T* k) {
  k[0] = w[0] + (lambda - 1.0) * v0 * z[0];
  k[1] = w[1] + (lambda - 1.0) * v0 * z[1];
}
/// The same with v0 = <omega_h, z_h> (omega_3 = 0).
template <typename T, typename Z, typename L>
inline void MomentumFromOmega(const Z* z, const T* w, const L& lambda, T* k) {
  MomentumFromOmega(z, w, T(w[0] * z[0] + w[1] * z[1]), lambda, k);
}

/// The axial spin v0 = <omega, z> from (z, K): v0 = <K, z_h>/(z3^2 + lambda |z_h|^2).
template <typename T, typename L>
inline T AxialSpinFromZK(const T* z, const T* k, const L& lambda) {
  return (k[0] * z[0] + k[1] * z[1]) / (z[2] * z[2] + lambda * (z[0] * z[0] + z[1] * z[1]));
}

/// omega_h from (z, K): v0 = AxialSpinFromZK, omega_h = K - (lambda-1) v0 z_h.
/// lambda may be a ceres::Jet too (identify.cc differentiates the motion with respect to it).
template <typename T, typename L>
inline void OmegaFromZK(const T* z, const T* k, const L& lambda, T* w) {
  const T v0 = AxialSpinFromZK(z, k, lambda);
  w[0] = k[0] - (lambda - 1.0) * v0 * z[0];
  w[1] = k[1] - (lambda - 1.0) * v0 * z[1];
}

/// z' = omega x z (omega_3 = 0), x' = omega x e3 = (omega_2, -omega_1).
template <typename T>
inline void ZxRhs(const T* z, const T* w, T* dz, T* dx) {
  dz[0] = w[1] * z[2];
  dz[1] = -w[0] * z[2];
  dz[2] = w[0] * z[1] - w[1] * z[0];
  dx[0] = w[1];
  dx[1] = -w[0];
}

/// A' = hat(omega) A for omega = (w0, w1, 0), A stored row-major in a[9]: the rolling equation
/// of the free motion and, with omega = e3 x p', of rolling along a curve.
template <typename T>
inline void RotationRhs(const T& w0, const T& w1, const T* a, T* da) {
  // hat(w) = rows (0, 0, w1), (0, 0, -w0), (-w1, w0, 0).
  for (int c = 0; c < 3; ++c) {
    da[0 + c] = w1 * a[6 + c];
    da[3 + c] = -w0 * a[6 + c];
    da[6 + c] = -w1 * a[0 + c] + w0 * a[3 + c];
  }
}

/// omega = e3 x v = (-v_2, v_1, 0) for a planar velocity v: the rolling of section 2.2.
inline void RollingOmega(const Eigen::Vector2d& v, double* w0, double* w1) {
  *w0 = -v.y();
  *w1 = v.x();
}

/// A0 turned minimally so that A0 e3 = z (so3.cc): the product of two rotations, not re-projected
/// (FreeMotion's start frame). AlignOrientationToAxis (so3.h) is this projected onto SO(3).
Eigen::Matrix3d RotateAxisOnto(const Eigen::Matrix3d& A0, const Eigen::Vector3d& z);

// ---------------------------------------------------------------------------------------------
// Row-major 3x3 storage used inside integrator states.

inline Eigen::Matrix3d MatrixFromRowMajor(const double* y) {
  Eigen::Matrix3d m;
  m << y[0], y[1], y[2], y[3], y[4], y[5], y[6], y[7], y[8];
  return m;
}

inline void RowMajorFromMatrix(const Eigen::Matrix3d& m, double* y) {
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) y[3 * r + c] = m(r, c);
}

}  // namespace plateball::internal
