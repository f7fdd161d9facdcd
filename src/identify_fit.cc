#include "identify_fit.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>
#include <vector>

#include "identify_model.h"
#include "kinematics.h"
#include "parallel_for.h"
#include "plateball/so3.h"

namespace plateball::internal {
namespace {

constexpr int kP = kTrackParameters;  // the parameters without chi and the impulses
constexpr double kInf = std::numeric_limits<double>::infinity();
// The multi-start and the window continuation only have to land in the right basin: looser
// tolerances, few samples per window.
constexpr double kStartTolerance = 1e-6;
// The grid of starts only has to reach a basin: a coarser tolerance still.
constexpr double kGridTolerance = 1e-5;
constexpr int kStartIterations = 10;
constexpr int kGridIterations = 8;
constexpr std::size_t kMaxCandidates = 3;
constexpr double kCandidateCost = 1.5;
constexpr double kStartCandidateCost = 10.0;
constexpr double kDistinctLambda = 0.1;
constexpr std::size_t kStartSamples = 50;
constexpr std::size_t kWindowSamples = 400;
// The first window: half a guessed period (every start sees the same arc of the orbit), and at
// least this many samples.
constexpr double kFirstWindowPeriods = 0.5;
constexpr std::size_t kMinWindowSamples = 12;
// mu is bounded to the problem files' range (schemas/input/problem.schema.json).
constexpr double kMuMin = 1e-12, kMuMax = 1e12;
// The variational equations of the Jacobian: 1e-8 gives the derivatives to ~1e-7 relative, ample
// for Levenberg-Marquardt and the standard errors; the residuals keep the full tolerance.
constexpr double kJacobianTolerance = 1e-8;
// The grid of delta psi tried for an impulse that enters the fit (ChooseImpulse): the contact
// velocity after the impulse turns along its velocity ellipse with delta psi, so 24 values
// (15 degrees apart) put one within the basin of the least-squares fit.
constexpr int kImpulseGrid = 24;
// Impulses a window may add to the last (NextWindow): each new flight's delta psi is chosen from
// the states fitted so far, so the fit goes on after every few flights.
constexpr std::size_t kImpulsesPerWindow = 2;
// The profile refits' integration tolerance as a fraction of the RMS residual (ProfileLambda).
constexpr double kProfileNoiseFraction = 1e-4;
constexpr double kProfileMaxTolerance = 1e-7;

/// The parameters of the start: the 7, and chi with the frame.
std::size_t StartCount(const TrackData& d) { return kP + (d.HasFrame() ? 1 : 0); }

/// The number of fitted parameters: those of the start and one delta psi per impulse.
std::size_t ParameterCount(const TrackData& d) { return StartCount(d) + d.impulse_tau.size(); }

IntegrationOptions JacobianOptions(const IntegrationOptions& o) {
  return {std::max(kJacobianTolerance, o.absolute_tolerance),
          std::max(kJacobianTolerance, o.relative_tolerance),
          o.max_steps};
}

/// The model's values at q (TrackFit's model, spin, orientation, body_rate).
struct ModelValues {
  std::vector<double> x, spin, orientation, body_rate;
};

/// The inverse of SO(3)'s right Jacobian at the rotation vector e: Log(R Exp(d)) = Log(R) +
/// JrInv(Log R) d + O(d^2).
Eigen::Matrix3d RightJacobianInverse(const Eigen::Vector3d& e) {
  const double a = e.norm();
  // (1/a^2 - (1 + cos a)/(2 a sin a)), its series 1/12 + a^2/720 near 0 (cancellation).
  const double c =
      a < 1e-4 ? 1.0 / 12.0 + a * a / 720.0 : 1.0 / (a * a) - (1.0 + std::cos(a)) / (2.0 * a * std::sin(a));
  const Eigen::Matrix3d h = Hat(e);
  return Eigen::Matrix3d::Identity() + 0.5 * h + c * h * h;
}

/// The unweighted residuals at q into *r (model - measured; for the orientation
/// LogSO3(A_i^T A(tau_i))), the model's values into *m, and with jacobian != nullptr dr/dq
/// row-major (ResidualCount x ParameterCount). Throws when an integration fails.
void EvaluateModel(const TrackData& d,
                   const double* q,
                   const IntegrationOptions& o,
                   ModelValues* m,
                   std::vector<double>* r,
                   std::vector<double>* jacobian) {
  const std::size_t n = d.tau.size(), p = ParameterCount(d), ns = d.spin.size();
  const std::size_t no = d.orientation.size() / 9, nb = d.body_rate.size() / 3;
  m->x.resize(2 * n);
  m->spin.resize(ns);
  m->orientation.resize(9 * no);
  m->body_rate.resize(3 * nb);
  if (jacobian != nullptr) jacobian->resize(ResidualCount(d) * p);
  double* j = jacobian != nullptr ? jacobian->data() : nullptr;
  const std::size_t row_spin = 2 * n, row_orientation = row_spin + ns, row_rate = row_orientation + 3 * no;
  auto part = [&](std::vector<double>& v, std::size_t row) {
    return v.empty() ? nullptr : (j != nullptr ? j + row * p : nullptr);
  };
  BodyOutput body;
  body.spin = ns > 0 ? m->spin.data() : nullptr;
  body.spin_jacobian = ns > 0 ? part(m->spin, row_spin) : nullptr;
  body.orientation = no > 0 ? m->orientation.data() : nullptr;
  body.orientation_jacobian = no > 0 ? part(m->orientation, row_orientation) : nullptr;
  body.body_rate = nb > 0 ? m->body_rate.data() : nullptr;
  body.body_rate_jacobian = nb > 0 ? part(m->body_rate, row_rate) : nullptr;
  const IntegrationOptions jo = JacobianOptions(o);
  EvaluateImpulsiveTrack(
      q, d.tau.data(), n, d.impulse_tau, o, m->x.data(), j, &jo, nullptr, ns + no + nb > 0 ? &body : nullptr);
  r->resize(ResidualCount(d));
  for (std::size_t k = 0; k < 2 * n; ++k) (*r)[k] = m->x[k] - d.x[k];
  for (std::size_t k = 0; k < ns; ++k) (*r)[row_spin + k] = m->spin[k] - d.spin[k];
  using RowMajor3 = Eigen::Matrix<double, 3, 3, Eigen::RowMajor>;
  for (std::size_t i = 0; i < no; ++i) {
    const Eigen::Matrix3d measured = Eigen::Map<const RowMajor3>(d.orientation.data() + 9 * i);
    const Eigen::Matrix3d model = Eigen::Map<const RowMajor3>(m->orientation.data() + 9 * i);
    const Eigen::Vector3d e = LogSO3(measured.transpose() * model);
    Eigen::Map<Eigen::Vector3d>(r->data() + row_orientation + 3 * i) = e;
    if (j == nullptr) continue;
    using Rows = Eigen::Matrix<double, 3, Eigen::Dynamic, Eigen::RowMajor>;
    Eigen::Map<Rows> rows(j + (row_orientation + 3 * i) * p, 3, static_cast<Eigen::Index>(p));
    rows = RightJacobianInverse(e) * Rows(rows);
  }
  for (std::size_t k = 0; k < 3 * nb; ++k) (*r)[row_rate + k] = m->body_rate[k] - d.body_rate[k];
}

/// The weight of residual k: 1/sigma of its sample's position, then 1/sigma_spin,
/// 1/sigma_orientation, 1/sigma_body_rate.
double Weight(const TrackData& d, std::size_t k) {
  const std::size_t n2 = 2 * d.tau.size();
  if (k < n2) return d.weight[k / 2];
  k -= n2;
  if (k < d.spin.size()) return d.spin_weight[k];
  k -= d.spin.size();
  if (k < d.orientation.size() / 3) return d.orientation_weight[k / 3];
  return d.body_rate_weight[(k - d.orientation.size() / 3) / 3];
}

/// The weighted residuals and their exact Jacobian, parameter blocks lambda (1) and (mu, theta,
/// phi, psi, x0, y0, delta_psi...) (6 + m), so that the profile can hold lambda constant.
class TrackCost final : public ceres::CostFunction {
 public:
  TrackCost(const TrackData& data, const IntegrationOptions& options)
      : data_(data), options_(options), p_(ParameterCount(data)) {
    set_num_residuals(static_cast<int>(ResidualCount(data)));
    mutable_parameter_block_sizes()->push_back(1);
    mutable_parameter_block_sizes()->push_back(static_cast<int>(p_ - 1));
  }
  bool Evaluate(double const* const* p, double* residuals, double** jacobians) const override {
    std::vector<double> q{p[0][0]};
    q.insert(q.end(), p[1], p[1] + (p_ - 1));
    const bool want_j = jacobians != nullptr && (jacobians[0] != nullptr || jacobians[1] != nullptr);
    ModelValues model;
    std::vector<double> r, j;
    try {
      EvaluateModel(data_, q.data(), options_, &model, &r, want_j ? &j : nullptr);
    } catch (const std::exception&) {
      return false;  // an integration failure rejects the step (Ceres shrinks the trust region)
    }
    for (std::size_t k = 0; k < ResidualCount(data_); ++k) {
      const double w = Weight(data_, k);
      residuals[k] = w * r[k];
      if (!want_j) continue;
      if (jacobians[0] != nullptr) jacobians[0][k] = w * j[k * p_];
      if (jacobians[1] != nullptr)
        for (std::size_t c = 1; c < p_; ++c) jacobians[1][k * (p_ - 1) + c - 1] = w * j[k * p_ + c];
    }
    return true;
  }

 private:
  const TrackData& data_;
  IntegrationOptions options_;
  std::size_t p_;
};

/// One Levenberg-Marquardt fit from q (lambda held at q[0] when fixed).
TrackFit Solve(const TrackData& data,
               const std::vector<double>& q0,
               const IdentifyOptions& o,
               const IntegrationOptions& integration,
               int max_iterations,
               bool lambda_fixed) {
  TrackFit fit;
  if (q0.size() < ParameterCount(data))
    throw std::logic_error("Solve: a delta psi of the window's impulses is not chosen");
  fit.q.assign(q0.begin(), q0.begin() + static_cast<std::ptrdiff_t>(ParameterCount(data)));
  double* lambda = fit.q.data();
  double* rest = fit.q.data() + 1;
  ceres::Problem problem;
  problem.AddResidualBlock(new TrackCost(data, integration), nullptr, lambda, rest);
  problem.SetParameterLowerBound(lambda, 0, o.lambda_min);
  problem.SetParameterUpperBound(lambda, 0, o.lambda_max);
  problem.SetParameterLowerBound(rest, 0, kMuMin);
  problem.SetParameterUpperBound(rest, 0, kMuMax);
  if (lambda_fixed) problem.SetParameterBlockConstant(lambda);
  ceres::Solver::Options so;
  so.linear_solver_type = ceres::DENSE_QR;
  so.max_num_iterations = max_iterations;
  so.function_tolerance = 1e-12;
  so.gradient_tolerance = 1e-16;
  so.parameter_tolerance = 1e-13;
  so.num_threads = 1;
  so.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(so, &problem, &summary);
  fit.cost = summary.final_cost;
  fit.iterations = static_cast<int>(summary.iterations.size());
  if (!std::isfinite(fit.cost)) fit.cost = std::numeric_limits<double>::infinity();
  return fit;
}

/// The samples with tau <= tau_max (at least kMinWindowSamples, or the first flight's samples when
/// it has fewer), thinned evenly to <= max_samples, with the impulses before its last sample.
TrackData Window(const TrackData& d, double tau_max, std::size_t max_samples) {
  std::size_t end = 0, first_flight = 0;
  while (end < d.tau.size() && d.tau[end] <= tau_max) ++end;
  while (first_flight < d.tau.size() && (d.impulse_tau.empty() || d.tau[first_flight] <= d.impulse_tau[0]))
    ++first_flight;
  end = std::min(d.tau.size(), std::max(end, std::min(kMinWindowSamples, first_flight)));
  const std::size_t stride = (end + max_samples - 1) / max_samples;
  TrackData w;
  auto take = [&](std::size_t i) {
    w.tau.push_back(d.tau[i]);
    w.x.push_back(d.x[2 * i]);
    w.x.push_back(d.x[2 * i + 1]);
    w.weight.push_back(d.weight[i]);
    if (!d.spin.empty()) {
      w.spin.push_back(d.spin[i]);
      w.spin_weight.push_back(d.spin_weight[i]);
    }
    if (!d.orientation.empty()) {
      w.orientation.insert(w.orientation.end(),
                           d.orientation.begin() + static_cast<std::ptrdiff_t>(9 * i),
                           d.orientation.begin() + static_cast<std::ptrdiff_t>(9 * i + 9));
      w.orientation_weight.push_back(d.orientation_weight[i]);
    }
    if (!d.body_rate.empty()) {
      w.body_rate.insert(w.body_rate.end(),
                         d.body_rate.begin() + static_cast<std::ptrdiff_t>(3 * i),
                         d.body_rate.begin() + static_cast<std::ptrdiff_t>(3 * i + 3));
      w.body_rate_weight.push_back(d.body_rate_weight[i]);
    }
  };
  for (std::size_t i = 0; i < end; i += stride) take(i);
  // With impulses the last sample is kept, so that the window sees every flight it reaches.
  if (!d.impulse_tau.empty() && w.tau.back() < d.tau[end - 1]) take(end - 1);
  for (double t : d.impulse_tau)
    if (t < w.tau.back()) w.impulse_tau.push_back(t);
  return w;
}

/// 1/2 sum of the squared weighted residuals at q.
double Cost(const TrackData& d, const std::vector<double>& q, const IntegrationOptions& integration) {
  ModelValues model;
  std::vector<double> r;
  EvaluateModel(d, q.data(), integration, &model, &r, nullptr);
  double c = 0.0;
  for (std::size_t k = 0; k < ResidualCount(d); ++k) c += std::pow(Weight(d, k) * r[k], 2);
  return 0.5 * c;
}

/// Extends q (the start and the delta psi of the impulses decided so far) to the first `count`
/// impulses of d. Each new impulse gets the best of kImpulseGrid values of delta psi in
/// [-pi, pi) by the cost of the samples up to the next impulse (whose delta psi is not known
/// yet), the earlier parameters held: the least-squares fit then starts in its basin.
void ChooseImpulses(const TrackData& d,
                    std::size_t count,
                    const IntegrationOptions& integration,
                    std::vector<double>* q) {
  while (q->size() < StartCount(d) + count) {
    const std::size_t f = q->size() - StartCount(d);
    const double until = f + 1 < d.impulse_tau.size() ? d.impulse_tau[f + 1] : d.tau.back();
    const TrackData w = Window(d, until, kWindowSamples);
    double best_cost = std::numeric_limits<double>::infinity(), best = 0.0;
    q->push_back(0.0);
    for (int k = 0; k < kImpulseGrid; ++k) {
      q->back() = -M_PI + kTwoPi * k / kImpulseGrid;
      double c = std::numeric_limits<double>::infinity();
      try {
        c = Cost(w, *q, integration);
      } catch (const std::exception&) {
        continue;  // an integration failure: not a candidate
      }
      if (c < best_cost) {
        best_cost = c;
        best = q->back();
      }
    }
    q->back() = best;
  }
}

Eigen::Vector2d PointAt(const TrackData& d, std::size_t i) { return {d.x[2 * i], d.x[2 * i + 1]}; }

/// What the track says before any fit: mu ~ the mean squared speed (exact for v0 = 0,
/// |x'|^2 = mu + (1 - lambda) v0^2 otherwise) over chords of 1/50 of the track, and the direction
/// of the first chord.
struct TrackGuess {
  double mu = 1.0;
  double direction = 0.0;
};
TrackGuess GuessFromTrack(const TrackData& d) {
  const std::size_t n = d.tau.size();
  const double h = d.tau.back() / 50.0;
  TrackGuess g;
  double sum = 0;
  int count = 0;
  std::size_t j = 0;
  for (std::size_t i = 0; i < n; i = std::max(j, i + 1)) {
    j = i + 1;
    while (j + 1 < n && d.tau[j] - d.tau[i] < h) ++j;
    if (j >= n) break;
    const Eigen::Vector2d chord = PointAt(d, j) - PointAt(d, i);
    if (count == 0) g.direction = std::atan2(chord.y(), chord.x());
    sum += chord.squaredNorm() / std::pow(d.tau[j] - d.tau[i], 2);
    ++count;
  }
  g.mu = std::clamp(count > 0 ? sum / count : 1.0, kMuMin, kMuMax);
  return g;
}

/// The start with the given (lambda, mu, theta, w = phi - psi), phi turned so that the contact
/// velocity x'(0) = (omega_2, -omega_1) points along `direction` (the motion is invariant under
/// turning phi and psi together about the vertical).
std::vector<double> StartPoint(
    double lambda, double mu, double theta, double w, double direction, const Eigen::Vector2d& x0) {
  const PhaseVariables p = PhaseFromTrig(TrigFromAngles(AngleState{theta, 0.0, -w}), mu, lambda);
  const double phi = WrapPi(direction - std::atan2(-p.omega.x(), p.omega.y()));
  return {lambda, mu, theta, phi, WrapPi(phi - w), x0.x(), x0.y()};
}

/// The w = phi - psi at which the contact velocity x'(0) of (theta, phi, mu, lambda) points along
/// `direction` (x' turns once round the velocity ellipse as w goes round): the best of a grid.
double PhaseAlong(double lambda, double mu, double theta, double phi, double direction) {
  constexpr int kPhaseGrid = 360;
  double best = 0.0, best_distance = kInf;
  for (int k = 0; k < kPhaseGrid; ++k) {
    const double w = kTwoPi * k / kPhaseGrid;
    const PhaseVariables p = PhaseFromTrig(TrigFromAngles(AngleState{theta, phi, phi - w}), mu, lambda);
    const double distance = CircularDistance(std::atan2(-p.omega.x(), p.omega.y()), direction);
    if (distance < best_distance) {
      best_distance = distance;
      best = w;
    }
  }
  return best;
}

/// Inserts chi (q[7]) into the start q (7 values) from the first sample's frame data: the
/// measured orientation A_0 ~ Rz(phi) Ry(theta) Rz(chi), else the measured body rate
/// b_0 = Rz(chi)^T v with v = (Rz(phi) Ry(theta))^T omega(0).
void InsertChi(const TrackData& d, std::vector<double>* q) {
  const Eigen::Matrix3d axis_frame = StartFrame((*q)[2], (*q)[3], 0.0);
  double chi = 0.0;
  if (!d.orientation.empty()) {
    const Eigen::Matrix3d b =
        axis_frame.transpose() * Eigen::Map<const Eigen::Matrix<double, 3, 3, Eigen::RowMajor>>(d.orientation.data());
    chi = std::atan2(b(1, 0), b(0, 0));
  } else {
    const double* q0 = q->data();
    const Eigen::Vector3d v =
        axis_frame.transpose() * PhaseFromTrig(TrigFromAngles(AngleState{q0[2], q0[3], q0[4]}), q0[1], q0[0]).omega;
    chi = std::atan2(v.y(), v.x()) - std::atan2(d.body_rate[1], d.body_rate[0]);
  }
  q->insert(q->begin() + kP, WrapPi(chi));
}

/// The start with the given (lambda, mu, w): with measured orientations (theta, phi) are those of
/// the first sample's axis and w the grid's offset from the phase along the first chord;
/// otherwise StartPoint at the grid's theta. With frame data, chi is inserted (InsertChi).
std::vector<double> GridStart(const TrackData& d, double lambda, const TrackGuess& g, double theta, double w) {
  std::vector<double> q;
  if (!d.orientation.empty()) {
    const Eigen::Vector3d z(d.orientation[2], d.orientation[5], d.orientation[8]);  // A_0 e3
    const double th = std::acos(std::clamp(z.z(), -1.0, 1.0)), phi = std::atan2(z.y(), z.x());
    const double phase = PhaseAlong(lambda, g.mu, th, phi, g.direction) + w;
    q = {lambda, g.mu, th, phi, WrapPi(phi - phase), d.x[0], d.x[1]};
  } else {
    q = StartPoint(lambda, g.mu, theta, w, g.direction, PointAt(d, 0));
  }
  if (d.HasFrame()) InsertChi(d, &q);
  return q;
}

/// The grid of starts on the first window, each stopped after kGridIterations: enough to fall
/// into a basin, not to converge in it (on half a period lambda is weakly determined, and the
/// minima of different lambda have nearly the same cost there). Sorted by cost.
std::vector<TrackFit> MultiStart(
    const TrackData& d, const IdentifyOptions& o, const TrackGuess& g, double window, int* starts) {
  const TrackData w = Window(d, window, kStartSamples);
  const IntegrationOptions coarse{kGridTolerance, kGridTolerance, o.integration.max_steps};
  std::vector<TrackFit> fits;
  // z -> -z gives the same contact track: theta in (0, pi/2] is enough, but not with body rates
  // (v0 changes sign); measured orientations fix the axis (one theta).
  const int theta_starts = d.orientation.empty() ? o.theta_starts : 1;
  const double theta_range = d.body_rate.empty() ? M_PI / 2.0 : M_PI;
  const int per_lambda = theta_starts * o.phase_starts;
  const int count = static_cast<int>(o.lambda_starts.size()) * per_lambda;
  // Grid point i: lambda_starts[i / per_lambda], theta a, phase b; each start is independent and
  // lands in fits[i], so the order (and the sort below) does not depend on the threads.
  fits.resize(static_cast<std::size_t>(count));
  ParallelFor(count, o.threads, [&](int i) {
    const int a = (i % per_lambda) / o.phase_starts, b = i % o.phase_starts;
    const double theta = (a + 0.5) / theta_starts * theta_range;
    // With orientations the offset from the phase along the first chord, 0 first.
    const double phase = (d.orientation.empty() ? b + 0.5 : b) / o.phase_starts * kTwoPi;
    std::vector<double> q = GridStart(d, o.lambda_starts[static_cast<std::size_t>(i / per_lambda)], g, theta, phase);
    ChooseImpulses(d, w.impulse_tau.size(), coarse, &q);
    fits[static_cast<std::size_t>(i)] = Solve(w, q, o, coarse, kGridIterations, false);
  });
  *starts += count;
  std::sort(fits.begin(), fits.end(), [](const TrackFit& a, const TrackFit& b) { return a.cost < b.cost; });
  return fits;
}

/// The candidates carried to the whole track: the best start, and up to kMaxCandidates - 1 more
/// within kStartCandidateCost x its cost whose lambda differs from every chosen one by more than
/// kDistinctLambda (relative): the window decides the phase, the whole track decides lambda.
std::vector<std::vector<double>> Candidates(const std::vector<TrackFit>& fits) {
  std::vector<std::vector<double>> chosen;
  for (const TrackFit& f : fits) {
    if (chosen.size() == kMaxCandidates || !(f.cost <= kStartCandidateCost * fits.front().cost)) break;
    const bool distinct = std::all_of(chosen.begin(), chosen.end(), [&](const std::vector<double>& c) {
      return std::abs(f.q[0] - c[0]) > kDistinctLambda * c[0];
    });
    if (distinct) chosen.push_back(f.q);
  }
  return chosen;
}

/// The next window after tau_max: twice as long, but with at most kImpulsesPerWindow more
/// impulses (it then ends at the next one's time), at most the whole track.
double NextWindow(const TrackData& d, double tau_max) {
  const double doubled = std::min(d.tau.back(), 2.0 * tau_max);
  const auto seen = static_cast<std::size_t>(std::lower_bound(d.impulse_tau.begin(), d.impulse_tau.end(), tau_max) -
                                             d.impulse_tau.begin());
  if (seen + kImpulsesPerWindow < d.impulse_tau.size() && d.impulse_tau[seen + kImpulsesPerWindow] < doubled)
    return d.impulse_tau[seen + kImpulsesPerWindow];
  return doubled;
}

/// Model and weighted Jacobian at fit.q on the whole track.
void FinishFit(const TrackData& d, const IntegrationOptions& integration, TrackFit* fit) {
  const std::size_t p = ParameterCount(d);
  std::vector<double> j, r;
  ModelValues m;
  EvaluateModel(d, fit->q.data(), integration, &m, &r, &j);
  fit->model = std::move(m.x);
  fit->spin = std::move(m.spin);
  fit->orientation = std::move(m.orientation);
  fit->body_rate = std::move(m.body_rate);
  fit->jacobian.resize(static_cast<Eigen::Index>(ResidualCount(d)), static_cast<Eigen::Index>(p));
  for (std::size_t k = 0; k < ResidualCount(d); ++k)
    for (std::size_t c = 0; c < p; ++c)
      fit->jacobian(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(c)) = Weight(d, k) * j[k * p + c];
}

}  // namespace

std::size_t ResidualCount(const TrackData& d) {
  return 2 * d.tau.size() + d.spin.size() + d.orientation.size() / 3 + d.body_rate.size();
}

TrackFit FitTrack(const TrackData& data, const IdentifyOptions& o, int* starts) {
  *starts = 0;
  std::vector<double> q;
  const double span = data.tau.back();
  const IntegrationOptions mid{kStartTolerance / 10, kStartTolerance / 10, o.integration.max_steps};
  if (o.guess) {
    const IdentifyGuess& g = *o.guess;
    q = {g.lambda, g.mu, g.angles.theta, g.angles.phi, g.angles.psi, g.x0.x() / o.radius, g.x0.y() / o.radius};
    if (data.HasFrame()) InsertChi(data, &q);
    q.insert(q.end(), g.delta_psi.begin(), g.delta_psi.end());
    ChooseImpulses(data, data.impulse_tau.size(), mid, &q);
  } else {
    const TrackGuess g = GuessFromTrack(data);
    // With impulses in the first window each start gets their delta psi from ChooseImpulses.
    const double first = std::min(span, kFirstWindowPeriods * kTwoPi / std::sqrt(g.mu));
    // Doubling the window carries the phase from one window to the next without skipping a turn;
    // each impulse that enters a window gets its delta psi from ChooseImpulses first.
    // The candidates go through the windows together; after each window those whose cost
    // exceeds kCandidateCost x the best are dropped (a wrong lambda shows as the window grows).
    std::vector<TrackFit> candidates;
    for (const std::vector<double>& c : Candidates(MultiStart(data, o, g, first, starts))) {
      candidates.emplace_back();
      candidates.back().q = c;
    }
    double window = first;
    do {
      window = NextWindow(data, window);
      const TrackData w = Window(data, window, kWindowSamples);
      for (TrackFit& c : candidates) {
        ChooseImpulses(data, w.impulse_tau.size(), mid, &c.q);
        c = Solve(w, c.q, o, mid, kStartIterations, false);
      }
      std::sort(
          candidates.begin(), candidates.end(), [](const TrackFit& a, const TrackFit& b) { return a.cost < b.cost; });
      const double keep = kCandidateCost * candidates.front().cost;
      candidates.erase(
          std::find_if(candidates.begin() + 1, candidates.end(), [&](const TrackFit& c) { return !(c.cost <= keep); }),
          candidates.end());
    } while (window < span);
    q = candidates.front().q;
  }
  ChooseImpulses(data, data.impulse_tau.size(), mid, &q);
  TrackFit fit = Solve(data, q, o, o.integration, o.max_iterations, false);
  FinishFit(data, o.integration, &fit);
  return fit;
}

namespace {

/// One side (dir = -1 or +1) of the profile interval: the secant method on the signed root
/// r(lambda) = sqrt(2 (cost(lambda) - cost_min)), nearly linear in lambda, for r = sqrt(threshold).
double ProfileSide(const TrackData& d,
                   const IdentifyOptions& o,
                   const IntegrationOptions& integration,
                   const TrackFit& fit,
                   double se,
                   double threshold,
                   double dir,
                   int* fits) {
  constexpr int kMaxSteps = 16;
  constexpr double kRootTolerance = 1e-3;  // relative on r: ~0.1% of the interval's half-width
  const double target = std::sqrt(threshold);
  const double bound = dir < 0 ? o.lambda_min : o.lambda_max;
  const double lam_hat = fit.q[0];
  double last_lam = lam_hat, last_r = 0.0;
  double lam = std::clamp(lam_hat + dir * 1.96 * se, o.lambda_min, o.lambda_max);
  std::vector<double> warm = fit.q;
  if (lam == lam_hat) return dir < 0 ? 0.0 : std::numeric_limits<double>::infinity();  // at the bound
  for (int step = 0; step < kMaxSteps && lam != lam_hat; ++step) {
    std::vector<double> q = warm;
    q[0] = lam;
    const TrackFit f = Solve(d, q, o, integration, o.max_iterations, true);
    ++*fits;
    const double r = std::sqrt(std::max(0.0, 2.0 * (f.cost - fit.cost)));
    if (std::abs(r - target) <= kRootTolerance * target) return lam;
    if (r < target && lam == bound) return dir < 0 ? 0.0 : std::numeric_limits<double>::infinity();
    const double slope = (r - last_r) / (lam - last_lam);
    double next = slope * dir > 0 ? lam + (target - r) / slope : lam + 4.0 * (lam - lam_hat);
    // Never jump more than 4x the current distance from the optimum (a flat profile).
    const double far = lam_hat + 4.0 * (lam - lam_hat);
    if (dir * (next - far) > 0) next = far;
    if (r < target) warm = f.q;
    last_lam = lam;
    last_r = r;
    lam = std::clamp(next, o.lambda_min, o.lambda_max);
  }
  return lam;
}

}  // namespace

ProfileInterval ProfileLambda(
    const TrackData& data, const IdentifyOptions& options, const TrackFit& fit, double se, double threshold) {
  // The profile's cost differences are ~threshold ~ sigma^2 per residual: an integration error
  // delta moves them by ~sum r_i delta_i, negligible when delta << sigma, so the refits use
  // kProfileNoiseFraction x the RMS residual (at most kJacobianTolerance, never tighter than
  // asked). The optimum's cost is re-evaluated with the same tolerance so that the common part
  // of the integration error cancels in the differences.
  const double rms = std::sqrt(2.0 * fit.cost / static_cast<double>(ResidualCount(data)));
  const double tol = std::min(kProfileNoiseFraction * rms, kProfileMaxTolerance);
  const IntegrationOptions integration{std::max(tol, options.integration.absolute_tolerance),
                                       std::max(tol, options.integration.relative_tolerance),
                                       options.integration.max_steps};
  TrackFit optimum = fit;
  optimum.cost = Cost(data, fit.q, integration);
  ProfileInterval p;
  // The two sides are independent refits: in parallel when there are threads.
  double side[2];
  int fits[2] = {0, 0};
  ParallelFor(2, options.threads, [&](int i) {
    side[i] = ProfileSide(data, options, integration, optimum, se, threshold, i == 0 ? -1.0 : 1.0, &fits[i]);
  });
  p.low = side[0];
  p.high = side[1];
  p.fits = fits[0] + fits[1];
  return p;
}

}  // namespace plateball::internal
