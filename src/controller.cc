#include "plateball/controller.h"

#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>
#include <exception>
#include <stdexcept>

#include "arc.h"
#include "check.h"
#include "feedback_policy.h"
#include "plateball/so3.h"

namespace plateball {

std::string ToString(ControllerStatus status) {
  switch (status) {
    case ControllerStatus::kNotRun:
      return "not_run";
    case ControllerStatus::kOk:
      return "ok";
    case ControllerStatus::kMeasurementRejected:
      return "measurement_rejected";
    case ControllerStatus::kTimeOutOfOrder:
      return "time_out_of_order";
    case ControllerStatus::kDone:
      return "done";
    case ControllerStatus::kLost:
      return "lost";
    case ControllerStatus::kIntegrationFailure:
      return "integration_failure";
  }
  return "unknown";
}

std::string ControllerOptions::Validate() const {
  using internal::InvalidValueMessage;
  if (!(tick_period >= 1e-7 && tick_period <= 1.0))
    return InvalidValueMessage("tick_period", tick_period, "must be in [1e-7, 1]");
  if (strategy == ExecutionStrategy::kOpenLoop)
    return InvalidValueMessage("strategy", "'open_loop'", "the controller feeds back (feedback, feedback_exact)");
  if (!(time_budget > 0.0 && time_budget <= 10.0))
    return InvalidValueMessage("time_budget", time_budget, "must be in (0, 10] seconds");
  if (!(jump_tolerance > 0.0 && jump_tolerance <= 1e6))
    return InvalidValueMessage("jump_tolerance", jump_tolerance, "must be in (0, 1e6]");
  if (!(orientation_jump_tolerance > 0.0 && orientation_jump_tolerance <= M_PI))
    return InvalidValueMessage("orientation_jump_tolerance", orientation_jump_tolerance, "must be in (0, pi]");
  if (!(rotation_tolerance >= 1e-14 && rotation_tolerance <= 0.1))
    return InvalidValueMessage("rotation_tolerance", rotation_tolerance, "must be in [1e-14, 0.1]");
  if (physical) {
    const std::string e = physical->Validate();
    if (!e.empty()) return "physical: " + e;
  }
  const std::string e = execution.Validate();
  return e.empty() ? "" : "execution: " + e;
}

Controller::Controller(std::shared_ptr<const NominalPlan> nominal, const ControllerOptions& options)
    : nominal_(std::move(nominal)), options_(options) {
  if (!nominal_) internal::ThrowInvalid("nominal", "null", "a nominal plan is required (MakeNominalPlan)");
  if (!nominal_->plan.IsSolutionUsable())
    internal::ThrowInvalid("nominal.plan.status",
                           "'" + ToString(nominal_->plan.status) + "'",
                           "the nominal plan must be usable: " + nominal_->plan.message);
  internal::ThrowIfInvalid(options_.Validate());
  policy_ = std::make_unique<internal::FeedbackPolicy>(*nominal_, options_.strategy, options_.execution);
  estimate_.x = nominal_->pass_points.front();
  estimate_.A = nominal_->plan.A0;
  estimate_.state = StateFromAngles(nominal_->initial, nominal_->mu, nominal_->model);
  message_.reserve(512);
  out_.now = estimate_;
  out_.at_next_impulse = estimate_;
}

Controller::~Controller() = default;

int Controller::exact_solves() const { return policy_->exact_solves(); }
int Controller::exact_failures() const { return policy_->exact_failures(); }

namespace {
// The free motion of the estimate over `duration` (nominal lambda).
ControllerEstimate Roll(const ControllerEstimate& e,
                        double duration,
                        const BallModel& model,
                        const IntegrationOptions& integration) {
  if (duration <= 0.0) return e;
  const Eigen::Vector2d k = ConservedMomentum(e.state, model);
  const internal::ArcEnd arc = internal::IntegrateArc(model.lambda(), e.state.z, k, duration, integration);
  ControllerEstimate r = e;
  r.x += arc.dx;
  r.A = arc.phi * e.A;
  r.state = {arc.z, OmegaFromMomentum(arc.z, k, model)};
  return r;
}
}  // namespace

// The estimate rolled freely from its tick to `tick`.
void Controller::Propagate(long tick) {
  const double duration = static_cast<double>(tick - estimate_.tick) * options_.tick_period;
  estimate_ = Roll(estimate_, duration, nominal_->model, nominal_->options.integration);
  estimate_.tick = tick;
}

// Takes the measurement into the estimate unless it contradicts the model (then `reason` says why).
bool Controller::Accept(const ControllerMeasurement& m) {
  const char* why = nullptr;
  const double tol = options_.rotation_tolerance;
  if (!m.x.allFinite()) {
    why = "the measured contact point is not finite";
  } else if ((m.x - estimate_.x).norm() > options_.jump_tolerance) {
    why = "the measured contact point jumped farther than jump_tolerance from the prediction";
  } else if (m.has_orientation) {
    if (!m.A.allFinite() || !m.omega.allFinite()) {
      why = "the measured orientation or angular velocity is not finite";
    } else if ((m.A.transpose() * m.A - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > tol ||
               std::abs(m.A.determinant() - 1.0) > tol) {
      why = "the measured orientation is not a rotation (rotation_tolerance)";
    } else if (std::abs(m.omega.z()) > tol * std::max(1.0, m.omega.norm())) {
      why = "the measured angular velocity has a vertical component (spin; rotation_tolerance)";
    } else if (m.omega.head<2>().norm() == 0.0) {
      why = "the measured ball is at rest: no feedback join exists";
    } else if (RotationAngle(m.A, estimate_.A) > options_.orientation_jump_tolerance) {
      why = "the measured orientation turned farther than orientation_jump_tolerance from the prediction";
    }
  }
  if (why != nullptr) {
    out_.reason = why;
    return false;
  }
  estimate_.x = m.x;
  if (m.has_orientation) {
    estimate_.A = m.A;
    estimate_.state.z = m.A.col(2).normalized();
    estimate_.state.omega = {m.omega.x(), m.omega.y(), 0.0};
  }
  return true;
}

// Decides impulse next_impulse_ from the estimate (the feedback policy), applies the commanded jump to
// the estimate and schedules the next impulse on the tick grid.
void Controller::Fire(long tick, std::chrono::steady_clock::time_point start) {
  const int k = next_impulse_;
  internal::FeedbackObservation obs;
  obs.angles = AnglesFromState(estimate_.state, nominal_->model);
  obs.mu = Energy(estimate_.state, nominal_->model);
  obs.x = estimate_.x;
  obs.A = estimate_.A;
  const std::chrono::duration<double> spent = std::chrono::steady_clock::now() - start;
  const bool exact_allowed = spent.count() < options_.time_budget;
  if (!exact_allowed && policy_->WantsExact(k)) out_.budget_exhausted = true;
  const int solves = policy_->exact_solves();
  internal::FeedbackCommand c;
  if (!policy_->Decide(k, obs, exact_allowed, &c)) {
    out_.status = policy_->status() == ExecutionStatus::kIntegrationFailure ? ControllerStatus::kIntegrationFailure
                                                                            : ControllerStatus::kLost;
    out_.reason = "the next pass point cannot be joined from the estimate (message())";
    message_ = policy_->message();
    return;
  }
  out_.impulse = true;
  out_.impulse_index = k;
  out_.late = tick > next_impulse_tick_;
  out_.delta_psi = c.delta_psi;
  out_.delta_omega = c.delta_omega;
  out_.plate_velocity_change = 2.0 * c.delta_omega.cross(Eigen::Vector3d(Eigen::Vector3d::UnitZ()));
  out_.exact_replan = policy_->exact_solves() > solves;
  if (options_.physical) {
    out_.plate_impulse = PlateImpulseFor(*options_.physical, estimate_.state.z, c.delta_omega);
    out_.has_plate_impulse = true;
  }
  estimate_.state.omega += c.delta_omega;
  next_impulse_tick_ = tick + std::max(1L, std::lround(c.duration / options_.tick_period));
  ++next_impulse_;
}

const ControllerOutput& Controller::Update(double time, const ControllerMeasurement& measurement) {
  const auto start = std::chrono::steady_clock::now();
  const ControllerEstimate last_now = out_.now, last_next = out_.at_next_impulse;
  out_ = ControllerOutput{};
  out_.now = last_now;
  out_.at_next_impulse = last_next;
  const double ticks = time / options_.tick_period;
  if (!std::isfinite(ticks) || std::abs(ticks) > 1e15 || (started_ && std::lround(ticks) < estimate_.tick)) {
    out_.status = ControllerStatus::kTimeOutOfOrder;
    out_.reason = "the time is not finite or precedes the last tick";
    out_.tick = estimate_.tick;
    return out_;
  }
  const long tick = std::lround(ticks);
  out_.tick = tick;
  const int n = policy_->impulses();
  try {
    if (started_) Propagate(tick);
    estimate_.tick = tick;
    started_ = true;
    out_.measurement_used = Accept(measurement);
    out_.status = out_.measurement_used ? ControllerStatus::kOk : ControllerStatus::kMeasurementRejected;
    if (next_impulse_ < n && tick >= next_impulse_tick_) Fire(tick, start);
    if (out_.status == ControllerStatus::kLost || out_.status == ControllerStatus::kIntegrationFailure) return out_;
    if (next_impulse_ >= n && tick >= next_impulse_tick_ && out_.status == ControllerStatus::kOk)
      out_.status = ControllerStatus::kDone;
    out_.now = estimate_;
    out_.next_impulse_tick = next_impulse_ < n ? next_impulse_tick_ : -1;
    const long ahead = std::max(0L, next_impulse_tick_ - tick);
    out_.at_next_impulse = Roll(
        estimate_, static_cast<double>(ahead) * options_.tick_period, nominal_->model, nominal_->options.integration);
    out_.at_next_impulse.tick = tick + ahead;
  } catch (const std::exception& e) {
    // An integration that failed (runtime_error) or an estimate the model rejects (invalid_argument,
    // e.g. an energy below the join's range after lossy impulses).
    out_.status = dynamic_cast<const std::runtime_error*>(&e) != nullptr ? ControllerStatus::kIntegrationFailure
                                                                         : ControllerStatus::kLost;
    out_.reason = "the estimate left what the model can integrate or join (message())";
    message_ = e.what();
    return out_;
  }
  const std::chrono::duration<double> spent = std::chrono::steady_clock::now() - start;
  if (spent.count() > options_.time_budget) out_.budget_exhausted = true;
  return out_;
}

}  // namespace plateball
