// SO(3) helpers: hat/vee, exponential and logarithm, the operator-norm distance the paper uses.
#pragma once

#include <Eigen/Core>
#include <string>

#include "plateball/export.h"

namespace plateball PLATEBALL_EXPORT {

/// hat(w) v = w x v.
Eigen::Matrix3d Hat(const Eigen::Vector3d& w);
/// Inverse of Hat on skew-symmetric matrices (the skew part of m is used).
Eigen::Vector3d Vee(const Eigen::Matrix3d& m);
/// Rotation exp(hat(w)): rotation about w/|w| by the angle |w| (Rodrigues, exact near 0).
Eigen::Matrix3d ExpSO3(const Eigen::Vector3d& w);
/// Rotation vector w with ExpSO3(w) = r and |w| in [0, pi]; accurate near 0 and near pi.
Eigen::Vector3d LogSO3(const Eigen::Matrix3d& r);
/// Operator 2-norm ||a - b||_2 (largest singular value), the norm of Theorems 2.5 and 2.6.
double OperatorNormDistance(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b);
/// Geodesic angle between two rotations, |log(a^T b)| in [0, pi].
double RotationAngle(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b);
/// Nearest rotation in the Frobenius norm (polar factor). Used to remove round-off drift.
Eigen::Matrix3d ProjectToSO3(const Eigen::Matrix3d& m);
/// True when m is a rotation to within tol: ||m^T m - I||_max <= tol and |det m - 1| <= tol.
bool IsRotation(const Eigen::Matrix3d& m, double tol = 1e-9);
/// Rotation about e3 by the angle a (the plane's rotations, the B of section 2.2).
Eigen::Matrix3d RotationZ(double a);
/// A0 rotated minimally (about A0 e3 x z) so that its third column is the unit vector z, then
/// projected onto SO(3); a reversed axis is turned by pi about A0 e1. Throws
/// std::invalid_argument naming A0 when A0 is not a finite rotation (to 1e-9). The angles
/// (theta, phi) fix z = A e3; A0 fixes the rest of the frame.
Eigen::Matrix3d AlignOrientationToAxis(const Eigen::Matrix3d& A0, const Eigen::Vector3d& z);
/// Unit quaternion (w, x, y, z) to rotation; throws std::invalid_argument naming `field` on a zero
/// or non-finite quaternion.
Eigen::Matrix3d QuaternionToRotation(const Eigen::Vector4d& wxyz, const std::string& field = "quaternion");

}  // namespace PLATEBALL_EXPORT
