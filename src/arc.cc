#include "arc.h"

#include <algorithm>
#include <cmath>

#include "dopri5.h"
#include "dynamics.h"
#include "fehlberg78.h"

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

namespace {

// What |x'| and |x''| depend on along an arc (ArcDerivativeMaxima): lambda, mu, C = v0^2 D with
// D = z3^2 + lambda |z_h|^2 = lambda - (lambda - 1) z3^2 (conserved), and z3^2 + z3'^2 / mu.
struct Z3Motion {
  double lambda = 1.0, eps = 0.0, mu = 0.0, c = 0.0, z3 = 0.0, dz3 = 0.0;
  // |x'|^2 = |omega|^2 = mu + (1 - lambda) v0^2 at z3^2 = u, v0^2 = C / D(u).
  double Speed2(double u) const { return mu - eps * c / (lambda - eps * u); }
  // |x''|^2 = (lambda - 1)^2 |v0' z_h + v0 z_h'|^2 at z3^2 = u, with v0' = (lambda - 1) v0 z3 z3' / D
  // (from v0^2 D = C), <z_h, z_h'> = -z3 z3', |z_h'|^2 = |z'|^2 - z3'^2, |z'|^2 = mu - lambda v0^2
  // and z3'^2 = mu (z3(0)^2 - u) + z3'(0)^2 (z3 is a sinusoid of frequency sqrt(mu)).
  double Acceleration2(double u) const {
    const double inv_d = 1.0 / (lambda - eps * u), v2 = c * inv_d, q = std::max(0.0, mu * (z3 * z3 - u) + dz3 * dz3);
    const double e_uq = eps * u * q * inv_d;
    return eps * eps * v2 * (e_uq * (eps * (1.0 - u) * inv_d - 2.0) + mu - lambda * v2 - q);
  }
};

Z3Motion MotionOfZ3(double lambda, const Eigen::Vector3d& z, const Eigen::Vector2d& k) {
  Z3Motion m;
  double w[2];
  OmegaFromZK(z.data(), k.data(), lambda, w);
  const double d = z.z() * z.z() + lambda * (z.x() * z.x() + z.y() * z.y());
  const double v0 = (k.x() * z.x() + k.y() * z.y()) / d;
  m.lambda = lambda;
  m.eps = lambda - 1.0;
  m.c = v0 * v0 * d;
  m.mu = w[0] * w[0] + w[1] * w[1] + m.eps * v0 * v0;  // |omega x z|^2 + lambda v0^2
  m.z3 = z.z();
  m.dz3 = w[0] * z.y() - w[1] * z.x();  // (omega x z)_3
  return m;
}

// Arcs shorter than this (t sqrt(mu), about the distance rolled) take one or a few Dormand-Prince
// 5(4) steps at tolerance 1e-12, cheaper than one Fehlberg 7(8) step (13 evaluations); longer
// ones fewer evaluations with Fehlberg 7(8) (T2 n = 16: 61 dopri5 steps per arc, 4 rkf78 ones).
constexpr double kDopriArcLength = 0.05;
constexpr int kMaxEqualArcSteps = 64;
// The error measure the equal steps aim at: close to 1 on short arcs (consecutive arcs are near
// identical there and a refused dopri5 step costs little), with a margin on long ones (the state
// changes more from arc to arc, and a refused step costs its Fehlberg 7(8) stages and the arc's
// adaptive integration).
constexpr double kShortTarget = 0.97, kLongTarget = 0.5;

// The fewest equal steps of a method of order `order` (error ~ h^(order + 1)) over t whose
// error, predicted from the last arc's (steps of h with the largest error measure err), is at
// most `target`; 0 when none up to kMaxEqualArcSteps.
int PredictedSteps(const EqualStepHint& last, double t, int order, double target) {
  const double err = std::max(last.err, 1e-6);
  for (int n = 1; n <= kMaxEqualArcSteps; ++n) {
    const double r = t / (n * last.h);
    double power = r;
    for (int i = 0; i < order; ++i) power *= r;
    if (err * power <= target) return n;
  }
  return 0;
}

// The arc in equal steps (Fehlberg 7(8), or on a short arc hand-written Dormand-Prince 5(4),
// dopri5.h: odeint's tableau and error measure without its stepper's overhead), as few as the
// last arc's error predicts; false (y unchanged) when a step is refused, no hint is at hand or too
// many steps (or more than options.max_steps) would be needed. On success *hint is this arc's.
bool EqualArcSteps(const FullRhs& rhs,
                   FullState* y,
                   double t,
                   bool short_arc,
                   const IntegrationOptions& options,
                   EqualStepHint* hint,
                   int* steps) {
  const int n = !(hint->h > 0) ? (short_arc ? 1 : 0)
                               : PredictedSteps(*hint, t, short_arc ? 4 : 7, short_arc ? kShortTarget : kLongTarget);
  if (n == 0 || n > options.max_steps) return false;
  double err = 0.0;
  if (short_arc) {
    const auto dopri5 = [&](FullState& w, double t0, double dt) {
      return DormandPrince5Step(rhs, w, t0, dt, options.absolute_tolerance, options.relative_tolerance);
    };
    if (!EqualSteps(dopri5, *y, 0.0, t, n, &err)) return false;
  } else if (!IntegrateEqualSteps(rhs, *y, 0.0, t, n, options, &err)) {
    return false;
  }
  *hint = {t / n, err};
  *steps = n;
  return true;
}

// The arc adaptively (odeint's dopri5 or Fehlberg 7(8)) from the step dt0; returns the largest
// step taken.
template <typename Stepper>
double AdaptiveArc(
    const FullRhs& rhs, FullState* y, double t, double dt0, const IntegrationOptions& options, int* steps) {
  double last = 0.0, largest = 0.0;
  IntegrateAdaptive<Stepper>(rhs, *y, 0.0, t, dt0, options, [&](double tt, const FullState&) {
    largest = std::max(largest, tt - last);
    last = tt;
    ++*steps;
  });
  return largest;
}

}  // namespace

ArcMaxima ArcDerivativeMaxima(double lambda, const Eigen::Vector3d& z0, const Eigen::Vector2d& k, double t) {
  const Z3Motion m = MotionOfZ3(lambda, z0, k);
  ArcMaxima out;
  out.mu = m.mu;
  if (!(m.mu > 0)) return out;                      // mu = 0 only for omega = 0: the ball is at rest
  const double b = std::sqrt(m.mu), a = m.dz3 / b;  // z3(tau) = z3 cos(b tau) + a sin(b tau)
  // |x''| at N + 1 equally spaced times, cos and sin of b tau_i by turning (cos, sin) of b t / N.
  const int n = std::clamp(static_cast<int>(std::ceil(b * t / kArcSamplePhase)), 2, kArcAccelerationSamples);
  const double ch = std::cos(b * t / n), sh = std::sin(b * t / n);
  double c = 1.0, s = 0.0, prev = 0.0, jump = 0.0, z3 = m.z3;
  for (int i = 0; i <= n; ++i) {
    z3 = m.z3 * c + a * s;
    const double acc = std::sqrt(std::max(0.0, m.Acceleration2(z3 * z3)));
    if (i > 0) jump = std::max(jump, std::abs(acc - prev));
    out.acceleration = std::max(out.acceleration, acc);
    prev = acc;
    const double c_next = c * ch - s * sh;
    s = s * ch + c * sh;
    c = c_next;
  }
  // z3 has zeros pi / b apart: one lies in [0, t] iff b t >= pi or z3 changes sign (z3: at t now).
  const double u_min = (b * t >= M_PI || m.z3 * z3 <= 0) ? 0.0 : std::min(m.z3 * m.z3, z3 * z3);
  out.speed = std::sqrt(std::max(0.0, m.Speed2(u_min)));
  out.acceleration += jump;
  return out;
}

ArcEnd IntegrateArc(double lambda,
                    const Eigen::Vector3d& z0,
                    const Eigen::Vector2d& k,
                    double t,
                    const IntegrationOptions& options,
                    ArcStepHints* hints) {
  namespace odeint = boost::numeric::odeint;
  const FullRhs rhs{lambda, {k.x(), k.y()}};
  FullState y = InitialFullState(z0);
  ArcEnd out;
  const ArcMaxima maxima = ArcDerivativeMaxima(lambda, z0, k, t);
  out.max_speed = maxima.speed;
  out.max_acceleration = maxima.acceleration;
  const bool short_arc = t * std::sqrt(maxima.mu) <= kDopriArcLength;
  if (t > 0 && hints == nullptr) {
    AdaptiveArc<odeint::runge_kutta_dopri5<FullState>>(rhs, &y, t, t, options, &out.steps);
  } else if (t > 0) {
    EqualStepHint& hint = short_arc ? hints->dopri5 : hints->fehlberg78;
    if (!EqualArcSteps(rhs, &y, t, short_arc, options, &hint, &out.steps)) {
      // Adaptively from the hinted step; its largest step is the next hint (error taken as 1).
      const double dt0 = hint.h > 0 ? std::min(hint.h, t) : t;
      const double largest =
          short_arc ? AdaptiveArc<odeint::runge_kutta_dopri5<FullState>>(rhs, &y, t, dt0, options, &out.steps)
                    : AdaptiveArc<odeint::runge_kutta_fehlberg78<FullState>>(rhs, &y, t, dt0, options, &out.steps);
      hint = {largest, 1.0};
    }
  }
  out.z = Eigen::Vector3d(y[0], y[1], y[2]).normalized();
  out.dx = {y[3], y[4]};
  out.phi = MatrixFromRowMajor(y.data() + 5);
  return out;
}

}  // namespace plateball::internal
