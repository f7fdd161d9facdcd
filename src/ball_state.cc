#include "plateball/ball_state.h"

#include <Eigen/Geometry>
#include <cmath>

#include "check.h"
#include "kinematics.h"

namespace plateball {
using internal::WrapPi;

AngleState AngleState::Canonicalize() const {
  double th = std::remainder(theta, 2.0 * M_PI);  // [-pi, pi]
  double ph = phi;
  if (th < 0) {  // (theta, phi, psi) ~ (-theta, phi + pi, psi)
    th = -th;
    ph += M_PI;
  }
  return {th, WrapPi(ph), WrapPi(psi)};
}

double SemiAxisA(double theta, double mu, double lambda) {
  return internal::SemiAxisFromTrig(std::sin(theta), std::cos(theta), mu, lambda);
}

PhaseVariables PhaseFromAngles(const AngleState& s, double mu, const BallModel& model) {
  internal::RequireFinite("theta", s.theta);
  internal::RequireFinite("phi", s.phi);
  internal::RequireFinite("psi", s.psi);
  internal::RequireEnergy("mu", mu);
  // Each sine and cosine once (the same values AxisFromAngles and SemiAxisA would compute).
  return internal::PhaseFromTrig(internal::TrigFromAngles(s), mu, model.lambda());
}

namespace internal {
PhaseVariables PhaseFromTrig(const AngleTrig& g, double mu, double lambda) {
  const double st = g.sin_theta, ct = g.cos_theta, sp = g.sin_phi, cp = g.cos_phi, sw = g.sin_w, cw = g.cos_w;
  const double a = internal::SemiAxisFromTrig(st, ct, mu, lambda);
  const double b = std::sqrt(mu);
  PhaseVariables p;
  p.z = {st * cp, st * sp, ct};                 // (12)-(14)
  p.u = {-a * cw * ct * ct * cp - b * sw * sp,  // (15)
         -a * cw * ct * ct * sp + b * sw * cp,  // (16)
         a * cw * ct * st};                     // (17)
  p.v0 = a * cw * st;                           // (18)
  p.omega = p.v0 * p.z - p.u;
  p.omega.z() = 0.0;  // exactly zero in exact arithmetic (eq. (8)); remove round-off
  return p;
}
}  // namespace internal

BallState StateFromAngles(const AngleState& s, double mu, const BallModel& model) {
  const PhaseVariables p = PhaseFromAngles(s, mu, model);
  BallState out;
  out.z = p.z;
  out.omega = p.omega;
  return out;
}

AngleState AnglesFromState(const BallState& s, const BallModel& model) {
  ValidateState(s);
  const double mu = Energy(s, model);
  if (!(mu > 0)) internal::ThrowInvalid("state energy mu", mu, "the angle chart needs mu > 0");
  const double rho = std::hypot(s.z.x(), s.z.y());
  const double theta = std::atan2(rho, s.z.z());
  const double phi = rho > 0 ? std::atan2(s.z.y(), s.z.x()) : 0.0;
  // The sines and cosines of theta and phi from z itself (theta in [0, pi]: sin theta = rho / |z|).
  const double cp = rho > 0 ? s.z.x() / rho : 1.0, sp = rho > 0 ? s.z.y() / rho : 0.0;
  const Eigen::Vector2d er(cp, sp), ephi(-sp, cp);
  const Eigen::Vector2d wh = s.omega.head<2>();
  const double r = s.z.norm();
  const double a = internal::SemiAxisFromTrig(rho / r, s.z.z() / r, mu, model.lambda());
  const double b = std::sqrt(mu);
  const double w = std::atan2(-wh.dot(ephi) / b, wh.dot(er) / a);
  return AngleState{theta, phi, phi - w}.Canonicalize();
}

double Energy(const BallState& s, const BallModel& model) {
  const double v0 = s.omega.dot(s.z);
  return s.omega.cross(s.z).squaredNorm() + model.lambda() * v0 * v0;
}

Eigen::Vector2d ConservedMomentum(const BallState& s, const BallModel& model) {
  Eigen::Vector2d k;
  internal::MomentumFromOmega(s.z.data(), s.omega.data(), s.omega.dot(s.z), model.lambda(), k.data());
  return k;
}

Eigen::Vector3d OmegaFromMomentum(const Eigen::Vector3d& z, const Eigen::Vector2d& k, const BallModel& model) {
  Eigen::Vector3d w = Eigen::Vector3d::Zero();
  internal::OmegaFromZK(z.data(), k.data(), model.lambda(), w.data());
  return w;
}

Eigen::Vector4d ConstraintResiduals(const PhaseVariables& p, double mu, const BallModel& model) {
  return {p.u.z() - p.v0 * p.z.z(),                               // (8)
          p.u.squaredNorm() + model.lambda() * p.v0 * p.v0 - mu,  // (9)
          p.z.squaredNorm() - 1.0,                                // (10)
          p.z.dot(p.u)};                                          // (11)
}

void ValidateState(const BallState& s, const char* field) {
  // Field names are built only for a bad value (this runs on every join).
  const auto f = [field](const char* member) { return std::string(field) + member; };
  if (!s.z.allFinite()) internal::RequireFinite(f(".z"), s.z);
  if (!s.omega.allFinite()) internal::RequireFinite(f(".omega"), s.omega);
  if (std::abs(s.z.norm() - 1.0) > 1e-9)
    internal::ThrowInvalid(f(".z norm"), s.z.norm(), "the symmetry axis must be a unit vector");
  if (std::abs(s.omega.z()) > 1e-9 * std::max(1.0, s.omega.norm()))
    internal::ThrowInvalid(f(".omega[2]"), s.omega.z(), "no spin: omega_3 must be 0");
}

}  // namespace plateball
