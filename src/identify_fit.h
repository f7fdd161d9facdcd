// Internal: the least-squares fits of identify.cc (multi-start, window continuation, the
// profile of lambda) on the track model of identify_model.h.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "plateball/identify.h"

namespace plateball::internal {

/// A track in model units: times since the first sample, positions in radii (x, y interleaved),
/// the weight 1/sigma of each sample (1 when sigma is estimated), and the times of the known
/// impulses since the first sample (identify_model.h, EvaluateImpulsiveTrack).
struct TrackData {
  std::vector<double> tau;
  std::vector<double> x;
  std::vector<double> weight;
  std::vector<double> impulse_tau;
  /// The measured axial spin v0 at each sample and its weight 1/sigma_spin (both empty: none).
  /// Its residuals follow the 2n of the positions.
  std::vector<double> spin;
  std::vector<double> spin_weight;
  /// The measured orientation A_i = R_WB of each sample (row-major, 9 per sample) and its weight
  /// 1/sigma_orientation (both empty: none); 3 residuals per sample, LogSO3(A_i^T A(tau_i)), after
  /// the spin's.
  std::vector<double> orientation;
  std::vector<double> orientation_weight;
  /// The measured body angular velocity A^T omega (3 per sample) and its weight 1/sigma_body_rate
  /// (both empty: none); 3 residuals per sample, after the orientation's.
  std::vector<double> body_rate;
  std::vector<double> body_rate_weight;
  /// True when the frame enters the fit (orientation or body rates): the parameter chi (q[7]).
  bool HasFrame() const { return !orientation.empty() || !body_rate.empty(); }
};

struct TrackFit {
  /// (lambda, mu, theta, phi, psi, x0, y0, [chi,] delta_psi_0, .., delta_psi_{m-1}), chi with
  /// TrackData::HasFrame() (identify_model.h, BodyOutput)
  std::vector<double> q = std::vector<double>(7, 0.0);
  double cost = 0.0;  ///< 1/2 sum of the squared weighted residuals
  int iterations = 0;
  std::vector<double> model;        ///< x(tau_i) at q (after FinishFit)
  std::vector<double> spin;         ///< v0(tau_i) at q when the track has a spin (after FinishFit)
  std::vector<double> orientation;  ///< A(tau_i) row-major at q when the track has orientations (after FinishFit)
  std::vector<double> body_rate;    ///< A^T omega at tau_i when the track has body rates (after FinishFit)
  Eigen::MatrixXd jacobian;         ///< weighted d residual / dq (ResidualCount x parameters) (after FinishFit)
};

/// The best fit: the multi-start (or options.guess) on a short window, the window doubled to the
/// whole track, then the final fit with options.integration; model and Jacobian filled.
/// *starts receives the number of multi-start fits.
TrackFit FitTrack(const TrackData& data, const IdentifyOptions& options, int* starts);

/// The residuals: 2 per sample, then one per measured spin, 3 per orientation, 3 per body rate.
std::size_t ResidualCount(const TrackData& d);

struct ProfileInterval {
  double low = 0.0, high = 0.0;  ///< 0 / infinity for a side that does not close in the range
  int fits = 0;
};
/// The lambda where the profile 2 (cost(lambda) - cost_min), every other parameter refitted,
/// reaches `threshold` on each side of the optimum `fit` (standard error `se` sets the first step).
ProfileInterval ProfileLambda(
    const TrackData& data, const IdentifyOptions& options, const TrackFit& fit, double se, double threshold);

}  // namespace plateball::internal
