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
#include <variant>
#include <vector>

#include "plateball/ball_model.h"
#include "plateball/ball_state.h"
#include "plateball/export.h"
#include "plateball/fewest_impulses.h"
#include "plateball/field_list.h"
#include "plateball/impulse_planner.h"
#include "plateball/integration_options.h"
#include "plateball/isoparallel.h"
#include "plateball/limits.h"
#include "plateball/partition.h"
#include "plateball/rig_limits.h"
#include "plateball/start_state.h"

namespace plateball PLATEBALL_EXPORT {

/// A planned planar path (JSON object "path"): a closed set of shapes, one struct per JSON
/// "type". Each is turned into a library Path by PathFromSpec (task_adapters.h).
/// "line": p = from + tau (to - from), tau in [0, 1].
struct LineSpec {
  Eigen::Vector2d from = Eigen::Vector2d::Zero();
  Eigen::Vector2d to = Eigen::Vector2d::UnitX();
};
/// "circle": p = center + radius (cos tau, sin tau), tau from tau_begin to tau_end.
struct CircleSpec {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double radius = 1.0;
  double tau_begin = 0.0;
  double tau_end = 2 * M_PI;
};
/// "ellipse": p = center + Rot(rotation) (a cos tau, b sin tau), (a, b) = semi_axes.
struct EllipseSpec {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  Eigen::Vector2d semi_axes = Eigen::Vector2d::Ones();
  double rotation = 0.0;
  double tau_begin = 0.0;
  double tau_end = 2 * M_PI;
};
/// "lemniscate" (Bernoulli, half-width `scale`):
/// p = center + Rot(rotation) scale (cos tau, sin tau cos tau) / (1 + sin^2 tau).
struct LemniscateSpec {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double scale = 1.0;
  double rotation = 0.0;
  double tau_begin = 0.0;
  double tau_end = 2 * M_PI;
};
/// "sine": p = from + Rot(rotation) (tau, amplitude sin(2 pi tau / wavelength)), tau in [0, length].
struct SineSpec {
  Eigen::Vector2d from = Eigen::Vector2d::Zero();
  double rotation = 0.0;  ///< direction of travel
  double length = 1.0;
  double amplitude = 0.0;
  double wavelength = 1.0;
};
/// "samples": points (>= 2), interpolated by a natural C^2 cubic spline, tau = chord length.
struct SamplesSpec {
  std::vector<Eigen::Vector2d> points;
};
struct PathSpec;
/// "piecewise": pieces (>= 1 smooth PathSpec, consecutive pieces share end points).
struct PiecewiseSpec {
  std::vector<PathSpec> pieces;
};
struct PathSpec {
  using Shape = std::variant<LineSpec, CircleSpec, EllipseSpec, LemniscateSpec, SineSpec, SamplesSpec, PiecewiseSpec>;
  Shape shape;
};
/// The JSON "type" of a path: "line", "circle", ..., "piecewise".
std::string ToString(const PathSpec& spec);

/// How the path parameter interval is partitioned (JSON object "partition"): the planner's
/// PartitionRule (partition.h). "uniform_parameter" (n, default 16), "uniform_arc_length" (n) or
/// "explicit" (taus: strictly increasing, first and last at the ends of the parameter interval;
/// single-piece paths only). For piecewise paths n applies to each piece.
using PartitionSpec = PartitionRule;

/// An energy-changing impulse inserted into a plan (JSON "energy_changes"): the planner's
/// EnergyChange (impulse_planner.h).
using EnergyChangeSpec = EnergyChange;

/// `plateball simulate`: sample the free motion on [0, t_end].
struct SimulateTask {
  double t_end = 10.0;
  int samples = 101;

  /// The field list (field_list.h): the problem file's "simulate" section.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(PLATEBALL_FIELD(t_end, "end of the sampled time span [0, t_end]").Positive(),
             PLATEBALL_FIELD(samples, "number of samples, both ends included").Counts(2, limits::kMaxSamples));
  }
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

/// The isoparallel problem (section 2.2): shortest path from (start, A_start) to (goal, A_goal).
struct IsoparallelTask {
  Eigen::Vector2d start = Eigen::Vector2d::Zero();
  Eigen::Vector2d goal = Eigen::Vector2d::Zero();
  Eigen::Matrix3d start_orientation = Eigen::Matrix3d::Identity();
  Eigen::Matrix3d goal_orientation = Eigen::Matrix3d::Identity();
  int impulses = 12;  ///< partition size of the impulsive approximation
  /// JSON "solver": read straight into the solver's options with its ranges (isoparallel.h);
  /// the task adapter adds the file's seed and integration section.
  IsoparallelOptions solver;
};

/// `plateball steer` / `isoparallel_solve --exact`: exact arrival at (goal,
/// goal_orientation) with `impulses` impulses along a reference: the plan section's path when the
/// file has one, else the shortest isoparallel path.
struct SteerTask {
  Eigen::Vector2d goal = Eigen::Vector2d::Zero();
  Eigen::Matrix3d goal_orientation = Eigen::Matrix3d::Identity();
  int impulses = 12;           ///< n >= 3
  bool start_at_rest = false;  ///< the ball starts at rest (first impulse energy-changing)
  bool stop_at_goal = false;   ///< arrive and stop: one more impulse brings omega to zero
  /// What the exact arrival minimises under the rig's limits (rig_limits.h).
  ArrivalObjective objective = ArrivalObjective::kDeviation;
  /// `fewest` (fewest_impulses.h): the search's settings; present = the file asks for the fewest
  /// impulses (`plateball steer` runs the search instead of the exact arrival along a reference).
  struct Fewest {
    int max_impulses = 6;
    int starts = 24;
    int pareto_counts = 3;
    double max_total_time = 0.0;  ///< 0: automatic
    bool orientation_only = false;

    /// The field list (field_list.h): the problem file's "steer.fewest" section.
    template <class Archive>
    void Serialize(Archive* a) {
      using O = FewestImpulsesOptions;
      a->Visit(PLATEBALL_FIELD(max_impulses, "largest impulse count searched").Counts(1, O::kMaxImpulses),
               PLATEBALL_FIELD(starts, "starts per count").Counts(1, O::kMaxStarts),
               PLATEBALL_FIELD(pareto_counts, "rows of the Pareto table from the fewest count up")
                   .Counts(1, O::kMaxImpulses),
               PLATEBALL_FIELD(max_total_time, "search window: total time T <= max_total_time")
                   .NonNegative(kMaxTotalTime, "0: automatic"),
               PLATEBALL_FIELD(orientation_only, "only the goal orientation is prescribed (three conditions)"));
    }
    /// The largest search window a problem file may ask for: the library's.
    static constexpr double kMaxTotalTime = FewestImpulsesOptions::kMaxTotalTime;
  };
  std::optional<Fewest> fewest;
};

/// Golden values a problem file may carry ("expected"): name -> value, with a tolerance each.
struct ExpectedValue {
  double value = 0.0;
  double tolerance = 0.0;
};

/// The start state (StartState: JSON "model", "initial", "mu", "x0" and "orientation", which a file
/// may give as a quaternion, a rotation matrix or an axis-angle) and the task sections.
struct Problem : StartState {
  std::string source = "<memory>";  ///< file name, for messages
  std::string name;
  std::string description;
  std::optional<PhysicalParameters> physical;  ///< when the file gave physical parameters
  std::uint64_t seed = 1;
  IntegrationOptions integration;

  std::optional<SimulateTask> simulate;
  std::optional<ReachTask> reach;
  std::optional<PlanTask> plan;
  std::optional<IsoparallelTask> isoparallel;
  std::optional<SteerTask> steer;
  /// The rig's limits (JSON "rig"), honoured by `steer`; empty: an unbounded plate and actuator.
  RigLimits rig;
  std::map<std::string, ExpectedValue> expected;
};

}  // namespace PLATEBALL_EXPORT
