// The constrained arrival's boundary with the rig problem (constrained_arrival.h): the problem's
// own admissibility (limits, masses, start and goal inside the plate, outside the obstacles, within
// the stroke) and the impulse times of a solution placed exactly on the controller's tick grid.
#include <algorithm>
#include <cmath>
#include <string>

#include "check.h"
#include "constrained_arrival.h"
#include "plateball/rig_limits.h"

namespace plateball::internal {

namespace {

std::string PointText(const Eigen::Vector2d& x) { return "(" + FormatNumber(x.x()) + ", " + FormatNumber(x.y()) + ")"; }

// The start and the goal must themselves meet the plate and obstacle limits.
void RequireAdmissiblePoint(const char* field, const Eigen::Vector2d& x, const RigLimits& l) {
  if (l.plate && SignedDistanceInside(*l.plate, x) < l.clearance)
    ThrowInvalid(field, PointText(x), "lies outside rig.plate (or within rig.clearance of its edge)");
  for (std::size_t i = 0; i < l.obstacles.size(); ++i)
    if (-SignedDistanceInside(l.obstacles[i], x) < l.clearance)
      ThrowInvalid(
          field, PointText(x), "lies inside rig.obstacles[" + std::to_string(i) + "] (or within rig.clearance of it)");
}

}  // namespace

void ValidateRigProblem(const RigLimits& l,
                        const std::optional<PhysicalParameters>& physical,
                        const Eigen::Vector2d& x0,
                        const Eigen::Vector2d& x1) {
  ThrowIfInvalid(l.Validate());
  if (l.NeedsPhysical() && !physical)
    ThrowInvalid(std::isinf(l.max_plate_impulse) ? "rig.max_force" : "rig.max_plate_impulse",
                 std::min(l.max_plate_impulse, l.max_force),
                 "needs ball.physical (a bare lambda fixes no masses)");
  if (physical) ThrowIfInvalid(physical->Validate());
  RequireAdmissiblePoint("x0", x0, l);
  RequireAdmissiblePoint("x1", x1, l);
  if (l.stroke && ((2.0 * (x1 - x0)).cwiseAbs().array() > l.stroke->array()).any())
    ThrowInvalid("x1", PointText(x1), "needs a plate displacement 2 (x1 - x0) beyond rig.stroke");
}

double PlaceOnGrid(double tick,
                   std::vector<ExactImpulse>* impulses,
                   std::optional<ExactImpulse>* stop,
                   double total_time) {
  if (!(tick > 0) || impulses->empty() || impulses->front().tick < 0) return total_time;
  std::vector<ExactImpulse*> all;
  for (ExactImpulse& e : *impulses) all.push_back(&e);
  if (*stop) all.push_back(&**stop);
  for (ExactImpulse* e : all) e->t_impulse = static_cast<double>(e->tick) * tick;
  for (std::size_t k = 0; k + 1 < all.size(); ++k) all[k]->duration = all[k + 1]->t_impulse - all[k]->t_impulse;
  const ExactImpulse& last = impulses->back();
  return last.t_impulse + last.duration;
}

}  // namespace plateball::internal
