// Internal: conjugate points of the isoparallel extremals (docs/paper_notes.md, "Conjugate points
// of the isoparallel extremals").
//
// An extremal (elastica.h) is fixed by the constant horizontal vector W = (W1, W2) of the heading
// pendulum g'' = -(W1 cos g + W2 sin g) ("Isoparallel extremals") and by g(0), g'(0): these four
// numbers are coordinates of the normalised initial costate (|x'| = 1), and with the arc length s
// they parametrise the 5-dimensional exponential map
//   Exp(W1, W2, g0, kappa0, s) = (x(s), R(s)),  x' = (cos g, sin g),  R' = hat(omega) R,
//   omega = e3 x x' = (-sin g, cos g, 0)   (rolling along the path, R(0) = I).
// A conjugate time is an s > 0 where its 5 x 5 Jacobian is singular. The Jacobian is integrated
// alongside the extremal by the variational equations (Dormand-Prince 5(4), dopri5.h):
//   dg' = dkappa,  dkappa' = -(dW1 cos g + dW2 sin g) + (W1 sin g - W2 cos g) dg,
//   dx' = (-sin g, cos g) dg,  eta' = domega + omega x eta,  domega = (-cos g, -sin g, 0) dg,
// with eta = vee(dR R^T) (the rotation's variation in the tangent space at R; it differs from
// d log R by the invertible left Jacobian, so the zeros are the same), and the s column (x', omega).
// The same variational equations give the planar (Euler) elastica of Sachkov: state (x, y, g) in
// SE(2), the heading at s = 0 fixed, Jacobian 3 x 3 of (x, y, g)(s) with respect to
// (W1, W2, kappa0) at fixed s (the Hamiltonian H = h1 cos g + h2 sin g + h3^2 / 2 gives the same
// pendulum with (W1, W2) = (h2, -h1)).
//
// The determinant of the Jacobian with unit-normalised columns is followed along s on a grid; the
// first sign change after it has left the round-off of s = 0 (where it vanishes to high order) is
// refined by regula falsi (Illinois). A zero of even order (a touch without sign change) is not detected.
#pragma once

#include <Eigen/Core>

#include "plateball/elastica.h"

namespace plateball::internal {

/// The initial data of an extremal: W and the heading and curvature at s = 0.
struct ExtremalData {
  Eigen::Vector2d w = Eigen::Vector2d::Zero();
  double heading = 0.0;
  double curvature = 0.0;
};
ExtremalData ExtremalDataOf(const ElasticaParameters& parameters);

enum class ConjugateProblem {
  kPlateBall,       ///< length-minimising rolling: (x, y, R) from (W, g0, kappa0, s), 5 x 5
  kPlanarElastica,  ///< Euler's elastica: (x, y, g) from (W, kappa0) at fixed s, 3 x 3
};

/// det of the Jacobian at s with unit columns (sign and zeros of the exponential map's Jacobian).
double ConjugateDeterminant(ConjugateProblem problem, const ExtremalData& data, double s);

/// The first conjugate time in (0, s_max]; `found` false when there is none there.
struct ConjugateTime {
  bool found = false;
  double time = 0.0;
};
/// Throws std::runtime_error when the integration stalls (more than 10^6 steps in one interval).
ConjugateTime FirstConjugateTime(ConjugateProblem problem, const ExtremalData& data, double s_max);

}  // namespace plateball::internal
