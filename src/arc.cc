#include "arc.h"

#include <algorithm>
#include <cmath>

#include "dynamics.h"

namespace plateball::internal {

ImpulseBasis MakeImpulseBasis(const AngleState& start, double mu, double lambda) {
  ImpulseBasis e;
  e.z0 = AxisFromAngles(start.theta, start.phi);
  e.a = SemiAxisA(start.theta, mu, lambda);
  e.b = std::sqrt(mu);
  e.cos_phi = std::cos(start.phi);
  e.sin_phi = std::sin(start.phi);
  e.phi = start.phi;
  e.psi = start.psi;
  e.lambda = lambda;
  return e;
}

ReachDirection DirectionFor(const ImpulseBasis& e, double s) {
  const double w = e.phi - (e.psi + s);
  return DirectionFromTrig(e, s, std::cos(w), std::sin(w));
}

ReachDirection DirectionFromTrig(const ImpulseBasis& e, double s, double cw, double sw) {
  ReachDirection d;
  d.s = s;
  d.z0 = e.z0;
  double omega[2], domega[2];
  OmegaHOnEllipse(e.a, e.b, e.cos_phi, e.sin_phi, cw, sw, omega);
  OmegaHOnEllipse(e.a, e.b, e.cos_phi, e.sin_phi, sw, -cw, domega);  // d/dpsi = -d/dw
  // K is linear in omega_h at fixed z: dK/ds is K of d omega_h / ds.
  const double zh[2] = {e.z0.x(), e.z0.y()};
  MomentumFromOmega(zh, omega, e.lambda, d.k.data());
  MomentumFromOmega(zh, domega, e.lambda, d.dk_ds.data());
  return d;
}

ReachDirection DirectionFor(const AngleState& start, double mu, double lambda, double s) {
  return DirectionFor(MakeImpulseBasis(start, mu, lambda), s);
}

void ContactVelocityAndAcceleration(double lambda, const double* z, const double* k, double* w, double* acc) {
  OmegaFromZK(z, k, lambda, w);
  // d/dt of omega_h = K - (lambda - 1) v0 z_h along z' = omega x z (K is constant), with
  // v0 = N / D, N = <K, z_h>, D = z3^2 + lambda |z_h|^2 (kinematics.h, OmegaFromZK).
  const double dz[3] = {w[1] * z[2], -w[0] * z[2], w[0] * z[1] - w[1] * z[0]};
  const double n = k[0] * z[0] + k[1] * z[1], d = z[2] * z[2] + lambda * (z[0] * z[0] + z[1] * z[1]);
  const double dn = k[0] * dz[0] + k[1] * dz[1], dd = 2.0 * (z[2] * dz[2] + lambda * (z[0] * dz[0] + z[1] * dz[1]));
  const double v0 = n / d, dv0 = (dn - v0 * dd) / d;
  const double dw[2] = {-(lambda - 1.0) * (dv0 * z[0] + v0 * dz[0]), -(lambda - 1.0) * (dv0 * z[1] + v0 * dz[1])};
  acc[0] = dw[1];  // x' = (omega_2, -omega_1)
  acc[1] = -dw[0];
}

Eigen::Vector2d ContactAcceleration(double lambda, const Eigen::Vector3d& z, const Eigen::Vector2d& k) {
  double w[2];
  Eigen::Vector2d acc;
  ContactVelocityAndAcceleration(lambda, z.data(), k.data(), w, acc.data());
  return acc;
}

ArcEnd IntegrateArc(double lambda, const Eigen::Vector3d& z0, const Eigen::Vector2d& k, double t,
                    const IntegrationOptions& options) {
  FullRhs rhs{lambda, {k.x(), k.y()}};
  FullState y = InitialFullState(z0);
  ArcEnd out;
  // Maxima over the accepted steps plus the largest change between neighbouring steps, so that a
  // maximum between two steps of a smooth arc is covered.
  double prev_v = -1.0, prev_a = -1.0, jump_v = 0.0, jump_a = 0.0;
  auto track = [&](const double* yy) {
    double w[2], dw[2];
    ContactVelocityAndAcceleration(lambda, yy, k.data(), w, dw);
    const double v = std::hypot(w[0], w[1]);
    const double acc = std::sqrt(dw[0] * dw[0] + dw[1] * dw[1]);
    if (prev_v >= 0) {
      jump_v = std::max(jump_v, std::abs(v - prev_v));
      jump_a = std::max(jump_a, std::abs(acc - prev_a));
    }
    prev_v = v;
    prev_a = acc;
    out.max_speed = std::max(out.max_speed, v);
    out.max_acceleration = std::max(out.max_acceleration, acc);
  };
  track(y.data());
  if (t > 0) {
    IntegrateAdaptive(rhs, y, 0.0, t, t, options, [&](double, const FullState& s) {
      ++out.steps;
      track(s.data());
    });
  }
  out.max_speed += jump_v;
  out.max_acceleration += jump_a;
  out.z = Eigen::Vector3d(y[0], y[1], y[2]).normalized();
  out.dx = {y[3], y[4]};
  out.phi = MatrixFromRowMajor(y.data() + 5);
  return out;
}

}  // namespace plateball::internal
