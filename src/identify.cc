// Identification of (lambda, mu, theta, phi, psi, x0) from a track (identify.h, docs/identify.md).
//
// The model is the free motion from the state at the first sample (identify_model.h). The fit is
// Ceres' Levenberg-Marquardt on the weighted residuals w_i (x(t_i) - x_i) with the exact Jacobian.
// The motion is periodic and its phase unknown, so one fit from one guess can lock onto a wrong
// number of turns: the multi-start fits a grid of (theta, w = phi - psi, lambda) on a short
// window (half a guessed period), where every start sees the same part of the orbit, and the
// best one is carried to the whole track by doubling the window (identify_fit.cc).
#include "plateball/identify.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <boost/math/distributions/chi_squared.hpp>
#include <boost/math/distributions/fisher_f.hpp>
#include <cmath>
#include <limits>
#include <sstream>

#include "check.h"
#include "identify_fit.h"
#include "identify_model.h"
#include "kinematics.h"
#include "plateball/so3.h"

namespace plateball {

namespace {
constexpr int kMinSamples = 8;  // 2n = 16 residuals for 7 parameters: 9 degrees of freedom for the noise
constexpr int kP = internal::kTrackParameters;
constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
// Eigenvalue ratio of the column-scaled J^T J below which a direction counts as unseen: the
// round-off floor of J^T J in double is ~1e-16 relative, the exact Jacobian's error ~1e-10.
constexpr double kSingularRatio = 1e-13;
// A parameter whose (scaled) standard error exceeds this is listed as not identified
// (for the angles: radians; for lambda and mu: relative; for x0: radii of spread).
constexpr double kHugeError = 1.0;
// Below this RMS residual (radii) the track is taken as noiseless: the fit's residual is then the
// integration error (~1e-11), and the interval is the Wald interval lambda +- 1.96 se.
constexpr double kNoiselessResidual = 1e-8;
// A fitted path within this many noise sigmas of a straight line counts as straight: the track
// does not show the curvature that carries lambda (identify.h, straight_path).
constexpr double kStraightPathNoise = 1.0;
}  // namespace

std::string ToString(IdentifyStatus status) {
  switch (status) {
    case IdentifyStatus::kNotRun:
      return "not_run";
    case IdentifyStatus::kIdentified:
      return "identified";
    case IdentifyStatus::kLambdaNotIdentified:
      return "lambda_not_identified";
    case IdentifyStatus::kNoFit:
      return "no_fit";
    case IdentifyStatus::kFailed:
      return "failed";
  }
  return "unknown";
}

namespace {

/// The impulse times: finite, strictly increasing, inside (t.front(), t.back()), and at least
/// kIdentifyMinFlightSamples samples in every flight.
std::string ValidateImpulseTimes(const std::vector<double>& t, const std::vector<double>& impulses) {
  using internal::FormatNumber;
  using internal::InvalidValueMessage;
  std::size_t first = 0;  // the first sample of the current flight
  for (std::size_t k = 0; k <= impulses.size(); ++k) {
    if (k < impulses.size()) {
      const std::string field = "impulse_times[" + std::to_string(k) + "]";
      const double v = impulses[k];
      if (!std::isfinite(v)) return InvalidValueMessage(field, v, "must be finite");
      if (k > 0 && !(v > impulses[k - 1]))
        return InvalidValueMessage(
            field, v, "impulse times must be strictly increasing (previous " + FormatNumber(impulses[k - 1]) + ")");
      if (!(v > t.front() && v < t.back()))
        return InvalidValueMessage(
            field, v, "must be inside the track (" + FormatNumber(t.front()) + ", " + FormatNumber(t.back()) + ")");
    }
    std::size_t end = first;
    while (end < t.size() && (k == impulses.size() || t[end] <= impulses[k])) ++end;
    if (!impulses.empty() && end - first < static_cast<std::size_t>(kIdentifyMinFlightSamples)) {
      // The flight before impulse k, or after the last one.
      const bool last = k == impulses.size();
      const std::size_t named = last ? k - 1 : k;
      return InvalidValueMessage("impulse_times[" + std::to_string(named) + "]",
                                 impulses[named],
                                 "too few samples in the flight " + std::string(last ? "after" : "before") +
                                     " it: " + std::to_string(end - first) + " (at least " +
                                     std::to_string(kIdentifyMinFlightSamples) + " per flight)");
    }
    first = end;
  }
  return {};
}

/// The spin columns: one finite v0 and one sigma_spin > 0 per sample, with sigma given.
std::string ValidateSpin(const IdentifyProblem& p) {
  using internal::InvalidValueMessage;
  if (p.spin.empty() && p.sigma_spin.empty()) return {};
  const std::string rows = "must have one row per time (" + std::to_string(p.t.size()) + ")";
  if (p.spin.size() != p.t.size()) return InvalidValueMessage("spin (rows)", p.spin.size(), rows);
  if (p.sigma_spin.size() != p.t.size())
    return InvalidValueMessage("sigma_spin (rows)", p.sigma_spin.size(), rows + ": a measured spin needs its noise");
  if (p.sigma.empty())
    return InvalidValueMessage(
        "sigma (rows)",
        p.sigma.size(),
        "a measured spin needs sigma given too (positions and spin share no common noise to estimate)");
  for (std::size_t i = 0; i < p.t.size(); ++i) {
    const std::string row = "[" + std::to_string(i) + "]";
    if (!std::isfinite(p.spin[i])) return InvalidValueMessage("spin" + row, p.spin[i], "must be finite");
    if (!(std::isfinite(p.sigma_spin[i]) && p.sigma_spin[i] > 0))
      return InvalidValueMessage("sigma_spin" + row, p.sigma_spin[i], "must be finite and > 0");
  }
  return {};
}

/// A column of one row per time (or empty when optional): its row count.
std::string RowsMessage(const char* field, std::size_t rows, std::size_t times, const std::string& why = {}) {
  return internal::InvalidValueMessage(
      std::string(field) + " (rows)", rows, "must have one row per time (" + std::to_string(times) + ")" + why);
}

/// One noise value: finite and > 0.
std::string NoiseMessage(const std::string& field, double v) {
  return std::isfinite(v) && v > 0 ? std::string() : internal::InvalidValueMessage(field, v, "must be finite and > 0");
}

/// The orientation columns: one unit quaternion per sample (to kIdentifyQuaternionTolerance), and
/// sigma_orientation with sigma (both or neither).
std::string ValidateOrientation(const IdentifyProblem& p) {
  using internal::FormatNumber;
  using internal::InvalidValueMessage;
  if (p.orientation.empty() && p.sigma_orientation.empty()) return {};
  const std::size_t n = p.t.size();
  if (p.orientation.size() != n) return RowsMessage("orientation", p.orientation.size(), n);
  if (!p.sigma_orientation.empty() && p.sigma_orientation.size() != n)
    return RowsMessage("sigma_orientation", p.sigma_orientation.size(), n, " or be empty");
  if (p.sigma_orientation.empty() && !p.sigma.empty())
    return InvalidValueMessage("sigma_orientation (rows)",
                               0,
                               "sigma is given: give the orientations' noise too (positions and "
                               "orientations then share no common noise to estimate)");
  if (!p.sigma_orientation.empty() && p.sigma.empty())
    return InvalidValueMessage("sigma (rows)",
                               0,
                               "sigma_orientation is given: give the positions' noise too (or neither, for one "
                               "common sigma estimated in radii and radians)");
  const char* names[4] = {"w", "x", "y", "z"};
  for (std::size_t i = 0; i < n; ++i) {
    const std::string row = "[" + std::to_string(i) + "]";
    for (int c = 0; c < 4; ++c)
      if (!std::isfinite(p.orientation[i][c]))
        return InvalidValueMessage("orientation" + row + "." + names[c], p.orientation[i][c], "must be finite");
    const double norm = p.orientation[i].norm();
    if (!(std::abs(norm - 1.0) <= kIdentifyQuaternionTolerance))
      return InvalidValueMessage("orientation" + row,
                                 "[" + FormatNumber(p.orientation[i][0]) + ", " + FormatNumber(p.orientation[i][1]) +
                                     ", " + FormatNumber(p.orientation[i][2]) + ", " +
                                     FormatNumber(p.orientation[i][3]) + "]",
                                 "not a unit quaternion (w, x, y, z): norm " + FormatNumber(norm) + ", allowed 1 +- " +
                                     FormatNumber(kIdentifyQuaternionTolerance));
    if (!p.sigma_orientation.empty()) {
      const std::string e = NoiseMessage("sigma_orientation" + row, p.sigma_orientation[i]);
      if (!e.empty()) return e;
    }
  }
  return {};
}

/// The body-rate columns: three finite rates and one sigma_body_rate > 0 per sample, sigma given,
/// and no spin column besides (the third rate is the axial spin).
std::string ValidateBodyRate(const IdentifyProblem& p) {
  using internal::InvalidValueMessage;
  if (p.body_rate.empty() && p.sigma_body_rate.empty()) return {};
  const std::size_t n = p.t.size();
  if (!p.spin.empty())
    return InvalidValueMessage("body_rate (rows)",
                               p.body_rate.size(),
                               "give either spin or body_rate, not both (the third body rate is the axial spin)");
  if (p.body_rate.size() != n) return RowsMessage("body_rate", p.body_rate.size(), n);
  if (p.sigma_body_rate.size() != n)
    return RowsMessage("sigma_body_rate", p.sigma_body_rate.size(), n, ": measured body rates need their noise");
  if (p.sigma.empty())
    return InvalidValueMessage(
        "sigma (rows)",
        0,
        "measured body rates need sigma given too (positions and rates share no common noise to estimate)");
  for (std::size_t i = 0; i < n; ++i) {
    const std::string row = "[" + std::to_string(i) + "]";
    for (int c = 0; c < 3; ++c)
      if (!std::isfinite(p.body_rate[i][c]))
        return InvalidValueMessage(
            "body_rate" + row + "[" + std::to_string(c) + "]", p.body_rate[i][c], "must be finite");
    const std::string e = NoiseMessage("sigma_body_rate" + row, p.sigma_body_rate[i]);
    if (!e.empty()) return e;
  }
  return {};
}

}  // namespace

std::string IdentifyProblem::Validate() const {
  using internal::InvalidValueMessage;
  if (t.size() != x.size())
    return InvalidValueMessage("x (rows)", x.size(), "must have one row per time (" + std::to_string(t.size()) + ")");
  if (t.size() < static_cast<std::size_t>(kMinSamples))
    return InvalidValueMessage("t (rows)",
                               t.size(),
                               "too few samples: at least " + std::to_string(kMinSamples) +
                                   " are needed for 7 parameters and a noise estimate");
  if (!sigma.empty() && sigma.size() != t.size())
    return InvalidValueMessage(
        "sigma (rows)", sigma.size(), "must be empty or have one row per time (" + std::to_string(t.size()) + ")");
  for (std::size_t i = 0; i < t.size(); ++i) {
    const std::string row = "[" + std::to_string(i) + "]";
    if (!std::isfinite(t[i])) return InvalidValueMessage("t" + row, t[i], "must be finite");
    if (i > 0 && !(t[i] > t[i - 1]))
      return InvalidValueMessage(
          "t" + row,
          t[i],
          t[i] == t[i - 1] ? "duplicate time (times must be strictly increasing)"
                           : "times must be strictly increasing (previous " + internal::FormatNumber(t[i - 1]) + ")");
    for (int c = 0; c < 2; ++c)
      if (!std::isfinite(x[i][c])) return InvalidValueMessage((c == 0 ? "x" : "y") + row, x[i][c], "must be finite");
    if (!sigma.empty() && !(std::isfinite(sigma[i]) && sigma[i] > 0))
      return InvalidValueMessage("sigma" + row, sigma[i], "must be finite and > 0");
  }
  for (const std::string& e : {ValidateImpulseTimes(t, impulse_times),
                               ValidateSpin(*this),
                               ValidateOrientation(*this),
                               ValidateBodyRate(*this)})
    if (!e.empty()) return e;
  return {};
}

std::string IdentifyOptions::Validate() const {
  using internal::InvalidValueMessage;
  if (!(std::isfinite(radius) && radius > 0)) return InvalidValueMessage("radius", radius, "must be finite and > 0");
  if (!(lambda_min >= 1e-3 && lambda_min <= 1e3))
    return InvalidValueMessage("lambda_min", lambda_min, "must be in [0.001, 1000]");
  if (!(lambda_max >= lambda_min && lambda_max <= 1e3))
    return InvalidValueMessage("lambda_max", lambda_max, "must be in [lambda_min, 1000]");
  if (theta_starts < 1 || theta_starts > 50)
    return InvalidValueMessage("theta_starts", theta_starts, "must be in [1, 50]");
  if (phase_starts < 1 || phase_starts > 50)
    return InvalidValueMessage("phase_starts", phase_starts, "must be in [1, 50]");
  if (lambda_starts.empty() || lambda_starts.size() > 20)
    return InvalidValueMessage("lambda_starts (count)", lambda_starts.size(), "must be 1 ... 20 values");
  for (std::size_t i = 0; i < lambda_starts.size(); ++i)
    if (!(lambda_starts[i] >= lambda_min && lambda_starts[i] <= lambda_max))
      return InvalidValueMessage(
          "lambda_starts[" + std::to_string(i) + "]", lambda_starts[i], "must be in [lambda_min, lambda_max]");
  if (guess) {
    if (!(guess->lambda >= lambda_min && guess->lambda <= lambda_max))
      return InvalidValueMessage("guess.lambda", guess->lambda, "must be in [lambda_min, lambda_max]");
    if (!(std::isfinite(guess->mu) && guess->mu > 0))
      return InvalidValueMessage("guess.mu", guess->mu, "must be finite and > 0");
    const double g[5] = {guess->angles.theta, guess->angles.phi, guess->angles.psi, guess->x0.x(), guess->x0.y()};
    const char* names[5] = {"guess.theta", "guess.phi", "guess.psi", "guess.x0[0]", "guess.x0[1]"};
    for (int i = 0; i < 5; ++i)
      if (!std::isfinite(g[i])) return InvalidValueMessage(names[i], g[i], "must be finite");
  }
  if (max_iterations < 1 || max_iterations > 10000)
    return InvalidValueMessage("max_iterations", max_iterations, "must be in [1, 10000]");
  if (threads < 1 || threads > kMaxThreads)
    return InvalidValueMessage("threads", threads, "must be in [1, " + std::to_string(kMaxThreads) + "]");
  if (!(max_lambda_relative_error > 0 && max_lambda_relative_error <= 1e6))
    return InvalidValueMessage("max_lambda_relative_error", max_lambda_relative_error, "must be in (0, 1e6]");
  if (!(no_fit_significance > 0 && no_fit_significance < 1))
    return InvalidValueMessage("no_fit_significance", no_fit_significance, "must be in (0, 1)");
  if (!(max_relative_residual > 0 && max_relative_residual <= 1))
    return InvalidValueMessage("max_relative_residual", max_relative_residual, "must be in (0, 1]");
  const std::string integration_error = integration.Validate();
  return integration_error.empty() ? std::string() : "integration." + integration_error;
}

std::string IdentifySummary::BriefReport() const {
  std::ostringstream os;
  os << "identify: " << ToString(status) << " (" << message << ")";
  if (status == IdentifyStatus::kIdentified || status == IdentifyStatus::kLambdaNotIdentified) {
    os << "; lambda " << lambda;
    if (!standard_errors.empty()) os << " +- " << standard_errors[0];
    if (status == IdentifyStatus::kIdentified && !interval_method.empty())
      os << " (95% " << interval_method << " interval [" << lambda_low << ", " << lambda_high << "])";
    os << ", mu " << mu;
    if (!standard_errors.empty()) os << " +- " << standard_errors[1];
  }
  os << "; rms residual " << rms_residual << " over " << samples << " samples";
  return os.str();
}

namespace {

using internal::TrackData;

/// The track in model units: times relative to the first, positions over the radius, weights.
TrackData MakeTrackData(const IdentifyProblem& problem, const IdentifyOptions& options) {
  TrackData d;
  const std::size_t n = problem.t.size();
  d.tau.resize(n);
  d.x.resize(2 * n);
  d.weight.assign(n, 1.0);
  for (std::size_t i = 0; i < n; ++i) {
    d.tau[i] = problem.t[i] - problem.t[0];
    d.x[2 * i] = problem.x[i].x() / options.radius;
    d.x[2 * i + 1] = problem.x[i].y() / options.radius;
    if (!problem.sigma.empty()) d.weight[i] = options.radius / problem.sigma[i];
  }
  for (double t : problem.impulse_times) d.impulse_tau.push_back(t - problem.t[0]);
  d.spin = problem.spin;  // rad per time unit: the time is not scaled, nor is v0 by the radius
  for (double sigma : problem.sigma_spin) d.spin_weight.push_back(1.0 / sigma);
  for (std::size_t i = 0; i < problem.orientation.size(); ++i) {
    const Eigen::Vector4d& q = problem.orientation[i];
    double a[9];
    internal::RowMajorFromMatrix(QuaternionToRotation(q, "orientation[" + std::to_string(i) + "]"), a);
    d.orientation.insert(d.orientation.end(), a, a + 9);
    d.orientation_weight.push_back(problem.sigma_orientation.empty() ? 1.0 : 1.0 / problem.sigma_orientation[i]);
  }
  for (std::size_t i = 0; i < problem.body_rate.size(); ++i) {
    d.body_rate.insert(d.body_rate.end(), problem.body_rate[i].data(), problem.body_rate[i].data() + 3);
    d.body_rate_weight.push_back(1.0 / problem.sigma_body_rate[i]);
  }
  return d;
}

double TrackSpread(const TrackData& d) {
  const std::size_t n = d.tau.size();
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (std::size_t i = 0; i < n; ++i) mean += Eigen::Vector2d(d.x[2 * i], d.x[2 * i + 1]);
  mean /= static_cast<double>(n);
  double s = 0;
  for (std::size_t i = 0; i < n; ++i) s += (Eigen::Vector2d(d.x[2 * i], d.x[2 * i + 1]) - mean).squaredNorm();
  return std::sqrt(s / static_cast<double>(n));
}

/// R as the unit quaternion (w, x, y, z) with w >= 0.
Eigen::Vector4d QuaternionOf(const Eigen::Matrix3d& r) {
  Eigen::Quaterniond q(r);
  q.normalize();
  const double sign = q.w() < 0 ? -1.0 : 1.0;
  return sign * Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
}

/// The orientation and body-rate parts of the residual statistics.
void FillFrameResiduals(const TrackData& d, const internal::TrackFit& fit, IdentifySummary* s) {
  using RowMajor3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
  const std::size_t no = d.orientation.size() / 9, nb = d.body_rate.size() / 3;
  double sum2 = 0.0;
  s->fitted_orientation.clear();
  s->orientation_max_residual = 0.0;
  for (std::size_t i = 0; i < no; ++i) {
    const Eigen::Matrix3d model = Eigen::Map<const RowMajor3>(fit.orientation.data() + 9 * i);
    const Eigen::Matrix3d measured = Eigen::Map<const RowMajor3>(d.orientation.data() + 9 * i);
    s->fitted_orientation.push_back(QuaternionOf(model));
    const double angle = LogSO3(measured.transpose() * model).norm();
    sum2 += angle * angle;
    s->orientation_max_residual = std::max(s->orientation_max_residual, angle);
  }
  s->orientation_rms_residual = no > 0 ? std::sqrt(sum2 / static_cast<double>(3 * no)) : 0.0;
  sum2 = 0.0;
  s->fitted_body_rate.clear();
  s->body_rate_max_residual = 0.0;
  for (std::size_t i = 0; i < nb; ++i) {
    const Eigen::Vector3d model(fit.body_rate.data() + 3 * i), measured(d.body_rate.data() + 3 * i);
    s->fitted_body_rate.push_back(model);
    sum2 += (model - measured).squaredNorm();
    s->body_rate_max_residual = std::max(s->body_rate_max_residual, (model - measured).norm());
  }
  s->body_rate_rms_residual = nb > 0 ? std::sqrt(sum2 / static_cast<double>(3 * nb)) : 0.0;
}

/// Residual statistics of the fit at q (unweighted residuals in radii, chi^2 weighted).
void FillResiduals(const TrackData& d, const internal::TrackFit& fit, IdentifySummary* s) {
  const std::size_t n = d.tau.size();
  s->fitted.resize(n);
  double sum2 = 0, max_r = 0;
  for (std::size_t i = 0; i < n; ++i) {
    s->fitted[i] = Eigen::Vector2d(fit.model[2 * i], fit.model[2 * i + 1]);
    const double r = (s->fitted[i] - Eigen::Vector2d(d.x[2 * i], d.x[2 * i + 1])).norm();
    sum2 += r * r;
    max_r = std::max(max_r, r);
  }
  s->samples = static_cast<int>(n);
  s->rms_residual = std::sqrt(sum2 / static_cast<double>(2 * n));
  s->max_residual = max_r;
  s->residuals = static_cast<int>(internal::ResidualCount(d));
  s->chi_square = 2.0 * fit.cost;
  s->fitted_spin = fit.spin;
  double spin2 = 0.0;
  s->spin_max_residual = 0.0;
  for (std::size_t i = 0; i < d.spin.size(); ++i) {
    spin2 += std::pow(fit.spin[i] - d.spin[i], 2);
    s->spin_max_residual = std::max(s->spin_max_residual, std::abs(fit.spin[i] - d.spin[i]));
  }
  s->spin_rms_residual = d.spin.empty() ? 0.0 : std::sqrt(spin2 / static_cast<double>(d.spin.size()));
  FillFrameResiduals(d, fit, s);
  s->track_spread = TrackSpread(d);
}

/// Standard errors and correlations from the weighted Jacobian at the optimum: cov = s^2 (J^T J)^-1,
/// s^2 = chi^2 / (m - p) when sigma is estimated, 1 when given. Singular directions of the
/// column-scaled J^T J get infinite errors for the parameters they involve.
void FillCovariance(const internal::TrackFit& fit, double s2, IdentifySummary* s) {
  const int np = static_cast<int>(fit.q.size());
  const Eigen::MatrixXd jtj = fit.jacobian.transpose() * fit.jacobian;
  Eigen::VectorXd scale = jtj.diagonal().cwiseSqrt();
  for (int i = 0; i < np; ++i)
    if (!(scale[i] > 0)) scale[i] = 1.0;
  const Eigen::MatrixXd c = scale.cwiseInverse().asDiagonal() * jtj * scale.cwiseInverse().asDiagonal();
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(c);
  const Eigen::VectorXd ev = eig.eigenvalues();
  s->scaled_condition = ev.maxCoeff() > 0 ? std::max(0.0, ev.minCoeff() / ev.maxCoeff()) : 0.0;
  Eigen::MatrixXd inv = Eigen::MatrixXd::Zero(np, np);
  std::vector<bool> singular(static_cast<std::size_t>(np), false);
  for (int k = 0; k < np; ++k) {
    const Eigen::VectorXd v = eig.eigenvectors().col(k);
    if (ev[k] > kSingularRatio * ev.maxCoeff()) {
      inv += v * v.transpose() / ev[k];
    } else {
      for (int i = 0; i < np; ++i)
        if (std::abs(v[i]) > 1e-3) singular[static_cast<std::size_t>(i)] = true;
    }
  }
  const Eigen::MatrixXd cov = s2 * scale.cwiseInverse().asDiagonal() * inv * scale.cwiseInverse().asDiagonal();
  s->standard_errors.assign(static_cast<std::size_t>(np), 0.0);
  s->correlation = Eigen::MatrixXd::Constant(np, np, kNaN);
  for (int i = 0; i < np; ++i) {
    s->standard_errors[static_cast<std::size_t>(i)] =
        singular[static_cast<std::size_t>(i)] ? kInf : std::sqrt(cov(i, i));
    for (int j = 0; j < np; ++j)
      if (!singular[static_cast<std::size_t>(i)] && !singular[static_cast<std::size_t>(j)])
        s->correlation(i, j) = cov(i, j) / std::sqrt(cov(i, i) * cov(j, j));
  }
}

/// The largest distance of the points [begin, end) from their principal axis.
double LineDeviation(const std::vector<Eigen::Vector2d>& points, std::size_t begin, std::size_t end) {
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (std::size_t i = begin; i < end; ++i) mean += points[i];
  mean /= static_cast<double>(end - begin);
  Eigen::Matrix2d scatter = Eigen::Matrix2d::Zero();
  for (std::size_t i = begin; i < end; ++i) scatter += (points[i] - mean) * (points[i] - mean).transpose();
  const Eigen::Vector2d normal = Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(scatter).eigenvectors().col(0);
  double deviation = 0.0;
  for (std::size_t i = begin; i < end; ++i) deviation = std::max(deviation, std::abs((points[i] - mean).dot(normal)));
  return deviation;
}

/// path_deviation and straight_path of the fitted path (identify.h): the distance of each
/// flight's fitted points from their principal axis, against the noise.
void FillStraightness(const std::vector<double>& t, IdentifySummary* s) {
  s->path_deviation = 0.0;
  std::size_t begin = 0;
  for (std::size_t k = 0; k <= s->impulse_times.size(); ++k) {
    std::size_t end = begin;
    while (end < t.size() && (k == s->impulse_times.size() || t[end] <= s->impulse_times[k])) ++end;
    if (end > begin) s->path_deviation = std::max(s->path_deviation, LineDeviation(s->fitted, begin, end));
    begin = end;
  }
  s->straight_path = s->path_deviation <= std::max(kStraightPathNoise * s->sigma, kNoiselessResidual);
}

/// The names of the p fitted parameters: kIdentifyParameterNames, "chi" with the frame, then
/// "delta_psi[k]".
std::vector<std::string> ParameterNames(bool frame, std::size_t p) {
  std::vector<std::string> names(kIdentifyParameterNames, kIdentifyParameterNames + kP);
  if (frame) names.emplace_back("chi");
  for (std::size_t k = 0; names.size() < p; ++k) names.push_back("delta_psi[" + std::to_string(k) + "]");
  return names;
}

/// With a measured spin: true when it shows v0 != 0, i.e. the hypothesis v0 = 0 at every sample
/// is rejected against the fit at 95% (its spin chi-square exceeds the fit's by chi^2_1's
/// quantile). A straight path with v0 != 0 is then the lambda = 1 one, not the v0 = 0 family in
/// which every lambda gives the same motion, and lambda's verdict comes from its standard error.
bool SpinShowsAxialSpin(const TrackData& d, const internal::TrackFit& fit) {
  if (d.spin.empty()) return false;
  double zero = 0.0, fitted = 0.0;
  for (std::size_t i = 0; i < d.spin.size(); ++i) {
    zero += std::pow(d.spin_weight[i] * d.spin[i], 2);
    fitted += std::pow(d.spin_weight[i] * (fit.spin[i] - d.spin[i]), 2);
  }
  return zero - fitted > boost::math::quantile(boost::math::chi_squared_distribution<double>(1.0), 0.95);
}

/// True when the straight path leaves lambda unidentifiable (identify.h, straight_path).
bool StraightBlocksLambda(const IdentifySummary& s, bool spin_shows_v0) { return s.straight_path && !spin_shows_v0; }

void FillUnidentified(bool spin_shows_v0, IdentifySummary* s) {
  const auto& e = s->standard_errors;
  std::vector<double> scaled{e[0] / s->lambda,
                             e[1] / s->mu,
                             e[2],
                             e[3],
                             e[4],
                             e[5] / std::max(s->track_spread, 1e-300),
                             e[6] / std::max(s->track_spread, 1e-300)};
  scaled.insert(scaled.end(), e.begin() + kP, e.end());  // chi and delta psi: radians, like the angles
  for (std::size_t i = 0; i < scaled.size(); ++i)
    if (!(scaled[i] <= kHugeError) || (i == 0 && StraightBlocksLambda(*s, spin_shows_v0)))
      s->unidentified.push_back(s->parameters[i]);
}

/// The profile threshold of a 95% interval: chi^2_1 with given sigma, F(1, m - p) with estimated.
double ProfileThreshold(bool sigma_estimated, int dof) {
  if (!sigma_estimated) return boost::math::quantile(boost::math::chi_squared_distribution<double>(1.0), 0.95);
  return boost::math::quantile(boost::math::fisher_f_distribution<double>(1.0, dof), 0.95);
}

/// True when the chi^2 (given sigma) or the RMS residual (estimated) rejects the model.
bool RejectsFit(const IdentifySummary& s, const IdentifyOptions& o, int dof, std::string* why) {
  std::ostringstream os;
  if (!s.sigma_estimated) {
    const double p =
        boost::math::cdf(boost::math::complement(boost::math::chi_squared_distribution<double>(dof), s.chi_square));
    os << "chi-square " << s.chi_square << " on " << dof << " degrees of freedom (p = " << p << " < "
       << o.no_fit_significance << ")";
    *why = os.str();
    return p < o.no_fit_significance;
  }
  os << "rms residual " << s.rms_residual << " radii > " << o.max_relative_residual << " x the track's spread "
     << s.track_spread;
  *why = os.str();
  return s.rms_residual > o.max_relative_residual * s.track_spread;
}

void FillFit(const internal::TrackFit& fit, bool frame, IdentifySummary* s) {
  s->lambda = fit.q[0];
  s->mu = fit.q[1];
  s->angles = AngleState{fit.q[2], fit.q[3], fit.q[4]}.Canonicalize();
  s->x0 = Eigen::Vector2d(fit.q[5], fit.q[6]);
  s->period = 2.0 * M_PI / std::sqrt(s->mu);
  s->iterations = fit.iterations;
  s->delta_psi.clear();
  const std::size_t first_impulse = kP + (frame ? 1 : 0);
  for (std::size_t k = first_impulse; k < fit.q.size(); ++k) s->delta_psi.push_back(internal::WrapPi(fit.q[k]));
  s->frame_fitted = frame;
  s->parameters = ParameterNames(frame, fit.q.size());
  if (frame) s->orientation = QuaternionOf(internal::StartFrame(fit.q[2], fit.q[3], fit.q[7]));
}

/// The fitted state at each flight's start (the flights of the model at the optimum).
void FillFlights(const TrackData& d,
                 const internal::TrackFit& fit,
                 const IntegrationOptions& integration,
                 IdentifySummary* s) {
  if (d.impulse_tau.empty()) {  // one flight: the state at t_ref
    s->flights = {IdentifiedFlight{s->t_ref, s->angles, s->x0}};
    return;
  }
  std::vector<double> model(d.x.size());
  std::vector<internal::FlightStart> flights;
  internal::EvaluateImpulsiveTrack(
      fit.q.data(), d.tau.data(), d.tau.size(), d.impulse_tau, integration, model.data(), nullptr, nullptr, &flights);
  const BallModel ball = BallModel::FromLambda(s->lambda);
  s->flights.clear();
  for (const internal::FlightStart& f : flights) {
    // The integrated axis drifts from unit length by the integration error: the chart wants |z| = 1.
    const Eigen::Vector3d z = f.z.normalized();
    const BallState state{z, OmegaFromMomentum(z, f.k, ball)};
    s->flights.push_back({s->t_ref + f.tau, AnglesFromState(state, ball), f.x});
  }
}

/// Decides identified / not identified from the standard error and the profile interval.
void Classify(const IdentifyOptions& o, bool spin_shows_v0, IdentifySummary* s) {
  s->lambda_relative_error = s->standard_errors[0] / s->lambda;
  const bool closed = s->lambda_low > 0 && std::isfinite(s->lambda_high);
  const bool straight = StraightBlocksLambda(*s, spin_shows_v0);
  s->lambda_identified =
      !straight && s->lambda_relative_error <= o.max_lambda_relative_error && (closed || !o.profile_interval);
  std::ostringstream os;
  if (straight) {
    s->status = IdentifyStatus::kLambdaNotIdentified;
    os << "lambda not identified, not identifiable from the contact track alone: the fitted contact path is a straight "
          "line (largest "
          "deviation "
       << s->path_deviation << " radii, within the noise " << s->sigma
       << "). Every lambda gives a straight path when the axial spin v0 is 0, and every state gives one at lambda = 1 "
          "(the ball rolls like a sphere), so the track fixes the speed but not lambda; a track with a curved, "
          "drifting contact path identifies lambda, and so do a measured spin v0 != 0, orientations or body rates "
          "(docs/identify.md)"
       << (s->fitted_spin.empty() ? "" : "; the measured spin does not show v0 != 0");
  } else if (s->lambda_identified) {
    s->status = IdentifyStatus::kIdentified;
    os << "lambda identified: relative standard error " << s->lambda_relative_error;
  } else {
    s->status = IdentifyStatus::kLambdaNotIdentified;
    os << "lambda not identified: relative standard error " << s->lambda_relative_error
       << (closed || !o.profile_interval ? "" : ", the 95% profile interval does not close in [lambda_min, lambda_max]")
       << "; the track fixes mu (the period 2 pi/sqrt(mu)) and the state but carries (almost) no information on "
          "lambda (docs/identify.md: a track with axial spin v0 != 0, i.e. a curved, drifting contact path, does, and "
          "so do "
          "measured orientations or body rates, whose reorientation along the path depends on lambda)";
  }
  s->message = os.str();
}

}  // namespace

IdentifySummary Identify(const IdentifyProblem& problem, const IdentifyOptions& options) {
  internal::ThrowIfInvalid(problem.Validate());
  internal::ThrowIfInvalid(options.Validate());
  if (options.guess && options.guess->delta_psi.size() > problem.impulse_times.size())
    internal::ThrowInvalid("guess.delta_psi (count)",
                           static_cast<double>(options.guess->delta_psi.size()),
                           "more values than impulse_times (" + std::to_string(problem.impulse_times.size()) + ")");
  if (options.guess)
    for (std::size_t k = 0; k < options.guess->delta_psi.size(); ++k)
      if (!std::isfinite(options.guess->delta_psi[k]))
        internal::ThrowInvalid(
            "guess.delta_psi[" + std::to_string(k) + "]", options.guess->delta_psi[k], "must be finite");
  const TrackData data = MakeTrackData(problem, options);
  IdentifySummary s;
  s.t_ref = problem.t[0];
  s.impulse_times = problem.impulse_times;
  s.sigma_estimated = problem.sigma.empty();
  try {
    internal::TrackFit fit = internal::FitTrack(data, options, &s.starts);
    FillFit(fit, data.HasFrame(), &s);
    FillFlights(data, fit, options.integration, &s);
    FillResiduals(data, fit, &s);
    const int dof = s.residuals - static_cast<int>(fit.q.size());
    const double s2 = s.sigma_estimated ? s.chi_square / dof : 1.0;
    s.sigma = s.sigma_estimated ? std::sqrt(s2) : 0.0;
    if (!s.sigma_estimated) {
      for (double v : problem.sigma) s.sigma += v / options.radius;
      s.sigma /= static_cast<double>(problem.sigma.size());
    }
    std::string why;
    if (RejectsFit(s, options, dof, &why)) {
      s.status = IdentifyStatus::kNoFit;
      s.message = "no free motion fits the track: " + why;
      return s;
    }
    FillCovariance(fit, s2, &s);
    FillStraightness(problem.t, &s);
    // Orientations and body rates see v0 and the reorientation themselves: the standard error decides.
    const bool spin_shows_v0 = data.HasFrame() || SpinShowsAxialSpin(data, fit);
    FillUnidentified(spin_shows_v0, &s);
    s.lambda_low = s.lambda_high = kNaN;
    if (options.profile_interval && std::isfinite(s.standard_errors[0]) && s.rms_residual < kNoiselessResidual) {
      // A noiseless track: the profile would resolve the integration's round-off, not a noise.
      s.lambda_low = s.lambda - 1.96 * s.standard_errors[0];
      s.lambda_high = s.lambda + 1.96 * s.standard_errors[0];
      s.interval_method = "wald";
    } else if (options.profile_interval && std::isfinite(s.standard_errors[0])) {
      const internal::ProfileInterval pi = internal::ProfileLambda(
          data, options, fit, s.standard_errors[0], ProfileThreshold(s.sigma_estimated, dof) * s2);
      s.lambda_low = pi.low;
      s.lambda_high = pi.high;
      s.profile_fits = pi.fits;
      s.interval_method = "profile";
    } else if (options.profile_interval) {
      s.lambda_low = 0.0;
      s.lambda_high = kInf;
      s.interval_method = "profile";
    }
    Classify(options, spin_shows_v0, &s);
  } catch (const std::exception& e) {
    s.status = IdentifyStatus::kFailed;
    s.message = std::string("the fit failed: ") + e.what();
  }
  return s;
}

}  // namespace plateball
