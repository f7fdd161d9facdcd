// Internal: a small dense convex quadratic programme,
//   min 1/2 d^T H d + c^T d  subject to  E d = e,  A d <= b,
// with H symmetric positive definite, by the dual active-set method of Goldfarb and Idnani
// (Math. Programming 27, 1983): from the equality-constrained minimum, the most violated
// inequality is added at a time; a step that would turn an active multiplier negative drops that
// constraint first (a partial step), so the multipliers stay dual feasible throughout. Each step
// solves the KKT system of the active set afresh (dense LU): meant for tens of unknowns and
// constraints, as the Gauss-Newton steps of the constrained arrival have.
#pragma once

#include <Eigen/Core>

namespace plateball::internal {

struct DenseQpResult {
  bool solved = false;  ///< false: the constraints are inconsistent, or max_changes was reached
  Eigen::VectorXd d;
  Eigen::VectorXd equality_multipliers;    ///< nu: H d + c + E^T nu + A^T mu = 0
  Eigen::VectorXd inequality_multipliers;  ///< mu >= 0, zero for the inactive rows
  int changes = 0;                         ///< active-set changes made
};

/// Solves the QP above; rows of A with b = +inf are ignored. `tolerance` is the violation of
/// A d <= b accepted as met.
DenseQpResult SolveDenseQp(const Eigen::MatrixXd& H,
                           const Eigen::VectorXd& c,
                           const Eigen::MatrixXd& E,
                           const Eigen::VectorXd& e,
                           const Eigen::MatrixXd& A,
                           const Eigen::VectorXd& b,
                           double tolerance = 1e-12,
                           int max_changes = 500);

}  // namespace plateball::internal
