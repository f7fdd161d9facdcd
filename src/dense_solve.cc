#include "dense_solve.h"

#include <Eigen/Dense>

namespace plateball::internal {

Eigen::VectorXd MinimumNormSolve(const Eigen::MatrixXd& a, const Eigen::VectorXd& b) {
  return a.completeOrthogonalDecomposition().solve(b);
}

Eigen::VectorXd FullPivLuSolve(const Eigen::MatrixXd& a, const Eigen::VectorXd& b) { return a.fullPivLu().solve(b); }

Eigen::Vector4d OrientedNullVector(const Eigen::Matrix<double, 3, 4>& a) {
  Eigen::Vector4d n;
  for (int i = 0; i < 4; ++i) {
    Eigen::Matrix3d minor;
    for (int c = 0, k = 0; c < 4; ++c)
      if (c != i) minor.col(k++) = a.col(c);
    n[i] = ((i % 2 == 0) ? -1.0 : 1.0) * minor.determinant();
  }
  const double norm = n.norm();
  return norm > 0.0 ? Eigen::Vector4d(n / norm) : Eigen::Vector4d::Zero();
}

}  // namespace plateball::internal
