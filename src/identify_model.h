// Internal: the track model of identify.cc. The contact point x(t_i) of the free motion from the
// state at t = 0 given by q = (lambda, mu, theta, phi, psi, x0, y0), and its exact derivatives
// dx(t_i)/dq: the chart-free equations (kinematics.h) integrated on ceres::Jet (forward-mode
// variational equations), read at the sample times from the dense output (dynamics.h).
#pragma once

#include <Eigen/Core>
#include <cstddef>
#include <vector>

#include "plateball/integration_options.h"

namespace plateball::internal {

inline constexpr int kTrackParameters = 7;  ///< (lambda, mu, theta, phi, psi, x0, y0)

/// x(tau_i) for the non-decreasing times tau[0..n) (tau >= 0, 0 = the state's time) into
/// x_out[2i], x_out[2i+1]; with jacobian != nullptr also dx/dq into the row-major (2n x 7)
/// matrix jacobian, integrated with jacobian_options when given (the derivatives need fewer
/// digits than the values: a looser tolerance only slows Gauss-Newton down, it does not move the
/// optimum). Throws std::runtime_error (or StepLimitError) when an integration fails.
void EvaluateTrack(const double* q,
                   const double* tau,
                   std::size_t n,
                   const IntegrationOptions& options,
                   double* x_out,
                   double* jacobian,
                   const IntegrationOptions* jacobian_options = nullptr);

/// The ball just after impulse k (k = 0: at the track's first time): axis z, conserved vector K
/// of the flight that starts there, contact point x, and the flight's start time tau.
struct FlightStart {
  double tau = 0.0;
  Eigen::Vector3d z = Eigen::Vector3d::UnitZ();
  Eigen::Vector2d k = Eigen::Vector2d::Zero();
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  Eigen::Matrix3d a = Eigen::Matrix3d::Identity();  ///< the frame A (when BodyOutput::HasFrame)
};

/// What the model gives besides the contact point, each pointer nullptr when not wanted:
/// - the axial spin v0 = <omega, z> (an IMU's rate about the symmetry axis): spin[i], and
///   dv0(t_i)/dq row-major (n x P) into spin_jacobian;
/// - the orientation A(t_i) = R_WB (z = A e3), row-major 9 per sample, and (3n x P) its body-frame
///   derivative: column j of rows 3i..3i+2 is vee(A^T dA(t_i)/dq_j);
/// - the body angular velocity A^T omega (an IMU's three rates), 3 per sample, and (3n x P) its
///   derivatives.
/// P = 7 + m, plus one when orientation or body_rate is wanted: then q = (lambda, mu, theta, phi,
/// psi, x0, y0, chi, s_0, .., s_{m-1}) with the start frame A(0) = Rz(phi) Ry(theta) Rz(chi) (its third column the axis
/// of (theta, phi), eqs. (12)-(14); chi turns the frame about the axis, which the contact track does not see).
struct BodyOutput {
  double* spin = nullptr;
  double* spin_jacobian = nullptr;
  double* orientation = nullptr;
  double* orientation_jacobian = nullptr;
  double* body_rate = nullptr;
  double* body_rate_jacobian = nullptr;
  /// True when the frame (and with it chi) enters the model.
  bool HasFrame() const { return orientation != nullptr || body_rate != nullptr; }
};

/// The start frame Rz(phi) Ry(theta) Rz(chi) (BodyOutput).
Eigen::Matrix3d StartFrame(double theta, double phi, double chi);

/// EvaluateTrack across energy-preserving impulses psi -> psi + s_j at fixed (theta, phi, mu)
/// (section 2.1, ImpulseMomentum of exact_chain.h) at the strictly increasing times
/// impulse_tau[0..m) in (0, tau[n-1]): q = (lambda, mu, theta, phi, psi, x0, y0, s_0, ..,
/// s_{m-1}), the contact point and the axis continuous across each impulse. A sample at an
/// impulse's time belongs to the flight before it (x is continuous). jacobian: row-major
/// (2n x (7 + m)), by the chain rule over the flights: each flight's variational equations with
/// respect to its start (z, K) and lambda (ceres::Jet), each impulse differentiated by Jets.
/// flights (optional) receives the m + 1 flight starts, body (optional) the axial spin, the
/// orientation and the body rates (BodyOutput; the frame is continuous across the impulses). With
/// m = 0 and neither, this is EvaluateTrack.
void EvaluateImpulsiveTrack(const double* q,
                            const double* tau,
                            std::size_t n,
                            const std::vector<double>& impulse_tau,
                            const IntegrationOptions& options,
                            double* x_out,
                            double* jacobian,
                            const IntegrationOptions* jacobian_options = nullptr,
                            std::vector<FlightStart>* flights = nullptr,
                            const BodyOutput* body = nullptr);

}  // namespace plateball::internal
