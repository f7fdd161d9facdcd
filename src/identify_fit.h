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
};

struct TrackFit {
  /// (lambda, mu, theta, phi, psi, x0, y0, delta_psi_0, .., delta_psi_{m-1})
  std::vector<double> q = std::vector<double>(7, 0.0);
  double cost = 0.0;          ///< 1/2 sum of the squared weighted residuals
  int iterations = 0;
  std::vector<double> model;  ///< x(tau_i) at q (after FinishFit)
  std::vector<double> spin;   ///< v0(tau_i) at q when the track has a spin (after FinishFit)
  Eigen::MatrixXd jacobian;   ///< weighted d residual / dq, ((2n + spin samples) x (7 + m)) (after FinishFit)
};

/// The best fit: the multi-start (or options.guess) on a short window, the window doubled to the
/// whole track, then the final fit with options.integration; model and Jacobian filled.
/// *starts receives the number of multi-start fits.
TrackFit FitTrack(const TrackData& data, const IdentifyOptions& options, int* starts);

struct ProfileInterval {
  double low = 0.0, high = 0.0;  ///< 0 / infinity for a side that does not close in the range
  int fits = 0;
};
/// The lambda where the profile 2 (cost(lambda) - cost_min), every other parameter refitted,
/// reaches `threshold` on each side of the optimum `fit` (standard error `se` sets the first step).
ProfileInterval ProfileLambda(const TrackData& data, const IdentifyOptions& options, const TrackFit& fit, double se,
                              double threshold);

}  // namespace plateball::internal
