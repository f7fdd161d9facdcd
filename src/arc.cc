#include "arc.h"

#include <ceres/jet.h>

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

Eigen::Vector2d ContactAcceleration(double lambda, const Eigen::Vector3d& z, const Eigen::Vector2d& k) {
  using J = ceres::Jet<double, 1>;
  double wd[2];
  const double zd[3] = {z.x(), z.y(), z.z()};
  const double kd[2] = {k.x(), k.y()};
  OmegaFromZK(zd, kd, lambda, wd);
  // Directional derivative of omega(z, K) along z' = omega x z (K is constant).
  J zj[3], kj[2], wj[2];
  const double dz[3] = {wd[1] * zd[2], -wd[0] * zd[2], wd[0] * zd[1] - wd[1] * zd[0]};
  for (int i = 0; i < 3; ++i) zj[i] = J(zd[i], 0), zj[i].v[0] = dz[i];
  for (int i = 0; i < 2; ++i) kj[i] = J(kd[i]);
  OmegaFromZK(zj, kj, lambda, wj);
  return {wj[1].v[0], -wj[0].v[0]};
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
    const Eigen::Vector3d z(yy[0], yy[1], yy[2]);
    double w[2];
    const double kd[2] = {k.x(), k.y()};
    OmegaFromZK(yy, kd, lambda, w);
    const double v = std::hypot(w[0], w[1]);
    const double acc = ContactAcceleration(lambda, z, k).norm();
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
