// Internal pieces of Reach (reach.cc): the start data for one impulse s = delta_psi, the cheap
// one-period tabulation used by the scan, and the tight evaluation of x_s(t) with dx/ds from the
// variational equations. Exposed to tests through this private header.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <vector>

#include "plateball/ball_state.h"
#include "plateball/integration_options.h"

namespace plateball::internal {

/// Horizontal angular velocity just after the impulse psi -> psi (section 2.1):
///   omega_1 = a(theta) cos(phi - psi) cos(phi) + b sin(phi - psi) sin(phi)
///   omega_2 = a(theta) cos(phi - psi) sin(phi) - b sin(phi - psi) cos(phi)
/// (a, b the semi-axes of SemiAxisA), so x' = (omega_2, -omega_1) is eqs. (25)-(26).
/// Templated on the scalar of psi so that ceres::Jet gives d omega / d psi.
template <typename T>
inline void OmegaHFromAngles(double theta, double phi, const T& psi, double mu, double lambda, T* w) {
  using std::cos;
  using std::sin;
  const double a = SemiAxisA(theta, mu, lambda);
  const double b = std::sqrt(mu);
  const T wv = phi - psi;
  w[0] = a * cos(wv) * std::cos(phi) + b * sin(wv) * std::sin(phi);
  w[1] = a * cos(wv) * std::sin(phi) - b * sin(wv) * std::cos(phi);
}

/// Everything the motion after the impulse s depends on: the axis z0 (unchanged by the impulse),
/// the conserved vector K(s) (docs/paper_notes.md) and dK/ds.
struct ReachDirection {
  double s = 0.0;
  Eigen::Vector3d z0 = Eigen::Vector3d::UnitZ();
  Eigen::Vector2d k = Eigen::Vector2d::Zero();
  Eigen::Vector2d dk_ds = Eigen::Vector2d::Zero();
};
ReachDirection DirectionFor(const AngleState& start, double mu, double lambda, double s);

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
TightPoint EvaluateTight(const ReachDirection& d, double lambda, double period, double t, bool with_ds,
                         const IntegrationOptions& options);

}  // namespace plateball::internal
