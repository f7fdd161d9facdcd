// The impulse schedule of a `plan`, `steer` or `isoparallel` result, read back for the MuJoCo twin (`plateball rig`),
// and the planned impulsive trajectory it defines (the reference the engine is compared with).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "plateball/ball_model.h"
#include "plateball/ball_state.h"
#include "plateball/free_motion.h"
#include "plateball/integration_options.h"
#include "plateball/problem.h"

namespace plateball::tools::rig {

/// One planned impulse: at time t the ball's angular velocity jumps by delta_omega to omega_after.
struct RigImpulse {
  double t = 0.0;                                         ///< s since the start
  Eigen::Vector3d z = Eigen::Vector3d::UnitZ();           ///< symmetry axis at the impulse
  Eigen::Vector3d delta_omega = Eigen::Vector3d::Zero();  ///< rad/s
  Eigen::Vector3d omega_after = Eigen::Vector3d::Zero();  ///< planned post-impulse omega, rad/s
};

/// What the twin needs of a result: the physical ball, the start and the impulses (SI units: the
/// normalised time is the second and omega is in rad/s; positions are normalised, r metres each).
struct RigPlan {
  std::string command;  ///< "plan", "steer" or "isoparallel" (empty for a free motion)
  Problem problem;      ///< the problem file the result names
  PhysicalParameters physical;
  BallModel model = BallModel::FromLambda(1.0);
  BallState start;                                   ///< before the first impulse, at t = 0
  Eigen::Vector2d x0 = Eigen::Vector2d::Zero();      ///< contact point at t = 0 (normalised)
  Eigen::Matrix3d A0 = Eigen::Matrix3d::Identity();  ///< R_WB at t = 0, A0 e3 = start.z
  std::vector<RigImpulse> impulses;                  ///< increasing t in [0, t_end]
  double t_end = 0.0;                                ///< s
  IntegrationOptions integration;
};

/// Reads a `plateball plan`, `steer` or `isoparallel` (`isoparallel_solve --out`) result (with its
/// per-impulse records) and the problem file it names (as `plateball view` does: as given, else
/// beside the result). Throws
/// std::invalid_argument "FIELD: value V: what is wrong" for a result without ball.physical, of
/// another command, without impulses or with impulses out of order.
RigPlan ReadRigPlan(const std::string& result_file);

/// The planned impulsive trajectory: free arcs (FreeMotion) from each impulse's planned
/// post-impulse omega, the position and orientation carried over from the previous arc.
class PlannedTrajectory {
 public:
  explicit PlannedTrajectory(const RigPlan& plan);
  /// The planned state at any t >= 0 (after an impulse at exactly t).
  MotionSample At(double t) const;
  /// Kinetic energy of ball and plate in J at the planned state: mu (I1 + M r^2) / 2.
  double EnergyAt(double t) const;
  /// The largest kinetic energy of the plan's arcs in J (the scale of its energy errors).
  double MaxEnergy() const { return max_energy_; }

 private:
  struct Arc {
    double t0 = 0.0;
    std::shared_ptr<const FreeMotion> motion;  ///< null for a ball at rest
    MotionSample rest;                         ///< the state of a ball at rest
  };
  const Arc& ArcAt(double t) const;
  RigPlan plan_;
  std::vector<Arc> arcs_;
  double max_energy_ = 0.0;
};

}  // namespace plateball::tools::rig
