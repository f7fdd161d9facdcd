// Identification of lambda, mu and the initial state from a measured track of the contact point
// (docs/identify.md): nonlinear least squares over the free motion (free_motion.h, the chart-free
// equations of docs/paper_notes.md) with multi-start, standard errors, a profile-likelihood
// interval for lambda and an identifiability report.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "plateball/ball_state.h"
#include "plateball/export.h"
#include "plateball/integration_options.h"

namespace plateball PLATEBALL_EXPORT {

/// A measured track of the contact point: x_i at strictly increasing times t_i, over one free
/// flight or several flights separated by energy-preserving impulses at known times.
struct IdentifyProblem {
  std::vector<double> t;
  std::vector<Eigen::Vector2d> x;  ///< contact point (length unit: IdentifyOptions::radius)
  /// Per-sample standard deviation of each coordinate (> 0), or empty: then one common sigma is
  /// estimated from the residuals.
  std::vector<double> sigma;
  /// Times of the impulses that separate the flights (strictly increasing, strictly inside
  /// (t.front(), t.back()), at least kIdentifyMinFlightSamples samples in every flight; a sample at
  /// an impulse's time belongs to the flight before it). Each is an energy-preserving impulse
  /// psi -> psi + delta_psi at fixed (theta, phi, mu) (section 2.1, "Modeling an impulse"): the
  /// contact point and the axis are continuous, lambda and mu shared, one delta_psi fitted per
  /// impulse. Empty: one free flight.
  std::vector<double> impulse_times;
  /// The measured axial spin v0 = <omega, z> at each sample (an IMU's rate about the ball's
  /// symmetry axis; rad per time unit of t), or empty. It needs sigma (the positions' noise) and
  /// sigma_spin (its own, > 0, one per sample) given: two kinds of residual share no common noise.
  std::vector<double> spin;
  std::vector<double> sigma_spin;
  /// The measured orientation of the ball at each sample (markers), or empty: the unit quaternion
  /// (w, x, y, z) of A = R_WB (body to world; z = A e3 is the symmetry axis, as in MotionSample),
  /// its norm within kIdentifyQuaternionTolerance of 1 (it is normalised). Its residual is the
  /// rotation vector LogSO3(A_i^T A(t_i)) (3 per sample). The reorientation along the path depends
  /// on lambda, so orientations identify lambda even from a short flight.
  std::vector<Eigen::Vector4d> orientation;
  /// The standard deviation (rad) of each component of that rotation vector, one per sample
  /// (> 0). Needed when sigma is given; when neither is given one common sigma is estimated for
  /// the positions (radii) and the orientations (radians: rolling one radius turns the ball by one
  /// radian).
  std::vector<double> sigma_orientation;
  /// The measured body angular velocity A^T omega at each sample (an IMU inside the ball; rad per
  /// time unit of t), or empty. Its third component is the axial spin, so it replaces spin (not
  /// both). Like spin it needs sigma and sigma_body_rate (> 0, one per sample, each component).
  std::vector<Eigen::Vector3d> body_rate;
  std::vector<double> sigma_body_rate;
  /// Empty when valid, else "FIELD: value V: what is wrong" naming the first bad row.
  std::string Validate() const;
};

/// Starting point of the fit instead of the multi-start (all at the track's first time).
struct IdentifyGuess {
  double lambda = 1.0;
  double mu = 1.0;
  AngleState angles;
  Eigen::Vector2d x0 = Eigen::Vector2d::Zero();
  /// The first delta_psi of the impulses (at most one per impulse); the rest are chosen from the
  /// track, each from a grid of values by the cost of the flight after it.
  std::vector<double> delta_psi;
};

/// Fewest samples in each flight of a track with impulses (the first flight's 8 residuals for its
/// 7 start parameters).
inline constexpr int kIdentifyMinFlightSamples = 4;

/// How far the norm of a measured orientation quaternion may be from 1: | |q| - 1 | <= 1e-5 (a
/// quaternion printed with 6 decimals is off by up to ~2e-6; a larger error is not a rotation
/// but a wrong column).
inline constexpr double kIdentifyQuaternionTolerance = 1e-5;

struct IdentifyOptions {
  static constexpr int kMaxThreads = 256;
  /// The ball's radius in the track's length unit: the track is divided by it (the model's unit is
  /// the radius). 1 when the track is already in radii.
  double radius = 1.0;
  /// Search range of lambda (README, "Limits": [1e-3, 1e3]).
  double lambda_min = 1e-3;
  double lambda_max = 1e3;
  /// Multi-start grid: theta values in (0, pi/2] times phase values w = phi - psi in [0, 2 pi)
  /// (z -> -z gives the same track, so theta in (0, pi/2] is enough).
  int theta_starts = 3;
  int phase_starts = 4;
  /// Start values of lambda tried at every grid point.
  std::vector<double> lambda_starts{0.7, 1.6};
  /// Skip the multi-start and start from this guess.
  std::optional<IdentifyGuess> guess;
  int max_iterations = 100;  ///< of the final fit, in [1, 10000]
  /// lambda counts as identified when its standard error is below this fraction of lambda and the
  /// 95% profile interval closes inside [lambda_min, lambda_max].
  double max_lambda_relative_error = 0.5;
  /// No model fits when the fit is rejected by the chi-square test at this significance (with
  /// given sigma), or, with estimated sigma, when the RMS residual exceeds this fraction of the
  /// track's RMS spread about its mean.
  double no_fit_significance = 1e-6;
  double max_relative_residual = 0.05;
  /// Compute the profile-likelihood interval of lambda (the costliest part).
  bool profile_interval = true;
  /// Worker threads in [1, kMaxThreads]: the multi-start's grid points and the profile interval's two
  /// sides run in parallel. The results do not depend on it.
  int threads = 1;
  /// Tolerances of the final fit (the multi-start and the windows use looser ones: they only have to
  /// land in the optimum's basin).
  IntegrationOptions integration{1e-11, 1e-11, 2'000'000};
  /// Empty when valid, else the first offending field, its value and the bound.
  std::string Validate() const;
};

enum class IdentifyStatus {
  kNotRun,               ///< default: nothing was fitted
  kIdentified,           ///< lambda, mu and the state fitted, lambda identified
  kLambdaNotIdentified,  ///< mu and the state fitted; the track carries no (or too little) information on lambda
  kNoFit,                ///< no free motion fits the track (the residual is reported)
  kFailed,               ///< the solver or an integration failed (message)
};
/// The status as the JSON spells it (e.g. "identified", "lambda_not_identified").
std::string ToString(IdentifyStatus status);

/// Names of the fitted parameters of the start, in the order of IdentifySummary::standard_errors
/// (followed by "chi" with orientations or body rates, then "delta_psi[k]" of each impulse;
/// IdentifySummary::parameters).
inline constexpr const char* kIdentifyParameterNames[7] = {"lambda", "mu", "theta", "phi", "psi", "x0", "y0"};

/// The fitted state at the start of one flight: just after its impulse (the first flight: at t_ref).
struct IdentifiedFlight {
  double t_start = 0.0;
  AngleState angles;                            ///< canonical (theta in [0, pi])
  Eigen::Vector2d x = Eigen::Vector2d::Zero();  ///< contact point (radii)
};

/// A default-constructed summary says "not run".
struct IdentifySummary {
  IdentifyStatus status = IdentifyStatus::kNotRun;
  std::string message = "not run";
  // The fit: the state at t_ref = the track's first time.
  double t_ref = 0.0;
  double lambda = 0.0;
  double mu = 0.0;
  AngleState angles;                             ///< (theta, phi, psi) at t_ref, theta in [0, pi]
  Eigen::Vector2d x0 = Eigen::Vector2d::Zero();  ///< contact point at t_ref (radii)
  double period = 0.0;                           ///< 2 pi / sqrt(mu)
  /// The impulse times (IdentifyProblem::impulse_times) and the fitted delta_psi of each, in
  /// (-pi, pi].
  std::vector<double> impulse_times;
  std::vector<double> delta_psi;
  /// The fitted state at the start of each flight (1 + impulses entries).
  std::vector<IdentifiedFlight> flights;
  /// With orientations or body rates the frame is fitted too: A(t_ref) = Rz(phi) Ry(theta)
  /// Rz(chi) with one more parameter chi (the turn about the axis, which the contact track does
  /// not see). orientation is A(t_ref) as the unit quaternion (w, x, y, z), w >= 0.
  bool frame_fitted = false;
  Eigen::Vector4d orientation{1.0, 0.0, 0.0, 0.0};
  /// The names of the fitted parameters, in the order of standard_errors: kIdentifyParameterNames,
  /// "chi" when frame_fitted, "delta_psi[k]" of each impulse.
  std::vector<std::string> parameters;
  /// Standard errors of the parameters (in the order of parameters); infinity where J^T J is
  /// singular.
  std::vector<double> standard_errors;
  /// Correlation matrix of the fitted parameters (square, in the order of parameters; NaN rows
  /// where singular).
  Eigen::MatrixXd correlation;
  /// 95% profile-likelihood interval of lambda. A side that does not close (the profile does not
  /// rise by the threshold before lambda_min / lambda_max) is 0 / infinity; NaN when not computed.
  double lambda_low = 0.0, lambda_high = 0.0;
  /// "profile"; "wald" (lambda +- 1.96 se) for a noiseless track (RMS residual < 1e-8 radii),
  /// whose profile would only resolve the integration error; empty when not computed.
  std::string interval_method;
  // Identifiability.
  bool lambda_identified = false;
  double lambda_relative_error = 0.0;  ///< standard error / lambda
  /// Smallest eigenvalue over the largest of the column-scaled J^T J (0: a direction the track
  /// does not see at all).
  double scaled_condition = 0.0;
  std::vector<std::string> unidentified;  ///< parameters with a huge or infinite standard error
  /// Largest distance of the fitted contact path from its least-squares line (radii); with
  /// impulses the largest over the flights, each from its own line.
  double path_deviation = 0.0;
  /// True when path_deviation is within the noise (sigma, at least 1e-8 radii): the track cannot
  /// tell its path (every flight's) from a straight line. A straight path is what every lambda gives when the axial
  /// spin v0 is 0, and what every state gives at lambda = 1 (the ball rolls like a sphere), so
  /// lambda is then not identifiable from the contact track alone (status kLambdaNotIdentified,
  /// "lambda" in unidentified, whatever its standard error) unless the track has a measured spin,
  /// which tells the two causes apart (the verdict then comes from the standard error).
  bool straight_path = false;
  // Residuals.
  int samples = 0;
  int residuals = 0;          ///< 2 per sample, one per measured spin, 3 per orientation, 3 per body rate
  double rms_residual = 0.0;  ///< sqrt(mean of the squared coordinate residuals), radii
  double max_residual = 0.0;  ///< largest |x_i - x(t_i)|, radii
  double sigma = 0.0;         ///< noise used for the errors (given mean or estimated)
  bool sigma_estimated = true;
  double chi_square = 0.0;              ///< sum of squared weighted residuals
  double track_spread = 0.0;            ///< RMS distance of the track from its mean, radii
  std::vector<Eigen::Vector2d> fitted;  ///< the fitted x(t_i), radii
  /// With a measured spin: the fitted v0(t_i), and the RMS and largest |v0(t_i) - v0_i|.
  std::vector<double> fitted_spin;
  double spin_rms_residual = 0.0;
  double spin_max_residual = 0.0;
  /// With measured orientations: the fitted A(t_i) as unit quaternions (w, x, y, z), w >= 0, the
  /// RMS component of the rotation-vector residuals LogSO3(A_i^T A(t_i)) and the largest angle
  /// |LogSO3(..)| (rad).
  std::vector<Eigen::Vector4d> fitted_orientation;
  double orientation_rms_residual = 0.0;
  double orientation_max_residual = 0.0;
  /// With measured body rates: the fitted A^T omega (t_i), the RMS component and the largest norm
  /// of A^T omega (t_i) - b_i.
  std::vector<Eigen::Vector3d> fitted_body_rate;
  double body_rate_rms_residual = 0.0;
  double body_rate_max_residual = 0.0;
  int starts = 0;        ///< multi-start fits run
  int iterations = 0;    ///< solver iterations of the final fit
  int profile_fits = 0;  ///< fits at fixed lambda for the profile interval

  /// True when lambda, mu and the state were all identified.
  bool IsSolutionUsable() const { return status == IdentifyStatus::kIdentified; }
  /// One line: the status and message, lambda and mu with their standard errors (and lambda's 95%
  /// interval), and the rms residual.
  std::string BriefReport() const;
};

/// Fits lambda, mu, (theta, phi, psi) and x0 at the track's first time, and the delta_psi of each
/// impulse, to the track. Throws
/// std::invalid_argument naming the field and row for an invalid track or options; a track that
/// no free motion fits is the status kNoFit with its residual.
IdentifySummary Identify(const IdentifyProblem& problem, const IdentifyOptions& options = {});

}  // namespace PLATEBALL_EXPORT
