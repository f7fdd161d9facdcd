// Internal: the planner for explicit per-piece partitions (PlanImpulses unpacks its problem into
// this), with the option of a tick grid for the impulse times, which the rig-honouring planner
// (rig_planner.h) uses.
#pragma once

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "plateball/impulse_planner.h"

namespace plateball::internal {

/// Impulse times on a grid: each interior partition point of a piece slides along the path (a 1-D
/// root find in tau between its neighbours) so that the ball arrives there at a multiple of `tick`,
/// at least `min_interval` after the impulse before; the flight then lasts exactly the grid
/// difference and t_impulse is the multiple itself. The ends of a piece are fixed points of the
/// path and do not slide. tick = 0: no grid (the partition is planned as given).
struct PlanGrid {
  double tick = 0.0;
  double min_interval = 0.0;
};

/// What the grid did: the points slid onto it, and one line per point that could not be.
struct PlanGridReport {
  int slid = 0;
  std::vector<std::string> missed;
  /// The points of `missed`: (piece, index of the point in the piece's partition).
  std::vector<std::pair<int, int>> missed_points;
};

/// The plan for explicit per-piece partitions (validated as PlanImpulses validates its problem).
/// With grid.tick > 0 the steps' tau_begin/tau_end are the slid partition points; `report` (may
/// be null) tells what the grid did.
PlanSummary PlanPartitioned(const BallModel& model,
                            const AngleState& initial,
                            double mu,
                            const Eigen::Matrix3d& A0,
                            const Path& path,
                            const std::vector<std::vector<double>>& partition,
                            const std::vector<EnergyChange>& energy_changes,
                            const PlanOptions& options,
                            const PlanGrid& grid = {},
                            PlanGridReport* report = nullptr);

}  // namespace plateball::internal
