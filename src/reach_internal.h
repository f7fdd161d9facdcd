// Internal pieces of Reach (reach.cc): the start data for one impulse s = delta_psi, the cheap
// one-period tabulation used by the scan, and the tight evaluation of x_s(t) with dx/ds from the
// variational equations. Exposed to tests through this private header.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "arc.h"
#include "plateball/ball_state.h"
#include "plateball/integration_options.h"

namespace plateball::internal {

/// One period tabulated by classical RK4 with `steps` equal steps: x[j] - x0 and the contact
/// velocity v[j] at t = j T / steps, j = 0..steps; drift = x[steps]. Cheap (no orientation, no
/// error control): used only to find candidates, never to report a solution.
struct ScanPeriod {
  std::vector<Eigen::Vector2d> x;
  std::vector<Eigen::Vector2d> v;
  Eigen::Vector2d drift = Eigen::Vector2d::Zero();
};
void TabulatePeriod(const ReachDirection& d, double lambda, double period, int steps, ScanPeriod* out);
/// The same for several directions at once (identical results; the independent RK4 chains run in
/// lockstep, which lets the processor overlap them).
void TabulatePeriods(const ReachDirection* d, int count, double lambda, double period, int steps, ScanPeriod* out);

/// x_s(t) - x0 from a tight integration (Dormand-Prince, `options`), using x(t + kT) = x(t) + k
/// drift: at most one period is integrated. velocity = x'(t) (the contact velocity);
/// dx_ds = d x_s(t) / ds from the variational equations (only when with_ds; the period does not
/// depend on s, so d/ds of the drift term is k d(drift)/ds).
struct TightPoint {
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  Eigen::Vector2d velocity = Eigen::Vector2d::Zero();
  Eigen::Vector2d dx_ds = Eigen::Vector2d::Zero();
};
TightPoint EvaluateTight(
    const ReachDirection& d, double lambda, double period, double t, bool with_ds, const IntegrationOptions& options);

}  // namespace plateball::internal
