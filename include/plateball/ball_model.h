// The symmetric ball (I1 = I2, centre of mass at the centre) between two plates, in the
// paper's normalised units (section 1, "Equations of motion"; section 2.1).
#pragma once

#include <string>

#include "plateball/export.h"

namespace plateball PLATEBALL_EXPORT {

/// Physical parameters of the plate-ball system (SI or any consistent units).
/// The upper plate rolls on the ball's top point, so it moves with twice the velocity v of the ball's
/// centre; its kinetic energy M_plate (2 v)^2 / 2 is that of a mass 4 M_plate moving with the centre.
/// The plate-ball system is therefore a ball of mass M = ball_mass + 4 plate_mass without a plate
/// (the paper's section 2.1 says 2 plate_mass; docs/paper_notes.md, "The upper plate's effective mass").
struct PhysicalParameters {
  double inertia_1 = 0.0;   ///< I1 = I2, principal moment about an equatorial axis (> 0)
  double inertia_3 = 0.0;   ///< I3, moment about the symmetry axis (> 0, I3 <= 2 I1)
  double ball_mass = 0.0;   ///< M_ball (> 0, 2 I1 + I3 <= 2 M_ball r^2: the mass lies within the radius)
  double radius = 0.0;      ///< r (> 0)
  double plate_mass = 0.0;  ///< M_plate of the upper plate (>= 0)

  /// Empty when valid; otherwise names the first offending field, its value and the bound.
  std::string Validate() const;
  /// M = M_ball + 4 M_plate: the mass of a plate-less ball with the same kinetic energy.
  double EffectiveMass() const { return ball_mass + 4.0 * plate_mass; }
};

/// The dimensionless model: alpha = I3/I1, beta = M r^2/I1, lambda = (alpha+beta)/(1+beta).
/// Only lambda enters the equations of motion (4)-(11).
///
/// A rigid ball (I3 <= 2 I1 and 2 I1 + I3 <= 2 M_ball r^2) has alpha <= 2 and beta >= 1 + alpha/2, hence
/// lambda in (1/2, 4/3]; the plate's mass raises beta and pulls lambda toward 1. Other values (the
/// paper's examples use lambda = 2) are accepted as mathematics and flagged by IsRealisable().
class BallModel {
 public:
  /// The lambda of rigid balls: (1/2, 4/3]. 1/2 is the limit of two point masses on the axis at the
  /// poles, 4/3 a thin ring in the equatorial plane without a plate.
  static constexpr double kMinRealisableLambda = 0.5;
  static constexpr double kMaxRealisableLambda = 4.0 / 3.0;

  /// Throws std::invalid_argument naming the field when a parameter is invalid.
  static BallModel FromPhysical(const PhysicalParameters& p);
  /// lambda in [1e-3, 1e3] (README, "Limits"); alpha and beta are then unknown (reported as 0 by has_inertia()).
  static BallModel FromLambda(double lambda);
  /// 0 < alpha <= 2 (a rigid body has I3 <= 2 I1), beta >= 0.
  static BallModel FromAlphaBeta(double alpha, double beta);

  /// lambda = J/(M r^2) of the ball (section 2.1); 0 for the inertia-free limit.
  double lambda() const { return lambda_; }
  /// False for the inertia-free limit (lambda = 0), true otherwise.
  bool has_inertia() const { return has_inertia_; }
  /// alpha of the equations of motion (section 2.1), from lambda and the plate mass.
  double alpha() const { return alpha_; }
  /// beta of the equations of motion (section 2.1), from lambda and the plate mass.
  double beta() const { return beta_; }
  /// True when some rigid ball with a plate of mass >= 0 has this model: alpha <= 2 and
  /// beta >= 1 + alpha/2 when alpha, beta are known, else lambda in (1/2, 4/3].
  bool IsRealisable() const;

  /// mu = 2E/(I1 + M r^2) for a kinetic energy E in physical units, M = EffectiveMass().
  static double EnergyToMu(const PhysicalParameters& p, double kinetic_energy);

 private:
  BallModel(double lambda, double alpha, double beta, bool has_inertia)
      : lambda_(lambda), alpha_(alpha), beta_(beta), has_inertia_(has_inertia) {}
  double lambda_;
  double alpha_;
  double beta_;
  bool has_inertia_;
};

}  // namespace PLATEBALL_EXPORT
