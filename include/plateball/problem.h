// A plateball problem: the value read from a JSON problem file (problem_io.h). It is separate
// from the solvers (OMPL's ProblemDefinition): the ball, its initial state and orientation, and
// a task section. Every field is documented with its JSON key in README.md ("Problem files").
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "plateball/ball_model.h"
#include "plateball/ball_state.h"
#include "plateball/export.h"
#include "plateball/integration_options.h"

namespace plateball PLATEBALL_EXPORT {

/// A planned planar path (JSON object "path"). `type` selects which fields are used:
///  "line":       from, to                             tau in [0, 1]
///  "circle":     center, radius, tau_begin, tau_end   p = center + radius (cos tau, sin tau)
///  "ellipse":    center, semi_axes (a, b), rotation, tau_begin, tau_end
///                p = center + Rot(rotation) (a cos tau, b sin tau)
///  "lemniscate": center, scale, rotation, tau_begin, tau_end   (Bernoulli, half-width `scale`)
///                p = center + Rot(rotation) scale (cos tau, sin tau cos tau) / (1 + sin^2 tau)
///  "sine":       from, rotation (direction of travel), length, amplitude, wavelength
///                p = from + Rot(rotation) (tau, amplitude sin(2 pi tau / wavelength)), tau in [0, length]
///  "samples":    points (>= 2), interpolated by a natural C^2 cubic spline, tau = chord length
///  "piecewise":  pieces (>= 1 PathSpec, consecutive pieces share end points)
struct PathSpec {
  std::string type;
  Eigen::Vector2d from = Eigen::Vector2d::Zero();
  Eigen::Vector2d to = Eigen::Vector2d::Zero();
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double radius = 0.0;
  Eigen::Vector2d semi_axes = Eigen::Vector2d::Zero();
  double rotation = 0.0;
  double scale = 0.0;
  double length = 0.0;
  double amplitude = 0.0;
  double wavelength = 0.0;
  double tau_begin = 0.0;
  double tau_end = 0.0;
  std::vector<Eigen::Vector2d> points;
  std::vector<PathSpec> pieces;
};

/// How the path parameter interval is partitioned (JSON object "partition").
///  "uniform_parameter": n equal steps of tau; "uniform_arc_length": n equal steps of arc
///  length; "explicit": the given parameter values (strictly increasing, first and last at the
///  ends of the parameter interval). For piecewise paths n applies to each piece.
struct PartitionSpec {
  std::string type = "uniform_parameter";
  int n = 16;
  std::vector<double> taus;
};

/// An energy-changing impulse inserted into a plan (JSON "energy_changes"): at partition point
/// `index` the speed |omega| is multiplied by `factor` (> 0); the path is unchanged.
struct EnergyChangeSpec {
  int index = 0;
  double factor = 1.0;
};

/// `plateball simulate`: sample the free motion on [0, t_end].
struct SimulateTask {
  double t_end = 10.0;
  int samples = 101;
};

/// `plateball join` / `plateball reach`: reach target points from the initial state.
struct ReachTask {
  std::vector<Eigen::Vector2d> targets;
  double horizon_periods = 5.0;  ///< solutions with t below this many periods are enumerated
};

/// `plateball plan` / `plateball converge`: follow a planned path with impulses.
struct PlanTask {
  PathSpec path;
  PartitionSpec partition;
  std::vector<EnergyChangeSpec> energy_changes;
  std::vector<int> converge_n;  ///< the n values of a convergence study (may be empty)
};

/// Options of the isoparallel solver (JSON object "solver" inside "isoparallel").
struct IsoparallelSolverSpec {
  int starts = 1024;                 ///< multi-start count (seeded; shooting only)
  double length_cap_factor = 3.0;    ///< report solutions up to this times the shortest length
  int max_iterations = 100;          ///< per Ceres solve
  double tolerance = 1e-12;          ///< residual tolerance of an accepted solution
  int threads = 1;
  /// Identity targets: enumerate the one-parameter families directly (complete up to the cap)
  /// instead of the multi-start shooting.
  bool enumerate_families = true;
};

/// The isoparallel problem (section 2.2): shortest path from (start, A_start) to (goal, A_goal).
struct IsoparallelTask {
  Eigen::Vector2d start = Eigen::Vector2d::Zero();
  Eigen::Vector2d goal = Eigen::Vector2d::Zero();
  Eigen::Matrix3d start_orientation = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d goal_orientation = Eigen::Matrix3d::Identity();
  int impulses = 12;  ///< partition size of the impulsive approximation
  IsoparallelSolverSpec solver;
};

/// Golden values a problem file may carry ("expected"): name -> value, with a tolerance each.
struct ExpectedValue {
  double value = 0.0;
  double tolerance = 0.0;
};

struct Problem {
  std::string source = "<memory>";  ///< file name, for messages
  std::string name;
  std::string description;
  BallModel model = BallModel::FromLambda(1.0);
  std::optional<PhysicalParameters> physical;  ///< when the file gave physical parameters
  AngleState initial_angles{M_PI / 3, 0.4, 0.1};
  double mu = 1.0;
  Eigen::Vector2d x0 = Eigen::Vector2d::Zero();
  /// Initial orientation R_WB. Its third column is set to the z of the initial angles by the
  /// solvers (FreeMotion::FromAngles rotates it minimally); a file may give it as a quaternion,
  /// a rotation matrix or an axis-angle.
  Eigen::Matrix3d A0 = Eigen::Matrix3d::Identity();
  std::uint64_t seed = 1;
  IntegrationOptions integration;

  std::optional<SimulateTask> simulate;
  std::optional<ReachTask> reach;
  std::optional<PlanTask> plan;
  std::optional<IsoparallelTask> isoparallel;
  std::map<std::string, ExpectedValue> expected;
};

}  // namespace plateball
