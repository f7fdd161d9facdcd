// Internal: free-motion arcs between impulses, integrated directly from (z, K) over a short time
// (no period is built), and the start data of an arc after an impulse. Used by the join (with
// s-sensitivities), the reach and the planner (with the orientation).
#pragma once

#include <Eigen/Core>
#include <array>

#include "kinematics.h"
#include "plateball/ball_state.h"
#include "plateball/integration_options.h"

namespace plateball::internal {

/// Everything the free motion after the impulse psi -> psi + s depends on: the axis z0 (unchanged
/// by the impulse), the conserved vector K(s) (kinematics.h) and dK/ds (exact, from ceres::Jet).
struct ReachDirection {
  double s = 0.0;
  Eigen::Vector3d z0 = Eigen::Vector3d::UnitZ();
  Eigen::Vector2d k = Eigen::Vector2d::Zero();
  Eigen::Vector2d dk_ds = Eigen::Vector2d::Zero();
};
/// What does not depend on the impulse s: the axis z0, the velocity ellipse (a, b) and the trig
/// of phi. Built once per start so that each direction costs one sine and one cosine.
struct ImpulseBasis {
  Eigen::Vector3d z0 = Eigen::Vector3d::UnitZ();
  double a = 0.0, b = 0.0, cos_phi = 1.0, sin_phi = 0.0, phi = 0.0, psi = 0.0, lambda = 1.0;
};
ImpulseBasis MakeImpulseBasis(const AngleState& start, double mu, double lambda);
/// The direction of the impulse s: K(s) = K(omega_h(theta, phi, psi + s)) and dK/ds.
ReachDirection DirectionFor(const ImpulseBasis& basis, double s);
/// The same with cos w, sin w of w = phi - (psi + s) already at hand (no sine computed).
ReachDirection DirectionFromTrig(const ImpulseBasis& basis, double s, double cos_w, double sin_w);
/// The same from the angles (angles already reduced).
ReachDirection DirectionFor(const AngleState& start, double mu, double lambda, double s);

/// Result of integrating one arc of the free motion over [0, t] from the axis z0 and momentum K.
struct ArcEnd {
  Eigen::Vector3d z;                                  ///< axis at t (renormalised)
  Eigen::Vector2d dx = Eigen::Vector2d::Zero();       ///< x(t) - x(0)
  Eigen::Matrix3d phi = Eigen::Matrix3d::Identity();  ///< A(t) A(0)^-1 (when asked)
  /// max |x'| over the arc (ArcDerivativeMaxima: exact up to rounding).
  double max_speed = 0.0;
  /// max |x''| = |omega_h'| over the arc (ArcDerivativeMaxima: sampled, plus the largest change).
  double max_acceleration = 0.0;
  int steps = 0;
};

/// The steps a caller integrating many similar arcs (the planner) carries from arc to arc.
struct EqualStepHint {
  double h = 0.0;    ///< the last arc's step (0: none yet)
  double err = 0.0;  ///< its largest error measure (<= 1)
};
struct ArcStepHints {
  EqualStepHint fehlberg78;  ///< long arcs' equal Fehlberg 7(8) steps
  EqualStepHint dopri5;      ///< short arcs' equal Dormand-Prince 5(4) steps
};

/// Integrates (z, x, Phi) over [0, t] (t >= 0). Without `hints`: odeint's adaptive dopri5. With
/// them (the planner, whose consecutive arcs are alike): as few equal steps as the last arc's
/// error predicts (arc.cc: hand-written Fehlberg 7(8) on long arcs, Dormand-Prince 5(4) on short
/// ones, each step within the tolerances), odeint's adaptive stepper of the same method when a
/// step is refused; the hints become this arc's steps.
/// Throws std::runtime_error on failure.
ArcEnd IntegrateArc(double lambda,
                    const Eigen::Vector3d& z0,
                    const Eigen::Vector2d& k,
                    double t,
                    const IntegrationOptions& options,
                    ArcStepHints* hints = nullptr);

/// The largest |x'| and |x''| over a free arc of length t >= 0 from (z0, K), without integrating:
/// with omega_3 = 0, v0^2 (z3^2 + lambda |z_h|^2) is conserved and z3(t) = z3(0) cos(b t) +
/// z3'(0) / b sin(b t) (b = sqrt(mu)), so |x'|^2 = mu - (lambda - 1) v0^2 and |x''|^2 are
/// functions of z3^2 (docs/paper_notes.md, "Constants of Lemmas 2.3-2.4"). |x'|^2 decreases in
/// z3^2, so max |x'| is exact (at the least z3^2 of the arc); max |x''| is the largest of N + 1
/// equally spaced samples plus the largest change between neighbours, N = b t / kArcSamplePhase
/// rounded up, at least 2 and at most kArcAccelerationSamples.
struct ArcMaxima {
  double speed = 0.0, acceleration = 0.0;
  double mu = 0.0;  ///< the arc's energy, |omega x z|^2 + lambda v0^2
};
constexpr int kArcAccelerationSamples = 16;
constexpr double kArcSamplePhase = 0.05;
ArcMaxima ArcDerivativeMaxima(double lambda, const Eigen::Vector3d& z0, const Eigen::Vector2d& k, double t);

/// x'' = d/dt (omega_2, -omega_1) at (z, K): the contact-point acceleration.
Eigen::Vector2d ContactAcceleration(double lambda, const Eigen::Vector3d& z, const Eigen::Vector2d& k);
/// omega_h (= (-x'_2, x'_1)) and x'' at (z[3], k[2]) together, x'' by differentiating OmegaFromZK by
/// hand along z' = omega x z (one evaluation of omega_h for the speed and the acceleration).
void ContactVelocityAndAcceleration(double lambda, const double* z, const double* k, double* w, double* acc);

}  // namespace plateball::internal
