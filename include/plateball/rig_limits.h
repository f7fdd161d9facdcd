// The limits of a physical rig that a plan must respect: a plate of finite size, obstacles on it,
// the upper plate's finite stroke, the actuator's largest impulse or plate velocity change, its
// shortest recovery time between impulses, and the control loop's tick (impulse times on a grid).
//
// Lengths are in ball radii and times in the problem's time unit (the second with ball.physical,
// units.h); the impulse bound is in the units of PhysicalParameters (N s for SI input).
//
// Geometry. The contact point x(t) is the ball center's horizontal position, and the upper plate
// moves at twice the center's velocity (it rolls on the top of the ball), so its displacement from
// its start is 2 (x(t) - x0): the stroke box |2 (x - x0)_i| <= stroke_i is a box for the contact
// point of half-widths stroke_i / 2 around x0.
#pragma once

#include <Eigen/Core>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "plateball/ball_model.h"
#include "plateball/export.h"
#include "plateball/field_list.h"

namespace plateball PLATEBALL_EXPORT {

/// A disk of the plate: |x - center| <= radius.
struct DiskShape {
  Eigen::Vector2d center = Eigen::Vector2d::Zero();
  double radius = 1.0;
};
/// A simple polygon (vertices in either orientation, not repeated at the end, >= 3). A rectangle
/// of the problem file is read as its four corners.
struct PolygonShape {
  std::vector<Eigen::Vector2d> vertices;
};
using PlateShape = std::variant<DiskShape, PolygonShape>;

/// Signed distance of x to the shape's boundary, positive inside, and its gradient (the unit
/// normal towards the inside at the nearest boundary point).
double SignedDistanceInside(const PlateShape& shape, const Eigen::Vector2d& x, Eigen::Vector2d* gradient = nullptr);

/// What a constrained exact arrival minimises besides arriving and meeting the limits: the
/// deviation from the reference (as without limits), the total time, or the total impulse (sum of
/// |J| with physical parameters, else of the plate velocity changes). kFewest asks for the fewest
/// impulses: the fewest-impulse search (fewest_impulses.h), not an exact arrival along a reference.
enum class ArrivalObjective { kDeviation, kTotalTime, kTotalImpulse, kFewest };
/// "deviation", "time", "impulse" or "fewest", as in the problem file and the JSON.
std::string ToString(ArrivalObjective objective);
/// The objective of a word of ToString; empty for another word.
std::optional<ArrivalObjective> ArrivalObjectiveFromString(const std::string& word);

struct RigLimits {
  /// The region the contact point must stay in, `clearance` away from its edge (none: unbounded).
  std::optional<PlateShape> plate;
  /// Regions the contact point must stay out of, `clearance` away from their edges.
  std::vector<PlateShape> obstacles;
  double clearance = 0.0;  ///< >= 0, ball radii
  /// Half-ranges (s_x, s_y) of the upper plate's displacement from its start: |2 (x - x0)_i| <= s_i.
  std::optional<Eigen::Vector2d> stroke;
  /// Largest |2 delta_omega x e3| of one impulse: the plate's velocity change (r per time unit).
  double max_plate_velocity_change = std::numeric_limits<double>::infinity();
  /// Largest |J| of one impulse (PlateImpulseFor); needs the physical parameters.
  double max_plate_impulse = std::numeric_limits<double>::infinity();
  /// Largest mean force |J| / pulse_duration of a pulse of `pulse_duration`; needs both.
  double max_force = std::numeric_limits<double>::infinity();
  double pulse_duration = 0.0;
  double min_interval = 0.0;  ///< shortest time between two impulses (actuator recovery)
  double tick = 0.0;          ///< impulse times are multiples of tick (0: any time)

  /// True when no limit is set (every plan satisfies it).
  bool Empty() const;
  /// The bound on |J| from max_plate_impulse and max_force x pulse_duration (infinite when unset).
  double ImpulseBound() const;
  /// True when an impulse bound needs the physical parameters (max_plate_impulse or max_force set).
  bool NeedsPhysical() const;
  /// Empty when valid; else a message naming the field (rig.plate.radius, rig.obstacles[1], ...).
  std::string Validate() const;

  /// The fields of a problem file's "rig" section, in its key order (field_list.h). The shapes
  /// and the stroke (nested, scaled by the section's length_unit) and pulse_duration (present
  /// exactly when max_force is) are read and written by the section's own code.
  template <class Archive>
  void Serialize(Archive* a) {
    constexpr double kUnbounded = std::numeric_limits<double>::infinity();
    a->Visit(
        PLATEBALL_FIELD(plate, "the region the contact point stays in").ByHand(),
        PLATEBALL_FIELD(obstacles, "regions the contact point stays out of").ByHand(),
        PLATEBALL_FIELD(clearance, "distance kept from the edges of the plate and the obstacles").NonNegative(),
        PLATEBALL_FIELD(stroke, "half-ranges of the upper plate's displacement 2 (x - x0) from its start").ByHand(),
        PLATEBALL_FIELD(max_plate_velocity_change, "largest plate velocity change |2 delta_omega x e3| of one impulse")
            .Positive()
            .OmittedAt(kUnbounded),
        PLATEBALL_FIELD(max_plate_impulse, "largest |J| (N s with SI physical parameters); needs ball.physical")
            .Positive()
            .OmittedAt(kUnbounded),
        PLATEBALL_FIELD(max_force, "largest mean force |J| / pulse_duration; needs ball.physical and pulse_duration")
            .Positive()
            .OmittedAt(kUnbounded),
        PLATEBALL_FIELD(pulse_duration, "duration of a pulse; only with max_force").ByHand(),
        PLATEBALL_FIELD(min_interval, "shortest time between two impulses").NonNegative().OmittedAt(0.0),
        PLATEBALL_FIELD(tick, "impulse times are multiples of tick (the control loop's period)")
            .Positive()
            .OmittedAt(0.0));
  }
};

/// What the solver reports about the limits in its result.
struct RigLimitsReport {
  bool constrained = false;         ///< the limits cut the free optimum: the constrained solve ran
  std::vector<std::string> active;  ///< limits active at the result ("plate", "obstacles[0]", ...)
  /// When the limits could not be met together with the arrival: the limits active at the closest
  /// feasible arrival, which block the goal.
  std::vector<std::string> blocking;
  int evaluations = 0;  ///< evaluations of the constrained solve(s) (Gauss-Newton SQP steps and SLSQP)
};

/// The independent check of a result: a replay with FreeMotion sampled densely on every arc.
struct RigCheck {
  bool passed = false;
  int samples = 0;  ///< contact points checked
  /// Per limit ("plate", "obstacles[0]", "stroke.x", "max_plate_impulse", "min_interval", ...): the
  /// smallest margin (bound - value, in the limit's unit) over everything checked; >= 0 when met.
  std::map<std::string, double> margins;
  std::vector<std::string>
      violations;  ///< one line per limit exceeded beyond its tolerance: its largest excess, and where
};

/// Tolerances of the check: positions and impulses to these; the grid exactly (tolerance zero).
struct RigCheckTolerances {
  double position = 1e-9;  ///< ball radii, for the plate, obstacles and stroke
  double impulse = 1e-9;   ///< relative, for the velocity-change and impulse bounds
  double time = 1e-12;     ///< relative, for the shortest interval

  /// The field list (field_list.h): the Python attributes and the ranges RigPlanOptions::Validate checks.
  template <class Archive>
  void Serialize(Archive* a) {
    a->Visit(PLATEBALL_FIELD(position, "tolerance of the plate, obstacles and stroke (ball radii)").NonNegative(),
             PLATEBALL_FIELD(impulse, "relative tolerance of the velocity-change and impulse bounds").NonNegative(),
             PLATEBALL_FIELD(time, "relative tolerance of the shortest interval").NonNegative());
  }
};

}  // namespace PLATEBALL_EXPORT
