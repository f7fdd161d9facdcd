// The pulse's mean forces and the contacts' friction demand, checked against the homogeneous ball's
// closed form (where the contact impulses follow from the ball's momentum and the angular momentum
// about its centre alone), the tilted ball's torsional impulse, and the schedule's bad cases.
#include "plateball/actuator_command.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "support/test_support.h"

namespace plateball {
namespace {

// Closed forms evaluated in a different order than the library: a few ulps of the forces.
constexpr double kRelative = 1e-13;

using plateball::testing::PhysicalUnitsBall;

TEST(ActuatorCommand, HomogeneousBallForcesMatchTheClosedForm) {
  // I = I0: the ball's angular momentum about its centre changes by I0 dw = r e3 x (Q - G) and its
  // momentum by M r dw x e3 = Q + G, so |Q| = (I0 + M r^2) |dw| / (2 r) and |G| = |M r^2 - I0| |dw| / (2 r).
  PhysicalParameters p = PhysicalUnitsBall();
  p.inertia_1 = p.inertia_3 = 0.4 * p.ball_mass * p.radius * p.radius;
  const double i0 = p.inertia_1, m = p.ball_mass, r = p.radius;
  const Eigen::Vector3d dw(3.0, -4.0, 0.0);  // |dw| = 5 rad/s
  PulseOptions o;
  o.duration = 2e-3;
  o.preload = 0.3;
  const PulseForces f = PulseForcesFor(p, PlateImpulseFor(p, Eigen::Vector3d(0.6, 0, 0.8), dw), o);
  const double top = (i0 + m * r * r) * 5.0 / (2 * r) / o.duration;
  const double bottom = std::abs(m * r * r - i0) * 5.0 / (2 * r) / o.duration;
  const double n_top = p.plate_mass * 9.80665 + 0.3, n_bottom = n_top + m * 9.80665;
  EXPECT_NEAR(f.top_tangential_force, top, kRelative * top);
  EXPECT_NEAR(f.bottom_tangential_force, bottom, kRelative * top);
  EXPECT_NEAR(f.top_normal_load, n_top, kRelative * n_top);
  EXPECT_NEAR(f.bottom_normal_load, n_bottom, kRelative * n_bottom);
  EXPECT_NEAR(f.sliding_friction_needed, std::max(top / n_top, bottom / n_bottom), kRelative * top / n_top);
  // The plate's force: the system's mass at the plate times dV / delta, with |dV| = 2 r |dw|.
  const double mass_at_plate = (i0 + m * r * r) / (4 * r * r) + p.plate_mass;
  EXPECT_NEAR(f.mean_force.norm(), mass_at_plate * 2 * r * 5.0 / o.duration, kRelative * top);
  EXPECT_EQ(f.torsional_torque, 0.0);
  EXPECT_FALSE(f.slides);
  EXPECT_FALSE(f.spins);
}

TEST(ActuatorCommand, SlipAndSpinAreFlaggedAgainstTheGivenFriction) {
  // A tilted non-homogeneous ball: z = (1, 0, 1)/sqrt(2), dw = e1 needs the torsional impulse
  // (I3 - I1) (z . dw) z3 = (I3 - I1)/2 (PlateImpulse.TheImpulseDependsOnTheOrientation).
  const PhysicalParameters p = PhysicalUnitsBall();
  const PlateImpulse j = PlateImpulseFor(p, Eigen::Vector3d(1, 0, 1).normalized(), Eigen::Vector3d(1, 0, 0));
  PulseOptions o;
  o.duration = 1e-2;
  const PulseForces need = PulseForcesFor(p, j, o);
  const double torque = 0.5 * (p.inertia_1 - p.inertia_3) / o.duration;
  EXPECT_NEAR(need.torsional_torque, torque, kRelative * torque);
  EXPECT_NEAR(need.torsional_friction_needed,
              torque / ((2 * p.plate_mass + p.ball_mass) * 9.80665),
              kRelative * need.torsional_friction_needed);
  for (const double factor : {0.99, 1.01}) {
    o.static_friction = factor * need.sliding_friction_needed;
    o.torsional_friction = factor * need.torsional_friction_needed;
    const PulseForces f = PulseForcesFor(p, j, o);
    EXPECT_EQ(f.slides, factor < 1) << factor;
    EXPECT_EQ(f.spins, factor < 1) << factor;
  }
  // A longer pulse needs proportionally less friction.
  o.duration *= 4;
  EXPECT_NEAR(PulseForcesFor(p, j, o).sliding_friction_needed,
              need.sliding_friction_needed / 4,
              kRelative * need.sliding_friction_needed);
}

TEST(ActuatorCommand, AnUnloadedMasslessPlateCannotHoldTheBall) {
  PhysicalParameters p = PhysicalUnitsBall();
  p.plate_mass = 0.0;
  const PulseForces f = PulseForcesFor(p, PlateImpulseFor(p, Eigen::Vector3d::UnitZ(), {1, 0, 0}), PulseOptions{});
  EXPECT_EQ(f.top_normal_load, 0.0);
  EXPECT_EQ(f.sliding_friction_needed, std::numeric_limits<double>::infinity());
}

TEST(ActuatorCommand, ScheduleRejectsPulsesThatDoNotFitNamingTheImpulse) {
  const std::vector<double> times{0.5, 1.0, 1.2};
  EXPECT_EQ(CheckPulseSchedule(times, 2.0, 0.19, PulseAlignment::kCentred), "");
  EXPECT_EQ(CheckPulseSchedule(times, 2.0, 0.19, PulseAlignment::kCausal), "");
  const std::string overlap = CheckPulseSchedule(times, 2.0, 0.25, PulseAlignment::kCentred);
  EXPECT_NE(overlap.find("impulses[2].time: value 1.2"), std::string::npos) << overlap;
  EXPECT_NE(overlap.find("overlaps"), std::string::npos) << overlap;
  // A centred pulse at t = 0.1 starts before 0; a causal one does not.
  EXPECT_NE(CheckPulseSchedule({0.1}, 1.0, 0.3, PulseAlignment::kCentred).find("impulses[0].time: value 0.1"),
            std::string::npos);
  EXPECT_EQ(CheckPulseSchedule({0.1}, 1.0, 0.3, PulseAlignment::kCausal), "");
  EXPECT_NE(CheckPulseSchedule({0.9}, 1.0, 0.3, PulseAlignment::kCausal).find("ends after the final time 1"),
            std::string::npos);
  EXPECT_NE(CheckPulseSchedule(times, 2.0, 0.0, PulseAlignment::kCentred).find("pulse.duration: value 0"),
            std::string::npos);
}

TEST(ActuatorCommand, InvalidOptionsAreRejectedNamingTheField) {
  const auto message = [](auto&& f) { return plateball::testing::InvalidArgumentMessage(f, "no exception"); };
  const PhysicalParameters p = PhysicalUnitsBall();
  const PlateImpulse j = PlateImpulseFor(p, Eigen::Vector3d::UnitZ(), {1, 0, 0});
  PulseOptions o;
  o.duration = -1;
  EXPECT_NE(message([&] { PulseForcesFor(p, j, o); }).find("pulse.duration: value -1"), std::string::npos);
  o = PulseOptions{};
  o.static_friction = NAN;
  EXPECT_NE(message([&] { PulseForcesFor(p, j, o); }).find("pulse.static_friction: value nan"), std::string::npos);
  o = PulseOptions{};
  o.preload = -2;
  EXPECT_NE(o.Validate().find("pulse.preload: value -2"), std::string::npos);
}

}  // namespace
}  // namespace plateball
