// Internal: the track model of identify.cc. The contact point x(t_i) of the free motion from the
// state at t = 0 given by q = (lambda, mu, theta, phi, psi, x0, y0), and its exact derivatives
// dx(t_i)/dq: the chart-free equations (kinematics.h) integrated on ceres::Jet (forward-mode
// variational equations), read at the sample times from the dense output (dynamics.h).
#pragma once

#include <cstddef>

#include "plateball/integration_options.h"

namespace plateball::internal {

inline constexpr int kTrackParameters = 7;  ///< (lambda, mu, theta, phi, psi, x0, y0)

/// x(tau_i) for the non-decreasing times tau[0..n) (tau >= 0, 0 = the state's time) into
/// x_out[2i], x_out[2i+1]; with jacobian != nullptr also dx/dq into the row-major (2n x 7)
/// matrix jacobian, integrated with jacobian_options when given (the derivatives need fewer
/// digits than the values: a looser tolerance only slows Gauss-Newton down, it does not move the
/// optimum). Throws std::runtime_error (or StepLimitError) when an integration fails.
void EvaluateTrack(const double* q, const double* tau, std::size_t n, const IntegrationOptions& options,
                   double* x_out, double* jacobian, const IntegrationOptions* jacobian_options = nullptr);

}  // namespace plateball::internal
