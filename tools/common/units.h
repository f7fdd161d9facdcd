// Physical units next to the normalised ones. With the problem file's ball.physical
// section (inertia_1, inertia_3, ball_mass, radius, plate_mass; validated by the reader, which
// names the field) a tool's JSON also reports times, distances and velocities in SI units.
//
// The paper normalises I1 = I2 = 1 and r = 1 (section 2.1); time is not rescaled, so with the
// physical section the normalised time is the second (mu = 2E/(I1 + M r^2) in s^-2,
// ball_model.h), a normalised length is r metres and a normalised velocity (the contact point's,
// the upper plate's 2 delta_omega x e3) is r metres per second. docs/units.md derives them.
#pragma once

#include <optional>

#include "common/json_output.h"
#include "plateball/problem.h"

namespace plateball::tools {

struct PhysicalScales {
  double length_m = 1.0;          ///< metres per normalised length (the radius r)
  double time_s = 1.0;            ///< seconds per normalised time
  double velocity_m_per_s = 1.0;  ///< metres per second per normalised velocity (r)
};

/// The scales of a problem with ball.physical; empty without it.
std::optional<PhysicalScales> ScalesOf(const Problem& problem);

/// With ball.physical: adds the document's "units" object (the physical parameters and the
/// scales) and, in every object of the document (not inside "samples", whose scales the "units"
/// object gives), an "si" object with the SI value of each time (t, t_impulse, duration,
/// total_time, period, t_end, horizon: s), length (x, x0, x_end, p, p_begin, p_end, target,
/// goal, start, length, distance, position_error, drift_per_period: m) and velocity
/// (plate_velocity_change, mean_velocity: m/s) it holds. Without it: nothing.
void AddPhysicalUnits(const Problem& problem, Json* doc);

}  // namespace plateball::tools
