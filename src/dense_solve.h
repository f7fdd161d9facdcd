// Dense linear solves shared by the solvers, compiled once in dense_solve.cc: Eigen's
// decompositions are large templates, instantiated again by every translation unit that calls
// one (the complete orthogonal decomposition alone costs about 14 s of compile time per unit).
#pragma once

#include <Eigen/Core>

namespace plateball::internal {

/// The minimum-norm least-squares solution of a x = b (Eigen's complete orthogonal decomposition;
/// a may be wide, tall or rank-deficient).
Eigen::VectorXd MinimumNormSolve(const Eigen::MatrixXd& a, const Eigen::VectorXd& b);

/// The solution of a x = b by LU decomposition with full pivoting (a square).
Eigen::VectorXd FullPivLuSolve(const Eigen::MatrixXd& a, const Eigen::VectorXd& b);

/// The unit vector n orthogonal to the three rows of a with det [a; n^T] >= 0: the cofactors of
/// the fourth row of [a; x^T], normalised (zero when a has rank below 3).
Eigen::Vector4d OrientedNullVector(const Eigen::Matrix<double, 3, 4>& a);

}  // namespace plateball::internal
