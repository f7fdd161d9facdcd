// The dynamical state of the ball: the angles (theta, phi, psi) of the paper and the chart-free
// pair (z, omega) used for integration (see docs/paper_notes.md, "Chart-free form").
#pragma once

#include <Eigen/Core>

#include "plateball/ball_model.h"
#include "plateball/export.h"

namespace plateball PLATEBALL_EXPORT {

/// Coordinates (theta, phi, psi) of S^2 x S^1, eqs. (12)-(18). Any real theta is accepted:
/// (theta, phi, psi) and (-theta, phi + pi, psi) give identical (z, u, v0) in (12)-(18), so the
/// paper's theta0 = -pi/3 (Figure 8) is used as written. Canonicalize() maps to theta in [0, pi].
struct AngleState {
  double theta = 0.0;
  double phi = 0.0;
  double psi = 0.0;
  /// Same physical state with theta in [0, pi], phi and psi in (-pi, pi].
  AngleState Canonicalize() const;
};

/// The paper's phase variables (z, u, v0) of (12)-(18), with omega = v0 z - u.
struct PhaseVariables {
  Eigen::Vector3d z;      ///< A e3, the symmetry axis (eqs. (12)-(14))
  Eigen::Vector3d u;      ///< z' x z (eqs. (15)-(17))
  double v0 = 0.0;        ///< <omega, z> (eq. (18))
  Eigen::Vector3d omega;  ///< spatial angular velocity, omega_3 = 0
};

/// Chart-free state: the symmetry axis z (unit) and the spatial angular velocity omega with
/// omega_3 = 0 (no spin). Together with lambda this fixes the whole motion.
struct BallState {
  Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();
};

/// a = sqrt(mu / (lambda sin^2 theta + cos^2 theta)), b = sqrt(mu): the semi-axes of the
/// velocity ellipse (section 1).
double SemiAxisA(double theta, double mu, double lambda);

/// Eqs. (12)-(18) for energy mu > 0; omega = v0 z - u.
PhaseVariables PhaseFromAngles(const AngleState& s, double mu, const BallModel& model);
/// (theta, phi, psi, mu) -> (z, omega). Validates mu > 0 and finite angles (names the field).
BallState StateFromAngles(const AngleState& s, double mu, const BallModel& model);
/// Inverse chart: theta in [0, pi], phi = atan2(z2, z1) (0 at the poles), psi = phi - w with
/// (a cos w, -b sin w) the components of omega on (e_r, e_phi). Requires energy > 0.
AngleState AnglesFromState(const BallState& s, const BallModel& model);
/// mu = |omega x z|^2 + lambda v0^2, eq. (9) (equivalently |u|^2 + lambda v0^2).
double Energy(const BallState& s, const BallModel& model);
/// v0 = <omega, z>.
inline double AxialSpin(const BallState& s) { return s.omega.dot(s.z); }
/// The conserved horizontal angular momentum about the contact point divided by (I1 + M r^2):
/// K = omega_h + (lambda - 1) v0 z_h (docs/paper_notes.md).
Eigen::Vector2d ConservedMomentum(const BallState& s, const BallModel& model);
/// omega from (z, K): v0 = <K, z_h>/(z3^2 + lambda |z_h|^2), omega_h = K - (lambda-1) v0 z_h.
Eigen::Vector3d OmegaFromMomentum(const Eigen::Vector3d& z, const Eigen::Vector2d& k, const BallModel& model);
/// Contact-point velocity x' = omega x e3 = (omega_2, -omega_1) (no sliding; eqs. (25)-(26)).
inline Eigen::Vector2d ContactVelocity(const Eigen::Vector3d& omega) { return {omega.y(), -omega.x()}; }
/// Residuals of the constraints (8)-(11) for given phase variables and energy (all ~0 when valid).
Eigen::Vector4d ConstraintResiduals(const PhaseVariables& p, double mu, const BallModel& model);
/// Throws std::invalid_argument (naming the field) when |z| != 1, omega_3 != 0 or values are not finite.
void ValidateState(const BallState& s, const char* field = "state");

}  // namespace PLATEBALL_EXPORT
