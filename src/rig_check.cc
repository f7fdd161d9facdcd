// The independent check of an exact arrival against the rig's limits (exact_arrival.h,
// CheckRigLimits): a replay with FreeMotion, not with the solver's chain.
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <set>

#include "check.h"
#include "rig_geometry.h"
#include "plateball/exact_arrival.h"
#include "plateball/free_motion.h"
#include "plateball/impulse.h"
#include "plateball/plate_impulse.h"

namespace plateball {

namespace {

// Records the smallest margin per limit and a line per limit exceeded beyond its tolerance.
class Recorder {
 public:
  explicit Recorder(RigCheck* out) : out_(out) {}
  // margin = bound - value (>= 0 when met); `tolerance` in the same unit.
  void Margin(const std::string& limit, double margin, double tolerance, const std::string& where) {
    auto it = out_->margins.find(limit);
    if (it == out_->margins.end() || margin < it->second) out_->margins[limit] = margin;
    if (!(margin >= -tolerance) && reported_.insert(limit).second)
      out_->violations.push_back(limit + " exceeded by " + internal::FormatNumber(-margin) + " at " + where);
  }

 private:
  RigCheck* out_;
  std::set<std::string> reported_;
};

void CheckPoint(const RigLimits& l, const Eigen::Vector2d& x0, const Eigen::Vector2d& x, double tol,
                const std::string& where, Recorder* rec) {
  internal::VisitGeometricMargins(l, x0, x, [&](const std::string& name, double margin) {
    rec->Margin(name, margin, tol, where);
  });
}

void CheckImpulse(const ExactArrivalProblem& p, const Eigen::Vector3d& z, const Eigen::Vector3d& delta_omega,
                  const RigCheckTolerances& tol, const std::string& where, Recorder* rec) {
  const RigLimits& l = p.limits;
  const double dv = 2.0 * delta_omega.cross(Eigen::Vector3d::UnitZ()).norm();
  if (!std::isinf(l.max_plate_velocity_change))
    rec->Margin("max_plate_velocity_change", l.max_plate_velocity_change - dv,
                tol.impulse * l.max_plate_velocity_change, where);
  if (!std::isinf(l.ImpulseBound()) && p.physical) {
    const double j = PlateImpulseFor(*p.physical, z, delta_omega).plate.norm();
    rec->Margin("max_plate_impulse", l.ImpulseBound() - j, tol.impulse * l.ImpulseBound(), where);
  }
}

void CheckTiming(const ExactArrivalProblem& p, const ExactImpulse& e, bool ends_at_impulse,
                 const RigCheckTolerances& tol, const std::string& where, Recorder* rec) {
  const RigLimits& l = p.limits;
  if (l.min_interval > 0 && ends_at_impulse)
    rec->Margin("min_interval", e.duration - l.min_interval, tol.time * l.min_interval, where);
  if (l.tick > 0) {  // exactly on the grid: tolerance zero
    const bool on_grid = e.tick >= 0 && e.t_impulse == static_cast<double>(e.tick) * l.tick;
    rec->Margin("tick", on_grid ? 0.0 : -std::abs(e.t_impulse - static_cast<double>(e.tick) * l.tick), 0.0, where);
  }
}

}  // namespace

RigCheck CheckRigLimits(const ExactArrivalProblem& p, const ExactArrivalSummary& summary,
                        const RigCheckTolerances& tolerances, int samples_per_arc) {
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
    const Eigen::Vector3d dw =
        e.kind == ExactImpulseKind::kStart ? imp.state_after.omega : Eigen::Vector3d(imp.state_after.omega - state.omega);
    CheckImpulse(p, state.z, dw, tolerances, where, &rec);
    CheckTiming(p, e, k + 1 < n || summary.stop.has_value(), tolerances, where, &rec);
    const FreeMotion motion(p.model, FreeMotionStart{imp.state_after, x, A});
    for (int j = 1; j <= samples_per_arc; ++j) {
      const MotionSample sample = motion.At(e.duration * j / samples_per_arc);
      CheckPoint(p.limits, p.x0, sample.x, tolerances.position, "flight " + std::to_string(k), &rec);
      ++out.samples;
      if (j == samples_per_arc) state = sample.state, x = sample.x, A = sample.A;
    }
  }
  if (summary.stop) {
    CheckImpulse(p, state.z, -state.omega, tolerances, "the stop", &rec);
    CheckTiming(p, *summary.stop, false, tolerances, "the stop", &rec);
  }
  out.passed = out.violations.empty();
  return out;
}

}  // namespace plateball
