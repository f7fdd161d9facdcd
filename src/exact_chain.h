// Internal: the impulse chain of exact arrival and its exact Jacobian.
//
// The ball between impulses is (z, K): the symmetry axis and the conserved vector of the free arc
// (kinematics.h). Impulse k, psi -> psi + s_k at fixed (theta, phi, mu) (section 2.1), moves the
// horizontal angular velocity along its velocity ellipse (semi-axes a along e_r(phi), b along
// e_phi, section 2.1): in the basis (e_r, e_phi) the phase w = phi - psi turns by -s,
//   omega_h' = M(z, s) omega_h,  M = [[cos s, -(a/b) sin s], [(b/a) sin s, cos s]],
// which in the plane is cos(s) I + sin(s) (J + c1 (J z_h) z_h^T + c2 z_h (J z_h)^T) with J the
// quarter turn, c1 = (lambda - 1)/(sqrt(q) + 1), c2 = (lambda - 1)/(sqrt(q) (sqrt(q) + 1)),
// q = z3^2 + lambda |z_h|^2 (b/a = sqrt(q)): smooth through theta = 0, where AnglesFromState has
// no phi. It is written once, templated, so that ceres::Jet differentiates it exactly.
//
// Arc k, of duration t_k, maps (z_k, K_k) to (z_{k+1}, x_{k+1} - x_k, Phi_k) with A_{k+1} = Phi_k
// A_k; its derivatives with respect to (z_k, K_k) come from the variational equations, evaluated
// on ceres::Jet<double, 5> through the same right-hand side (dynamics.h), and the derivative with
// respect to t_k is the right-hand side at the arc's end. The chain rule over the arcs gives the
// exact Jacobian of every pass point and of the final orientation with respect to
// u = (s_0..s_{n-1}, t_0..t_{n-1}) in one forward sweep (no finite differences).
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <string>
#include <vector>

#include "kinematics.h"
#include "plateball/exact_arrival.h"
#include "plateball/integration_options.h"

namespace plateball::internal {

/// K after the impulse s from the axis z and the conserved vector K before it (lambda given; a
/// ceres::Jet too when its derivative is wanted).
template <typename T, typename L = double>
void ImpulseMomentum(const T* z, const T* k_before, const T& s, const L& lambda, T* k_after) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  T w[2], v[2];
  OmegaFromZK(z, k_before, lambda, w);
  const T q = z[2] * z[2] + lambda * (z[0] * z[0] + z[1] * z[1]);
  const T rq = sqrt(q);
  const T c1 = (lambda - 1.0) / (rq + 1.0);
  const T c2 = c1 / rq;
  const T jz[2] = {-z[1], z[0]};              // J z_h
  const T zw = z[0] * w[0] + z[1] * w[1];     // z_h . omega_h
  const T jzw = jz[0] * w[0] + jz[1] * w[1];  // (J z_h) . omega_h
  const T cs = cos(s), sn = sin(s);
  for (int i = 0; i < 2; ++i) {
    const T jw = i == 0 ? T(-w[1]) : T(w[0]);
    v[i] = cs * w[i] + sn * (jw + c1 * jz[i] * zw + c2 * z[i] * jzw);
  }
  MomentumFromOmega(z, v, lambda, k_after);
}

/// The ball just before impulse k: axis, conserved vector of the arc before (the start's for
/// k = 0), contact point, orientation.
struct ChainNode {
  Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  Eigen::Vector2d k = Eigen::Vector2d::Zero();
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();
};

/// Derivatives of the chain with respect to u (2n columns; see ChainColumns).
struct ChainJacobian {
  std::vector<Eigen::MatrixXd> dx;  ///< dx_k/du, k = 0..n (2 x 2n each)
  std::vector<Eigen::MatrixXd> dz;  ///< dz_k/du, k = 0..n (3 x 2n each): the axis at node k
  std::vector<Eigen::MatrixXd> dk;  ///< dK_k/du, k = 0..n (2 x 2n each): K of the arc before node k
  Eigen::MatrixXd rotation;         ///< 3 x 2n: column j is delta with dA_n/du_j = hat(delta) A_n
};

/// The chain's parameters as functions of fewer unknowns (the Jacobian's columns): the turn of arc
/// i is unknown s_column[i] (-1: held at zero), its duration t_scale[i] times unknown t_column[i].
/// A chain whose arcs are cut into sub-arcs by zero impulses is then differentiated directly with
/// respect to the unknowns of the uncut chain.
struct ChainColumns {
  int columns = 0;
  std::vector<int> s_column;
  std::vector<int> t_column;
  std::vector<double> t_scale;
};

/// Rolls the chain from nodes[0] with u = (s, t) (n = u.size() / 2), filling nodes[1..n] (A
/// re-projected onto SO(3) after every arc). With `jacobian`, also the exact Jacobian, with respect
/// to u, or to the unknowns of `columns` when given: each arc is then integrated once, its values
/// together with their variational equations (the step control over both).
/// Throws std::runtime_error when an integration fails.
void RollChain(double lambda,
               const Eigen::VectorXd& u,
               const IntegrationOptions& integration,
               std::vector<ChainNode>* nodes,
               ChainJacobian* jacobian = nullptr,
               const ChainColumns* columns = nullptr);

/// The five arrival conditions at the chain's end: (x_n - x1, LogSO3(A1^T A_n)).
Eigen::Matrix<double, 5, 1> ArrivalResidual(const ChainNode& end, const Eigen::Vector2d& x1, const Eigen::Matrix3d& A1);
/// Their exact Jacobian (5 x 2n) from the chain's (the rotation rows through LeftJacobianInverse).
Eigen::MatrixXd ArrivalJacobian(const ChainJacobian& jacobian, const ChainNode& end, const Eigen::Matrix3d& A1);

/// The checks shared by exact arrival and the fewest-impulse search: mu, x0, x1 (fields named so),
/// A0 and A1 rotations; throws std::invalid_argument naming the field.
void ValidateStartAndGoal(double mu,
                          const Eigen::Vector2d& x0,
                          const Eigen::Vector2d& x1,
                          const Eigen::Matrix3d& A0,
                          const Eigen::Matrix3d& A1);
/// The start node: the state of `initial` at energy mu (its K), x0 and A0 turned onto its axis.
ChainNode StartNode(
    const BallModel& model, const AngleState& initial, double mu, const Eigen::Vector2d& x0, const Eigen::Matrix3d& A0);
/// The impulses of u along the rolled nodes (time, position, angles before, delta omega, the plate's
/// velocity change); the first is kStart when the ball starts at rest (exact_arrival.cc).
std::vector<ExactImpulse> ReportImpulses(const BallModel& model,
                                         double mu,
                                         const std::vector<ChainNode>& nodes,
                                         const Eigen::VectorXd& u,
                                         bool start_at_rest);
/// The impulse at the chain's end that brings omega to zero ("arrive and stop").
ExactImpulse StopImpulse(const BallModel& model, double mu, const ChainNode& end, double total_time);

/// The length of the contact point's path over the rolled chain (integral of |x'| per arc).
double ChainPathLength(double lambda,
                       const std::vector<ChainNode>& nodes,
                       const Eigen::VectorXd& u,
                       const IntegrationOptions& integration);

/// The inverse left Jacobian of SO(3) at the rotation vector phi: Log(exp(hat e) exp(hat phi)) =
/// phi + JlInv(phi) e + O(|e|^2).
Eigen::Matrix3d LeftJacobianInverse(const Eigen::Vector3d& phi);

}  // namespace plateball::internal
