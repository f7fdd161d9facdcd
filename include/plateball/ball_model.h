// The symmetric ball (I1 = I2, centre of mass at the centre) between two plates, in the
// paper's normalised units (section 1, "Equations of motion"; section 2.1).
#pragma once

#include <string>

#include "plateball/export.h"

namespace plateball PLATEBALL_EXPORT {

/// Physical parameters of the plate-ball system (SI or any consistent units).
/// The upper plate moves with twice the velocity of the ball centre, so for momentum it counts
/// as M = ball_mass + 2 plate_mass (section 2.1).
struct PhysicalParameters {
  double inertia_1 = 0.0;   ///< I1 = I2, principal moment about an equatorial axis (> 0)
  double inertia_3 = 0.0;   ///< I3, moment about the symmetry axis (> 0, I3 <= 2 I1)
  double ball_mass = 0.0;   ///< M_ball (>= 0)
  double radius = 0.0;      ///< r (> 0)
  double plate_mass = 0.0;  ///< M_plate of the upper plate (>= 0)

  /// Empty when valid; otherwise names the first offending field, its value and the bound.
  std::string Validate() const;
  /// M = M_ball + 2 M_plate.
  double EffectiveMass() const { return ball_mass + 2.0 * plate_mass; }
};

/// The dimensionless model: alpha = I3/I1, beta = M r^2/I1, lambda = (alpha+beta)/(1+beta).
/// Only lambda enters the equations of motion (4)-(11).
class BallModel {
 public:
  /// Throws std::invalid_argument naming the field when a parameter is invalid.
  static BallModel FromPhysical(const PhysicalParameters& p);
  /// lambda in [1e-3, 1e3] (README, "Limits"); alpha and beta are then unknown (reported as 0 by has_inertia()).
  static BallModel FromLambda(double lambda);
  /// 0 < alpha <= 2 (a rigid body has I3 <= 2 I1), beta >= 0.
  static BallModel FromAlphaBeta(double alpha, double beta);

  double lambda() const { return lambda_; }
  bool has_inertia() const { return has_inertia_; }
  double alpha() const { return alpha_; }
  double beta() const { return beta_; }

  /// mu = 2E/(I1 + M r^2) for a kinetic energy E in physical units (requires FromPhysical).
  static double EnergyToMu(const PhysicalParameters& p, double kinetic_energy);

 private:
  BallModel(double lambda, double alpha, double beta, bool has_inertia)
      : lambda_(lambda), alpha_(alpha), beta_(beta), has_inertia_(has_inertia) {}
  double lambda_;
  double alpha_;
  double beta_;
  bool has_inertia_;
};

}  // namespace plateball
