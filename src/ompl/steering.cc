#include "plateball/ompl/steering.h"

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/base/spaces/SO3StateSpace.h>
#include <ompl/control/SteeredControlSampler.h>
#include <ompl/control/spaces/RealVectorControlSpace.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "check.h"
#include "plateball/impulse.h"
#include "plateball/isoparallel_plan.h"
#include "plateball/path.h"
#include "plateball/so3.h"

namespace plateball::ompl_steering {
namespace {

namespace ob = ompl::base;
namespace oc = ompl::control;
using internal::InvalidValueMessage;

constexpr int kTargetDimension = 6;  // (x1, y1, qw, qx, qy, qz)

const ob::RealVectorStateSpace::StateType* PointPart(const ob::State* s) {
  return s->as<ob::CompoundState>()->as<ob::RealVectorStateSpace::StateType>(0);
}
const ob::SO3StateSpace::StateType* RotationPart(const ob::State* s) {
  return s->as<ob::CompoundState>()->as<ob::SO3StateSpace::StateType>(1);
}

// Rotation of a quaternion (w, x, y, z), NaN when it is zero or not finite.
Eigen::Matrix3d RotationOfQuaternion(double w, double x, double y, double z) {
  const Eigen::Quaterniond q(w, x, y, z);
  const double norm = q.norm();
  if (!(std::isfinite(norm) && norm > 0)) return Eigen::Matrix3d::Constant(std::numeric_limits<double>::quiet_NaN());
  return q.normalized().toRotationMatrix();
}

bool IsFiniteConfiguration(const Eigen::Vector2d& x, const Eigen::Matrix3d& A) {
  return x.allFinite() && A.allFinite();
}

// Upper bound of the contact-point speed |x'| = |omega_h| over all angles: omega_h lies on the
// velocity ellipse with semi-axes a = sqrt(mu / (lambda sin^2 theta + cos^2 theta)) and b = sqrt(mu)
// (ball_state.h, SemiAxisA), so |x'| <= sqrt(mu / min(1, lambda)).
double MaxContactSpeed(const SteeringOptions& o) { return std::sqrt(o.mu / std::min(1.0, o.model.lambda())); }

// The motion of a solved connection, sampled: each arc from its impulse (EnergyPreservingImpulse,
// FreeMotion) with time steps such that consecutive contact points are at most `spacing` apart.
void SampleMotion(const SteeringOptions& o, Connection& c) {
  const ExactArrivalProblem& p = c.problem;
  BallState state = StateFromAngles(p.initial, p.mu, p.model);
  Eigen::Vector2d x = p.x0;
  Eigen::Matrix3d A = AlignOrientationToAxis(p.A0, state.z);
  const double dt_max = o.sample_spacing / MaxContactSpeed(o);
  c.samples.clear();
  for (const ExactImpulse& e : c.summary.impulses) {
    const Impulse imp = EnergyPreservingImpulse(AnglesFromState(state, p.model), p.mu, e.delta_psi, p.model);
    const FreeMotion motion(p.model, FreeMotionStart{imp.state_after, x, A}, o.exact.integration);
    const int n = std::max(2, static_cast<int>(std::ceil(e.duration / dt_max)) + 1);
    std::vector<MotionSample> arc = motion.Sample(0.0, e.duration, n);
    const MotionSample end = arc.back();
    c.samples.insert(c.samples.end(), arc.begin(), arc.end());
    state = end.state;
    x = end.x;
    A = end.A;
  }
  c.end_state = state;
}

// The start state's and the control's values: the key of the propagator's one-entry cache.
std::vector<double> CacheKey(const ob::State* state, const oc::Control* control) {
  const double* x = PointPart(state)->values;
  const auto* q = RotationPart(state);
  const double* u = control->as<oc::RealVectorControlSpace::ControlType>()->values;
  return {x[0], x[1], q->w, q->x, q->y, q->z, u[0], u[1], u[2], u[3], u[4], u[5]};
}

Connection Failed(Connection c, ConnectionStatus status, std::string message) {
  c.status = status;
  c.message = std::move(message);
  return c;
}

}  // namespace

std::string SteeringOptions::Validate() const {
  if (!(std::isfinite(mu) && mu > 0)) return InvalidValueMessage("mu", mu, "must be finite and > 0");
  if (impulses < 3 || impulses > kMaxExactImpulses)
    return InvalidValueMessage("impulses", impulses, "must be in [3, " + std::to_string(kMaxExactImpulses) + "]");
  if (!(std::isfinite(min_distance) && min_distance > 0))
    return InvalidValueMessage("min_distance", min_distance, "must be finite and > 0");
  if (!(std::isfinite(sample_spacing) && sample_spacing > 0))
    return InvalidValueMessage("sample_spacing", sample_spacing, "must be finite and > 0");
  if (!(model.lambda() > 0)) return InvalidValueMessage("model.lambda", model.lambda(), "must be > 0");
  return exact.Validate();
}

ob::StateSpacePtr MakeBallStateSpace(const Eigen::Vector2d& low, const Eigen::Vector2d& high) {
  for (int i = 0; i < 2; ++i) {
    internal::RequireFinite("low", low[i]);
    internal::RequireFinite("high", high[i]);
    if (!(low[i] < high[i]))
      internal::ThrowInvalid("high", high[i], "must exceed low (" + internal::FormatNumber(low[i]) + ")");
  }
  auto point = std::make_shared<ob::RealVectorStateSpace>(2);
  ob::RealVectorBounds bounds(2);
  for (unsigned i = 0; i < 2; ++i) {
    bounds.setLow(i, low[static_cast<int>(i)]);
    bounds.setHigh(i, high[static_cast<int>(i)]);
  }
  point->setBounds(bounds);
  auto space = std::make_shared<ob::CompoundStateSpace>();
  space->addSubspace(point, 1.0);
  space->addSubspace(std::make_shared<ob::SO3StateSpace>(), 1.0);
  space->lock();
  return space;
}

oc::ControlSpacePtr MakeTargetControlSpace(const ob::StateSpacePtr& space) {
  const auto* compound = space->as<ob::CompoundStateSpace>();
  const ob::RealVectorBounds& point = compound->getSubspace(0)->as<ob::RealVectorStateSpace>()->getBounds();
  auto controls = std::make_shared<oc::RealVectorControlSpace>(space, kTargetDimension);
  ob::RealVectorBounds bounds(kTargetDimension);
  bounds.setLow(-1.0);
  bounds.setHigh(1.0);
  for (unsigned i = 0; i < 2; ++i) {
    bounds.setLow(i, point.low[i]);
    bounds.setHigh(i, point.high[i]);
  }
  controls->setBounds(bounds);
  return controls;
}

Eigen::Vector2d ContactPoint(const ob::State* state) {
  const double* v = PointPart(state)->values;
  return {v[0], v[1]};
}

Eigen::Matrix3d Orientation(const ob::State* state) {
  const auto* q = RotationPart(state);
  return RotationOfQuaternion(q->w, q->x, q->y, q->z);
}

void SetConfiguration(ob::State* state, const Eigen::Vector2d& x, const Eigen::Matrix3d& A) {
  if (!IsRotation(A, 1e-9)) internal::ThrowInvalid("A", "(matrix)", "not a rotation matrix (to 1e-9)");
  double* v = state->as<ob::CompoundState>()->as<ob::RealVectorStateSpace::StateType>(0)->values;
  v[0] = x.x();
  v[1] = x.y();
  const Eigen::Quaterniond q(A);
  auto* r = state->as<ob::CompoundState>()->as<ob::SO3StateSpace::StateType>(1);
  r->w = q.w();
  r->x = q.x();
  r->y = q.y();
  r->z = q.z();
}

void SetTarget(oc::Control* control, const Eigen::Vector2d& x1, const Eigen::Matrix3d& A1) {
  if (!IsRotation(A1, 1e-9)) internal::ThrowInvalid("A1", "(matrix)", "not a rotation matrix (to 1e-9)");
  const Eigen::Quaterniond q(A1);
  double* v = control->as<oc::RealVectorControlSpace::ControlType>()->values;
  const double values[kTargetDimension] = {x1.x(), x1.y(), q.w(), q.x(), q.y(), q.z()};
  std::copy(values, values + kTargetDimension, v);
}

Eigen::Vector2d TargetPoint(const oc::Control* control) {
  const double* v = control->as<oc::RealVectorControlSpace::ControlType>()->values;
  return {v[0], v[1]};
}

Eigen::Matrix3d TargetOrientation(const oc::Control* control) {
  const double* v = control->as<oc::RealVectorControlSpace::ControlType>()->values;
  return RotationOfQuaternion(v[2], v[3], v[4], v[5]);
}

std::string ToString(ConnectionStatus status) {
  switch (status) {
    case ConnectionStatus::kNotRun:
      return "not_run";
    case ConnectionStatus::kConnected:
      return "connected";
    case ConnectionStatus::kInvalidState:
      return "invalid_state";
    case ConnectionStatus::kTooClose:
      return "too_close";
    case ConnectionStatus::kNotReached:
      return "not_reached";
    case ConnectionStatus::kInvalidMotion:
      return "invalid_motion";
  }
  return "unknown";
}

std::string Connection::BriefReport() const {
  std::ostringstream s;
  s << ToString(status) << ": " << message;
  if (summary.status != ExactArrivalStatus::kNotRun)
    s << " (" << summary.impulses.size() << " impulses, position error " << summary.position_error
      << ", orientation error " << summary.orientation_error << ")";
  return s.str();
}

std::vector<ExactImpulse> ChainImpulses(const std::vector<Connection>& connections) {
  std::vector<ExactImpulse> out;
  double t0 = 0.0;
  for (std::size_t i = 0; i < connections.size(); ++i) {
    const Connection& c = connections[i];
    if (!c.IsSolutionUsable())
      internal::ThrowInvalid("connections[" + std::to_string(i) + "]", ToString(c.status), "not a usable connection");
    for (std::size_t k = 0; k < c.summary.impulses.size(); ++k) {
      ExactImpulse e = c.summary.impulses[k];
      if (k == 0 && i > 0) {
        // The ball arrives with the psi of the previous connection's end state; this connection
        // planned its first impulse from psi = problem.initial.psi (same theta, phi: z = A e3).
        const double psi_actual = AnglesFromState(connections[i - 1].end_state, connections[i - 1].problem.model).psi;
        // psi is an angle: the re-based value is reduced to [-pi, pi].
        e.delta_psi = std::remainder(e.delta_psi + c.problem.initial.psi - psi_actual, 2 * M_PI);
      }
      e.t_impulse += t0;
      out.push_back(e);
    }
    t0 += c.summary.total_time;
  }
  return out;
}

ExactSteeringPropagator::ExactSteeringPropagator(const oc::SpaceInformationPtr& si, SteeringOptions options)
    : oc::StatePropagator(si), si_c_(si.get()), options_(std::move(options)) {
  const std::string error = options_.Validate();
  if (!error.empty()) throw std::invalid_argument(error);
}

Connection ExactSteeringPropagator::Connect(const ob::State* from, const ob::State* to) const {
  Connection c;
  if (!si_c_->satisfiesBounds(to) || !si_c_->isValid(to))
    return Failed(c, ConnectionStatus::kInvalidState, "the target is out of bounds or not valid");
  return ConnectTo(from, ContactPoint(to), Orientation(to));
}

Connection ExactSteeringPropagator::ConnectTo(const ob::State* from,
                                              const Eigen::Vector2d& x1,
                                              const Eigen::Matrix3d& A1) const {
  Connection c;
  const Eigen::Vector2d x0 = ContactPoint(from);
  const Eigen::Matrix3d A0 = Orientation(from);
  if (!IsFiniteConfiguration(x0, A0)) return Failed(c, ConnectionStatus::kInvalidState, "the start is not finite");
  if (!IsFiniteConfiguration(x1, A1)) return Failed(c, ConnectionStatus::kInvalidState, "the target is not finite");
  const double distance = (x1 - x0).norm();
  if (distance < options_.min_distance)
    return Failed(c,
                  ConnectionStatus::kTooClose,
                  InvalidValueMessage("distance",
                                      distance,
                                      "below min_distance " + internal::FormatNumber(options_.min_distance) +
                                          ": no straight reference"));
  ExactArrivalProblem& p = c.problem;
  p.model = options_.model;
  p.mu = options_.mu;
  p.A0 = A0;
  p.initial = InitialAnglesFromOrientation(A0, 0.0);
  p.x0 = x0;
  p.reference = Path({SmoothCurve::Line(x0, x1)});
  p.impulses = options_.impulses;
  p.x1 = x1;
  p.A1 = A1;
  try {
    c.summary = SolveExactArrival(p, options_.exact);
  } catch (const std::exception& e) {
    return Failed(c, ConnectionStatus::kInvalidState, e.what());
  }
  if (!c.summary.IsSolutionUsable())
    return Failed(c, ConnectionStatus::kNotReached, "exact arrival: " + c.summary.BriefReport());
  SampleMotion(options_, c);
  ob::State* probe = si_c_->allocState();
  for (const MotionSample& s : c.samples) {
    SetConfiguration(probe, s.x, ProjectToSO3(s.A));
    if (!si_c_->satisfiesBounds(probe) || !si_c_->isValid(probe)) {
      si_c_->freeState(probe);
      return Failed(c,
                    ConnectionStatus::kInvalidMotion,
                    "the motion passes through an invalid configuration at contact point (" +
                        internal::FormatNumber(s.x.x()) + ", " + internal::FormatNumber(s.x.y()) + ")");
    }
  }
  si_c_->freeState(probe);
  c.status = ConnectionStatus::kConnected;
  c.message = "exact arrival with a valid motion";
  return c;
}

void ExactSteeringPropagator::propagate(const ob::State* state,
                                        const oc::Control* control,
                                        double /*duration*/,
                                        ob::State* result) const {
  const std::vector<double> key = CacheKey(state, control);
  {
    const std::lock_guard<std::mutex> lock(cache_mutex_);
    if (key == cache_key_) {
      SetConfiguration(result, cache_x_, cache_A_);
      return;
    }
  }
  const Connection c = ConnectTo(state, TargetPoint(control), TargetOrientation(control));
  if (!c.IsSolutionUsable()) {
    if (result != state) si_c_->copyState(result, state);  // no move
    return;
  }
  const Eigen::Matrix3d A = ProjectToSO3(c.summary.A_final);
  SetConfiguration(result, c.summary.x_final, A);
  const std::lock_guard<std::mutex> lock(cache_mutex_);
  cache_key_ = key;
  cache_x_ = c.summary.x_final;
  cache_A_ = A;
}

bool ExactSteeringPropagator::steer(const ob::State* from,
                                    const ob::State* to,
                                    oc::Control* result,
                                    double& duration) const {
  const Connection c = Connect(from, to);
  if (!c.IsSolutionUsable()) return false;
  double* u = result->as<oc::RealVectorControlSpace::ControlType>()->values;
  const Eigen::Vector2d x1 = ContactPoint(to);
  const auto* q = RotationPart(to);
  u[0] = x1.x();
  u[1] = x1.y();
  u[2] = q->w;
  u[3] = q->x;
  u[4] = q->y;
  u[5] = q->z;  // the state's own quaternion: the target is `to` exactly
  duration = 1.0;
  const std::lock_guard<std::mutex> lock(cache_mutex_);
  cache_key_ = CacheKey(from, result);
  cache_x_ = c.summary.x_final;
  cache_A_ = ProjectToSO3(c.summary.A_final);
  return true;
}

std::shared_ptr<ExactSteeringPropagator> UseExactSteering(const oc::SpaceInformationPtr& si,
                                                          const SteeringOptions& options) {
  auto propagator = std::make_shared<ExactSteeringPropagator>(si, options);
  si->setStatePropagator(propagator);
  si->setPropagationStepSize(1.0);
  si->setMinMaxControlDuration(1, 1);
  si->setDirectedControlSamplerAllocator(
      [](const oc::SpaceInformation* s) { return std::make_shared<oc::SteeredControlSampler>(s); });
  return propagator;
}

}  // namespace plateball::ompl_steering
