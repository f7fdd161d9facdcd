// The independent checks of an exact arrival (exact_arrival.h, CheckRigLimits) and of a
// path-following plan (plan_rig_check.h, CheckPlanRigLimits) against the rig's limits: replays with
// FreeMotion, not with the solvers' chains.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "check.h"
#include "plateball/exact_arrival.h"
#include "plateball/free_motion.h"
#include "plateball/impulse.h"
#include "plateball/plan_rig_check.h"
#include "plateball/plate_impulse.h"
#include "rig_geometry.h"

namespace plateball {

namespace {

// Records the smallest margin per limit and, for each limit exceeded beyond its tolerance, where
// it was exceeded most: Finish() writes one line per such limit (its worst excess) and `passed`.
class Recorder {
 public:
  explicit Recorder(RigCheck* out) : out_(out) {}
  // margin = bound - value (>= 0 when met); `tolerance` in the same unit.
  void Margin(const std::string& limit, double margin, double tolerance, const std::string& where) {
    auto it = out_->margins.find(limit);
    if (it != out_->margins.end() && !(margin < it->second)) return;
    out_->margins[limit] = margin;
    if (!(margin >= -tolerance)) worst_[limit] = where;
  }
  void Finish() {
    for (const auto& [limit, where] : worst_)
      out_->violations.push_back(limit + " exceeded by " + internal::FormatNumber(-out_->margins.at(limit)) + " at " +
                                 where);
    out_->passed = out_->violations.empty();
  }

 private:
  RigCheck* out_;
  std::map<std::string, std::string> worst_;  // limit -> where its margin is smallest
};

void CheckPoint(const RigLimits& l,
                const Eigen::Vector2d& x0,
                const Eigen::Vector2d& x,
                double tol,
                const std::string& where,
                Recorder* rec) {
  internal::VisitGeometricMargins(
      l, x0, x, [&](const std::string& name, double margin) { rec->Margin(name, margin, tol, where); });
}

void CheckImpulse(const RigLimits& l,
                  const std::optional<PhysicalParameters>& physical,
                  const Eigen::Vector3d& z,
                  const Eigen::Vector3d& delta_omega,
                  const RigCheckTolerances& tol,
                  const std::string& where,
                  Recorder* rec) {
  const double dv = 2.0 * delta_omega.cross(Eigen::Vector3d::UnitZ()).norm();
  if (!std::isinf(l.max_plate_velocity_change))
    rec->Margin("max_plate_velocity_change",
                l.max_plate_velocity_change - dv,
                tol.impulse * l.max_plate_velocity_change,
                where);
  if (!std::isinf(l.ImpulseBound()) && physical) {
    const double j = PlateImpulseFor(*physical, z, delta_omega).plate.norm();
    rec->Margin("max_plate_impulse", l.ImpulseBound() - j, tol.impulse * l.ImpulseBound(), where);
  }
}

// An impulse at t_impulse, `tick` its index on the grid (-1: none claimed), followed by a flight of
// `duration` that ends at another impulse when `ends_at_impulse`.
void CheckTiming(const RigLimits& l,
                 double t_impulse,
                 long long tick,
                 double duration,
                 bool ends_at_impulse,
                 const RigCheckTolerances& tol,
                 const std::string& where,
                 Recorder* rec) {
  if (l.min_interval > 0 && ends_at_impulse)
    rec->Margin("min_interval", duration - l.min_interval, tol.time * l.min_interval, where);
  if (l.tick > 0) {  // exactly on the grid: tolerance zero
    const bool on_grid = tick >= 0 && t_impulse == static_cast<double>(tick) * l.tick;
    rec->Margin("tick", on_grid ? 0.0 : -std::abs(t_impulse - static_cast<double>(tick) * l.tick), 0.0, where);
  }
}

}  // namespace

RigCheck CheckRigLimits(const ExactArrivalProblem& p,
                        const ExactArrivalSummary& summary,
                        const RigCheckTolerances& tolerances,
                        int samples_per_arc) {
  if (samples_per_arc < 1) internal::ThrowInvalid("samples_per_arc", samples_per_arc, "must be >= 1");
  RigCheck out;
  Recorder rec(&out);
  BallState state = StateFromAngles(p.initial, p.mu, p.model);
  Eigen::Vector2d x = p.x0;
  Eigen::Matrix3d A = AlignOrientationToAxis(p.A0, state.z);
  CheckPoint(p.limits, p.x0, x, tolerances.position, "the start", &rec);
  const std::size_t n = summary.impulses.size();
  for (std::size_t k = 0; k < n; ++k) {
    const ExactImpulse& e = summary.impulses[k];
    const std::string where = "impulse " + std::to_string(k);
    const Impulse imp = EnergyPreservingImpulse(AnglesFromState(state, p.model), p.mu, e.delta_psi, p.model);
    const Eigen::Vector3d dw = e.kind == ExactImpulseKind::kStart
                                   ? imp.state_after.omega
                                   : Eigen::Vector3d(imp.state_after.omega - state.omega);
    CheckImpulse(p.limits, p.physical, state.z, dw, tolerances, where, &rec);
    CheckTiming(
        p.limits, e.t_impulse, e.tick, e.duration, k + 1 < n || summary.stop.has_value(), tolerances, where, &rec);
    const FreeMotion motion(p.model, FreeMotionStart{imp.state_after, x, A});
    for (int j = 1; j <= samples_per_arc; ++j) {
      const MotionSample sample = motion.At(e.duration * j / samples_per_arc);
      CheckPoint(p.limits, p.x0, sample.x, tolerances.position, "flight " + std::to_string(k), &rec);
      ++out.samples;
      if (j == samples_per_arc) state = sample.state, x = sample.x, A = sample.A;
    }
  }
  if (summary.stop) {
    CheckImpulse(p.limits, p.physical, state.z, -state.omega, tolerances, "the stop", &rec);
    CheckTiming(p.limits,
                summary.stop->t_impulse,
                summary.stop->tick,
                summary.stop->duration,
                false,
                tolerances,
                "the stop",
                &rec);
  }
  rec.Finish();
  return out;
}

RigCheck CheckPlanRigLimits(const PlanProblem& problem,
                            const PlanSummary& plan,
                            const RigLimits& limits,
                            const std::optional<PhysicalParameters>& physical,
                            const RigCheckTolerances& tolerances,
                            int samples_per_arc) {
  if (samples_per_arc < 1) internal::ThrowInvalid("samples_per_arc", samples_per_arc, "must be >= 1");
  RigCheck out;
  Recorder rec(&out);
  const Eigen::Vector2d x0 = problem.path.StartPoint();
  Eigen::Vector2d x = x0;
  Eigen::Matrix3d A = plan.A0;
  CheckPoint(limits, x0, x, tolerances.position, "the start", &rec);
  const std::size_t n = plan.steps.size();
  for (std::size_t k = 0; k < n; ++k) {
    const PlanStep& s = plan.steps[k];
    const std::string where = "impulse " + std::to_string(k);
    // One actuation: the energy changes and the energy-preserving impulse at p(tau_k) together.
    const Eigen::Vector3d dw = s.impulse.state_after.omega - s.state_before.omega;
    CheckImpulse(limits, physical, s.state_before.z, dw, tolerances, where, &rec);
    const long long tick = limits.tick > 0 ? std::llround(s.t_impulse / limits.tick) : -1;
    CheckTiming(limits, s.t_impulse, tick, s.duration, k + 1 < n, tolerances, where, &rec);
    const FreeMotion motion(problem.model, FreeMotionStart{s.impulse.state_after, x, A});
    for (int j = 1; j <= samples_per_arc; ++j) {
      const MotionSample sample = motion.At(s.duration * j / samples_per_arc);
      CheckPoint(limits, x0, sample.x, tolerances.position, "flight " + std::to_string(k), &rec);
      ++out.samples;
      if (j == samples_per_arc) x = sample.x, A = sample.A;
    }
  }
  rec.Finish();
  return out;
}

}  // namespace plateball
