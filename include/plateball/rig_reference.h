// The reference of a rig: whether a planned path meets the plate, obstacle and stroke limits
// (rig_limits.h), and which isoparallel solution to steer along when the shortest one does not.
//
// Method. The isoparallel solver returns every distinct solution it found, sorted by length
// (isoparallel.h). Each optimal path is sampled densely and checked against the geometric limits
// (the impulse and timing limits concern the impulses, not the path). The reference is the
// shortest solution that meets them; when none does, the shortest one (the constrained exact
// arrival then moves the impulsive path inside, and its report says so).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "plateball/export.h"
#include "plateball/isoparallel.h"
#include "plateball/path.h"
#include "plateball/rig_limits.h"

namespace plateball PLATEBALL_EXPORT {

/// The plate, obstacle and stroke limits ("plate", "obstacles[i]", "stroke.x", "stroke.y") that the
/// path breaks at any of `samples_per_piece` + 1 points of each piece (x0: the stroke's origin).
std::vector<std::string> PathLimitBreaks(const Path& path,
                                         const RigLimits& limits,
                                         const Eigen::Vector2d& x0,
                                         int samples_per_piece = 2000);

struct ReferenceChoice {
  std::size_t index = 0;                     ///< the solution steered along
  std::vector<std::string> shortest_breaks;  ///< the limits the shortest solution's path breaks
  std::vector<std::string> chosen_breaks;    ///< those the chosen one breaks (empty when it meets them)
};

/// The shortest solution of `summary` whose optimal path meets the geometric limits, else the
/// shortest. The summary must hold at least one solution (std::invalid_argument otherwise).
ReferenceChoice ChooseIsoparallelReference(const IsoparallelSummary& summary,
                                           const RigLimits& limits,
                                           const Eigen::Vector2d& x0);

}  // namespace PLATEBALL_EXPORT
