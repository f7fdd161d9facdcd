#include "plateball/free_motion.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "check.h"
#include "dynamics.h"
#include "plateball/so3.h"

namespace plateball {
namespace {

using internal::FullState;

void ValidateStart(const FreeMotionStart& s, const IntegrationOptions& options) {
  internal::ThrowIfInvalid(options.Validate());
  ValidateState(s.state, "start.state");
  internal::RequireCoordinates("start.x0", s.x0);
  if (!IsRotation(s.A0, 1e-9))
    internal::ThrowInvalid("start.A0", "(matrix)", "not a rotation matrix (R^T R = I, det R = 1 to 1e-9)");
  if (std::abs(s.A0.col(2).dot(s.state.z) - 1.0) > 1e-9)
    internal::ThrowInvalid("start.A0 (|A0 e3 - z|)",
                           (s.A0.col(2) - s.state.z).norm(),
                           "A0 e3 must equal start.state.z (the symmetry axis)");
}

MotionSample MakeSample(double t,
                        const double* y,
                        const Eigen::Vector2d& x,
                        const Eigen::Matrix3d& A,
                        const Eigen::Vector2d& k,
                        const BallModel& model) {
  MotionSample s;
  s.t = t;
  s.state.z = Eigen::Vector3d(y[0], y[1], y[2]).normalized();
  s.state.omega = OmegaFromMomentum(s.state.z, k, model);
  s.x = x;
  s.A = A;
  s.energy = Energy(s.state, model);
  s.angles = AnglesFromState(s.state, model);
  return s;
}

}  // namespace

FreeMotion::FreeMotion(const BallModel& model, const FreeMotionStart& start, const IntegrationOptions& options)
    : model_(model), start_(start), options_(options) {
  ValidateStart(start, options);
  mu_ = Energy(start.state, model);
  if (!(mu_ > 1e-300))
    internal::ThrowInvalid("mu (energy of start.state)", mu_, "must be > 0: a ball at rest has no period");
  period_ = 2.0 * M_PI / std::sqrt(mu_);
  k_ = ConservedMomentum(start.state, model);
  internal::FullRhs rhs{model.lambda(), {k_.x(), k_.y()}};
  FullState y = internal::InitialFullState(start.state.z);
  checkpoint_t_.push_back(0.0);
  checkpoint_y_.push_back(y);
  internal::IntegrateAdaptive(rhs, y, 0.0, period_, period_ / 64.0, options_, [&](double t, const FullState& s) {
    checkpoint_t_.push_back(t);
    checkpoint_y_.push_back(s);
  });
  checkpoint_t_.back() = period_;
  drift_ = Eigen::Vector2d(y[3], y[4]);
  monodromy_ = ProjectToSO3(internal::MatrixFromRowMajor(y.data() + 5));
  monodromy_log_ = LogSO3(monodromy_);
}

FreeMotion FreeMotion::FromAngles(const BallModel& model,
                                  const AngleState& angles,
                                  double mu,
                                  const Eigen::Vector2d& x0,
                                  const Eigen::Matrix3d& A0,
                                  const IntegrationOptions& options) {
  FreeMotionStart s;
  s.state = StateFromAngles(angles, mu, model);
  s.x0 = x0;
  // If A0 does not carry z on its third column, rotate it minimally so that A0 e3 = z.
  s.A0 = internal::RotateAxisOnto(A0, s.state.z);
  return FreeMotion(model, s, options);
}

void FreeMotion::LocalState(double tau, double* out) const {
  auto it = std::upper_bound(checkpoint_t_.begin(), checkpoint_t_.end(), tau);
  std::size_t i = it == checkpoint_t_.begin() ? 0 : static_cast<std::size_t>(it - checkpoint_t_.begin()) - 1;
  if (i + 1 >= checkpoint_t_.size()) i = checkpoint_t_.size() - 2;
  // Integrate from the nearer end of the stored step: full tolerance, no interpolation error.
  const double t0 = checkpoint_t_[i], t1 = checkpoint_t_[i + 1];
  const bool from_left = (tau - t0) <= (t1 - tau);
  FullState y = from_left ? checkpoint_y_[i] : checkpoint_y_[i + 1];
  const double ts = from_left ? t0 : t1;
  internal::FullRhs rhs{model_.lambda(), {k_.x(), k_.y()}};
  if (tau != ts) internal::IntegrateAdaptive(rhs, y, ts, tau, std::abs(tau - ts), options_);
  std::copy(y.begin(), y.end(), out);
}

namespace {
// Beyond this many periods the periodic evaluation would lose all significant digits of the
// position (k * drift) and of the phase; such times are rejected instead of answered with noise.
constexpr double kMaxPeriods = 1e12;

void RequireEvaluableTime(double t, double period) {
  internal::RequireFinite("t", t);
  if (std::abs(t) > kMaxPeriods * period)
    internal::ThrowInvalid("t", t, "beyond 1e12 periods the periodic evaluation has no significant digits left");
}
}  // namespace

MotionSample FreeMotion::At(double t) const {
  RequireEvaluableTime(t, period_);
  const double kf = std::floor(t / period_);
  double tau = t - kf * period_;
  tau = std::clamp(tau, 0.0, period_);
  double y[14];
  LocalState(tau, y);
  const Eigen::Vector2d x = start_.x0 + kf * drift_ + Eigen::Vector2d(y[3], y[4]);
  // Phi(T)^k: rotation about the monodromy axis by k times its angle, reduced mod 2 pi.
  const double angle = monodromy_log_.norm();
  const Eigen::Matrix3d phi_k =
      angle > 0 ? ExpSO3(std::fmod(kf * angle, 2.0 * M_PI) / angle * monodromy_log_) : Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d A = ProjectToSO3(internal::MatrixFromRowMajor(y + 5) * phi_k * start_.A0);
  return MakeSample(t, y, x, A, k_, model_);
}

Eigen::Vector2d FreeMotion::PositionAt(double t) const {
  RequireEvaluableTime(t, period_);
  const double kf = std::floor(t / period_);
  const double tau = std::clamp(t - kf * period_, 0.0, period_);
  double y[14];
  LocalState(tau, y);
  return start_.x0 + kf * drift_ + Eigen::Vector2d(y[3], y[4]);
}

std::vector<MotionSample> FreeMotion::Sample(double t0, double t1, int n) const {
  internal::RequireFinite("t0", t0);
  internal::RequireFinite("t1", t1);
  if (n < 2 || n > internal::kMaxSamples)
    internal::ThrowInvalid("samples", n, "must be in [2, " + std::to_string(internal::kMaxSamples) + "]");
  if (!(t1 >= t0)) internal::ThrowInvalid("t1", t1, "must be >= t0");
  std::vector<MotionSample> out;
  out.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) out.push_back(At(t0 + (t1 - t0) * i / (n - 1)));
  return out;
}

std::vector<MotionSample> IntegrateFreeMotion(const BallModel& model,
                                              const FreeMotionStart& start,
                                              const std::vector<double>& times,
                                              const IntegrationOptions& options) {
  ValidateStart(start, options);
  for (std::size_t i = 0; i < times.size(); ++i) {
    internal::RequireFinite("times[" + std::to_string(i) + "]", times[i]);
    if (i > 0 && times[i] < times[i - 1])
      internal::ThrowInvalid("times[" + std::to_string(i) + "]", times[i], "times must be non-decreasing");
  }
  const Eigen::Vector2d k = ConservedMomentum(start.state, model);
  internal::FullRhs rhs{model.lambda(), {k.x(), k.y()}};
  FullState y = internal::InitialFullState(start.state.z);
  std::vector<MotionSample> out;
  double t = 0.0;
  double dt = 0.01;
  for (double target : times) {
    if (target != t) {
      double last_dt = dt;
      double prev = t;
      internal::IntegrateAdaptive(rhs, y, t, target, dt, options, [&](double tt, const FullState&) {
        last_dt = std::abs(tt - prev);
        prev = tt;
      });
      dt = std::max(last_dt, 1e-6);
      t = target;
    }
    const Eigen::Matrix3d A = ProjectToSO3(internal::MatrixFromRowMajor(y.data() + 5) * start.A0);
    out.push_back(MakeSample(t, y.data(), start.x0 + Eigen::Vector2d(y[3], y[4]), A, k, model));
  }
  return out;
}

}  // namespace plateball
