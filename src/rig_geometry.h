// Internal: the margins of the geometric limits at one contact point, shared by the independent
// check (rig_check.cc) and the reference choice (rig_reference.cc). The solver's constraints
// (constrained_arrival.cc) are the same margins tightened by its sampling margin, with gradients.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <string>

#include "plateball/rig_limits.h"

namespace plateball::internal {

/// Calls visit(name, margin) for each plate, obstacle and stroke limit at the contact point x
/// (margin = bound - value, in radii: >= 0 when met); x0 is the stroke's origin.
template <typename Visit>
void VisitGeometricMargins(const RigLimits& l, const Eigen::Vector2d& x0, const Eigen::Vector2d& x, Visit&& visit) {
  if (l.plate) visit(std::string("plate"), SignedDistanceInside(*l.plate, x) - l.clearance);
  for (std::size_t i = 0; i < l.obstacles.size(); ++i)
    visit("obstacles[" + std::to_string(i) + "]", -SignedDistanceInside(l.obstacles[i], x) - l.clearance);
  if (l.stroke) {
    const Eigen::Vector2d disp = 2.0 * (x - x0);
    visit(std::string("stroke.x"), l.stroke->x() - std::abs(disp.x()));
    visit(std::string("stroke.y"), l.stroke->y() - std::abs(disp.y()));
  }
}

}  // namespace plateball::internal
