#include "plateball/so3.h"

#include <Eigen/Dense>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "check.h"
#include "kinematics.h"
#include "quaternion_log.h"

namespace plateball {

Eigen::Matrix3d Hat(const Eigen::Vector3d& w) {
  Eigen::Matrix3d m;
  m << 0.0, -w.z(), w.y(), w.z(), 0.0, -w.x(), -w.y(), w.x(), 0.0;
  return m;
}

Eigen::Vector3d Vee(const Eigen::Matrix3d& m) {
  return 0.5 * Eigen::Vector3d(m(2, 1) - m(1, 2), m(0, 2) - m(2, 0), m(1, 0) - m(0, 1));
}

Eigen::Matrix3d ExpSO3(const Eigen::Vector3d& w) {
  const double t2 = w.squaredNorm();
  double a, b;  // sin(t)/t and (1 - cos t)/t^2; Taylor series (to below 1e-18) for small t
  if (t2 < 0.04) {
    a = 1.0 + t2 * (-1.0 / 6 + t2 * (1.0 / 120 + t2 * (-1.0 / 5040 + t2 * (1.0 / 362880 - t2 / 39916800))));
    b = 0.5 + t2 * (-1.0 / 24 + t2 * (1.0 / 720 + t2 * (-1.0 / 40320 + t2 * (1.0 / 3628800 - t2 / 479001600))));
  } else {
    const double t = std::sqrt(t2);
    a = std::sin(t) / t;
    b = (1.0 - std::cos(t)) / t2;
  }
  // Rodrigues: I + a hat(w) + b hat(w)^2, with hat(w)^2 = w w^T - |w|^2 I.
  Eigen::Matrix3d r = b * (w * w.transpose());
  const double d = 1.0 - b * t2;
  r(0, 0) += d;
  r(1, 1) += d;
  r(2, 2) += d;
  r(0, 1) -= a * w.z();
  r(1, 0) += a * w.z();
  r(0, 2) += a * w.y();
  r(2, 0) -= a * w.y();
  r(1, 2) -= a * w.x();
  r(2, 1) += a * w.x();
  return r;
}

Eigen::Vector3d LogSO3(const Eigen::Matrix3d& r) {
  // Quaternion route: stable at 0 and at pi.
  Eigen::Quaterniond q(r);
  q.normalize();
  return internal::QuaternionLog(q);
}

double OperatorNormDistance(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) {
  const Eigen::Matrix3d d = a - b;
  // Largest singular value = sqrt of the largest eigenvalue of d^T d (symmetric 3x3).
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(d.transpose() * d, Eigen::EigenvaluesOnly);
  return std::sqrt(std::max(0.0, es.eigenvalues()(2)));
}

double RotationAngle(const Eigen::Matrix3d& a, const Eigen::Matrix3d& b) { return LogSO3(a.transpose() * b).norm(); }

Eigen::Matrix3d ProjectToSO3(const Eigen::Matrix3d& m) {
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(m, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d u = svd.matrixU();
  const Eigen::Matrix3d v = svd.matrixV();
  if ((u * v.transpose()).determinant() < 0) u.col(2) = -u.col(2);
  return u * v.transpose();
}

bool IsRotation(const Eigen::Matrix3d& m, double tol) {
  if (!m.allFinite()) return false;
  const double orth = (m.transpose() * m - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  return orth <= tol && std::abs(m.determinant() - 1.0) <= tol;
}

Eigen::Matrix3d RotationZ(double a) {
  Eigen::Matrix3d r;
  const double c = std::cos(a), s = std::sin(a);
  r << c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 1.0;
  return r;
}

namespace internal {
Eigen::Matrix3d RotateAxisOnto(const Eigen::Matrix3d& A0, const Eigen::Vector3d& z) {
  RequireFinite("A0", A0);
  if (!IsRotation(A0, 1e-9)) {
    std::string rows;
    for (int i = 0; i < 3; ++i)
      rows += std::string(i > 0 ? ", " : "") + "[" + FormatNumber(A0(i, 0)) + ", " + FormatNumber(A0(i, 1)) + ", " +
              FormatNumber(A0(i, 2)) + "]";
    ThrowInvalid("A0", "[" + rows + "]", "not a rotation matrix (R^T R = I, det R = 1 to 1e-9)");
  }
  const Eigen::Vector3d e = A0.col(2);
  const Eigen::Vector3d axis = e.cross(z);
  const double angle = std::atan2(axis.norm(), e.dot(z));
  if (axis.norm() > 1e-15) return ExpSO3(axis.normalized() * angle) * A0;
  if (e.dot(z) < 0) return ExpSO3(A0.col(0) * M_PI) * A0;
  return A0;
}
}  // namespace internal

Eigen::Matrix3d AlignOrientationToAxis(const Eigen::Matrix3d& A0, const Eigen::Vector3d& z) {
  return ProjectToSO3(internal::RotateAxisOnto(A0, z));
}

Eigen::Matrix3d QuaternionToRotation(const Eigen::Vector4d& wxyz, const std::string& field) {
  const double n = wxyz.norm();
  if (!wxyz.allFinite() || !(n > 1e-12)) {
    using internal::FormatNumber;
    internal::ThrowInvalid(field,
                           "[" + FormatNumber(wxyz(0)) + ", " + FormatNumber(wxyz(1)) + ", " + FormatNumber(wxyz(2)) +
                               ", " + FormatNumber(wxyz(3)) + "]",
                           "not a finite non-zero quaternion [w, x, y, z]");
  }
  const Eigen::Quaterniond q(wxyz(0) / n, wxyz(1) / n, wxyz(2) / n, wxyz(3) / n);
  return q.toRotationMatrix();
}

}  // namespace plateball
