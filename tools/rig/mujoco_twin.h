// The MuJoCo digital twin of the plate-ball machine: a fixed lower plate, the ball (a free body with
// its principal inertia along the symmetry axis) and the upper plate on three slide joints, pressed on
// the ball by its weight; contacts that hold the ball to rolling without slip or spin. MuJoCo's types
// stay in mujoco_twin.cc.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "plateball/ball_model.h"
#include "rig/rig_plan.h"

namespace plateball::tools::rig {

/// Engine settings (SI units). The defaults are the ones docs/mujoco_twin.md measures.
struct TwinSettings {
  double timestep = 1e-3;              ///< s, RK4 step
  double time_constant_steps = 2.0;    ///< contact solref time constant in timesteps (MuJoCo's minimum is 2)
  double sliding_friction = 100.0;     ///< dimensionless, both plates
  double torsional_friction = 1.0;     ///< m (MuJoCo's torsional coefficient: torque per normal force)
  double impedance = 0.9999;           ///< contact solimp dmin = dmax (MuJoCo's maximum; its default is 0.9 to 0.95)
  int noslip_iterations = 50;          ///< MuJoCo's no-slip post-processing iterations
  double gravity = 9.81;               ///< m/s^2: the plate's weight presses it on the ball
  double plate_half_size_radii = 1e3;  ///< upper plate's half side in ball radii
  /// Empty when valid, else "FIELD: value V: what is wrong".
  std::string Validate() const;
};

/// Empty when MuJoCo can build this ball and plate, else the message naming the field: MuJoCo's
/// compiler rejects a body whose principal moments break the triangle inequality (I3 > 2 I1) and a
/// moving body without mass (plate_mass = 0).
std::string TwinBuildableMessage(const PhysicalParameters& p);

/// The MJCF (MuJoCo XML) of the machine with the ball's centre above x0 (normalised contact point)
/// and orientation A0, and the keyframe "start": the ball rolling with angular velocity omega0 (its
/// vertical part dropped), the plate moving with the top point. Throws std::invalid_argument naming
/// the field for an unbuildable ball or invalid settings.
std::string TwinMjcf(const PhysicalParameters& p,
                     const Eigen::Vector2d& x0,
                     const Eigen::Matrix3d& A0,
                     const TwinSettings& settings,
                     const Eigen::Vector3d& omega0 = Eigen::Vector3d::Zero());

/// The engine's ball and plate at one instant (SI units; x normalised like the library's).
struct TwinState {
  double t = 0.0;
  Eigen::Vector2d x = Eigen::Vector2d::Zero();               ///< ball centre's horizontal position / r
  Eigen::Matrix3d A = Eigen::Matrix3d::Identity();           ///< R_WB
  Eigen::Vector3d omega = Eigen::Vector3d::Zero();           ///< spatial angular velocity, rad/s
  Eigen::Vector3d v = Eigen::Vector3d::Zero();               ///< ball centre's velocity, m/s
  Eigen::Vector3d plate_velocity = Eigen::Vector3d::Zero();  ///< m/s
  double energy = 0.0;      ///< horizontal kinetic energy of ball and plate plus the ball's rotation, J
  double slip_speed = 0.0;  ///< largest horizontal slip speed of the two contacts, m/s
  double spin_rate = 0.0;   ///< |omega_3| relative to the (non-rotating) plates, rad/s
  int contacts = 0;         ///< active contacts (2 while the ball is between the plates)
};

/// A loaded model and its data. Not copyable.
class MujocoTwin {
 public:
  /// Builds the machine (TwinMjcf) and lets the vertical contacts settle under gravity.
  MujocoTwin(const PhysicalParameters& p, const TwinSettings& settings);
  ~MujocoTwin();
  MujocoTwin(const MujocoTwin&) = delete;
  MujocoTwin& operator=(const MujocoTwin&) = delete;

  /// Places the ball (contact point x, orientation A) at time t with angular velocity omega and the
  /// rolling velocities of ball and plate; the settled heights stay.
  void SetState(double t, const Eigen::Vector2d& x, const Eigen::Matrix3d& A, const Eigen::Vector3d& omega);
  /// Sets omega (its vertical part dropped: no spin) and the rolling velocities (an ideal impulse).
  void SetAngularVelocity(const Eigen::Vector3d& omega);
  /// One RK4 step of length h <= the settings' timestep with a constant horizontal force on the plate.
  void Step(double h, const Eigen::Vector2d& plate_force);
  TwinState State() const;
  const TwinSettings& settings() const { return settings_; }

 private:
  struct Engine;
  std::unique_ptr<Engine> engine_;
  PhysicalParameters physical_;
  TwinSettings settings_;
};

/// How a plan is executed in the engine.
struct ReplayOptions {
  double pulse_duration = 0.0;  ///< s; 0: ideal velocity jumps at the impulse times
  bool causal = false;          ///< pulses over [t_k, t_k + D] instead of [t_k - D/2, t_k + D/2]
  TwinSettings settings;
  std::string Validate() const;
};

/// How far the engine ends from the plan, and what it saw on the way.
struct ReplayReport {
  double t_begin = 0.0, t_end = 0.0;  ///< s (t_begin < 0 when the first pulse starts before 0)
  int steps = 0;
  double position_error = 0.0;                 ///< |x_engine - x_plan| at t_end, normalised (r)
  double orientation_error = 0.0;              ///< angle of R_plan^T R_engine at t_end, rad
  double energy_planned = 0.0;                 ///< J
  double energy_engine = 0.0;                  ///< J
  double energy_error = 0.0;                   ///< |E_engine - E_plan| / the plan's largest energy (J when it is 0)
  double max_slip_speed = 0.0;                 ///< m/s over all steps
  double max_spin_rate = 0.0;                  ///< rad/s over all steps
  std::vector<Eigen::Vector3d> pulse_impulse;  ///< J per impulse (N s), PlateImpulseFor
};

/// The pulse windows [t_k - D/2, t_k + D/2] must not overlap and lie within the flights: throws
/// std::invalid_argument naming `field` and the impulse otherwise.
void CheckPulseWindows(const RigPlan& plan, double duration, const std::string& field);

/// The contacts must hold each pulse (PulseForcesFor with the engine's gravity and friction): the top
/// contact's friction impulse over D within mu_s M_plate g, the bottom's within mu_s (M_plate + M_ball) g,
/// the torsional one within mu_t times the two contacts' loads.
/// Throws std::invalid_argument naming `field` and the impulse that would slip otherwise.
void CheckPulseFriction(const RigPlan& plan, double duration, const TwinSettings& settings, const std::string& field);

/// The upper plate's half side in radii for a plan: the settings' at least, and twice the farthest the
/// contact point gets from its start (impulse points plus the longest flight at the largest speed).
double PlateHalfSizeFor(const RigPlan& plan, const PlannedTrajectory& reference, const TwinSettings& settings);

/// Runs the plan in the engine from its start to max(t_end, last pulse's end) and compares with the
/// planned trajectory at that time. Ideal jumps set omega to the planned post-impulse omega at each
/// impulse time; pulses apply the force J/D to the plate over the centred (or causal) window, J =
/// PlateImpulseFor(z_k, delta_omega_k).plate. Throws std::invalid_argument for invalid options or
/// windows or more than 1e8 steps, std::runtime_error when the ball leaves the plates.
ReplayReport ReplayInTwin(const RigPlan& plan, const PlannedTrajectory& reference, const ReplayOptions& options);

}  // namespace plateball::tools::rig
