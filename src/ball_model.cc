#include "plateball/ball_model.h"

#include <cmath>
#include <stdexcept>

#include "check.h"

namespace plateball {
namespace {
// Relative slack of the rigid-body inequalities: a uniform ring or two pole masses given in decimal
// sit on the bound up to rounding.
constexpr double kRigidTolerance = 1e-12;

// lambda in [1e-3, 1e3] (README, "Limits"): beyond, the rolling ODE is so stiff that the
// energy drifts at tolerance 1e-12 (lambda 1e12) or the step size underflows (lambda 1e-300).
void RequireLambda(double lambda) {
  internal::RequirePositive("lambda", lambda);
  internal::RequireInRange("lambda", lambda, internal::kMinLambda, internal::kMaxLambda);
}
}  // namespace

std::string PhysicalParameters::Validate() const {
  auto bad = [](const char* field, double v, const std::string& bound) {
    return internal::InvalidValueMessage(std::string("physical.") + field, v, bound);
  };
  if (!(std::isfinite(inertia_1) && inertia_1 > 0)) return bad("inertia_1", inertia_1, "must be finite and > 0");
  if (!(std::isfinite(inertia_3) && inertia_3 > 0)) return bad("inertia_3", inertia_3, "must be finite and > 0");
  if (inertia_3 > 2.0 * inertia_1 * (1.0 + kRigidTolerance))
    return bad("inertia_3", inertia_3, "a rigid body has I3 <= I1 + I2 = 2 I1");
  if (!(std::isfinite(ball_mass) && ball_mass >= 0)) return bad("ball_mass", ball_mass, "must be finite and >= 0");
  if (!(std::isfinite(radius) && radius > 0)) return bad("radius", radius, "must be finite and > 0");
  if (!(std::isfinite(plate_mass) && plate_mass >= 0)) return bad("plate_mass", plate_mass, "must be finite and >= 0");
  // Sum of the principal moments = 2 * integral of rho |x|^2 <= 2 M_ball r^2 for a body within radius r.
  const double moment_sum = 2.0 * inertia_1 + inertia_3, moment_bound = 2.0 * ball_mass * radius * radius;
  if (!(moment_sum <= moment_bound * (1.0 + kRigidTolerance)))
    return bad("ball_mass",
               ball_mass,
               "a rigid ball holds its mass within its radius, 2 I1 + I3 <= 2 M_ball r^2 (2 I1 + I3 = " +
                   internal::FormatNumber(moment_sum) + ", 2 M_ball r^2 = " + internal::FormatNumber(moment_bound) +
                   ")");
  return {};
}

BallModel BallModel::FromPhysical(const PhysicalParameters& p) {
  internal::ThrowIfInvalid(p.Validate());
  const double alpha = p.inertia_3 / p.inertia_1;
  const double beta = p.EffectiveMass() * p.radius * p.radius / p.inertia_1;
  return FromAlphaBeta(alpha, beta);
}

BallModel BallModel::FromLambda(double lambda) {
  RequireLambda(lambda);
  return BallModel(lambda, 0.0, 0.0, false);
}

BallModel BallModel::FromAlphaBeta(double alpha, double beta) {
  internal::RequirePositive("alpha", alpha);
  // A rigid body has I3 <= I1 + I2 = 2 I1 (docs/paper_notes.md, "Physical range of lambda").
  if (alpha > 2.0 * (1.0 + kRigidTolerance))
    internal::ThrowInvalid("alpha", alpha, "a rigid body has alpha = I3/I1 <= 2");
  internal::RequireNonNegative("beta", beta);
  const double lambda = (alpha + beta) / (1.0 + beta);
  RequireLambda(lambda);
  return BallModel(lambda, alpha, beta, true);
}

bool BallModel::IsRealisable() const {
  if (has_inertia_)
    return alpha_ <= 2.0 * (1.0 + kRigidTolerance) && beta_ >= (1.0 + 0.5 * alpha_) * (1.0 - kRigidTolerance);
  return lambda_ > kMinRealisableLambda && lambda_ <= kMaxRealisableLambda * (1.0 + kRigidTolerance);
}

double BallModel::EnergyToMu(const PhysicalParameters& p, double kinetic_energy) {
  internal::ThrowIfInvalid(p.Validate());
  internal::RequireNonNegative("kinetic_energy", kinetic_energy);
  return 2.0 * kinetic_energy / (p.inertia_1 + p.EffectiveMass() * p.radius * p.radius);
}

}  // namespace plateball
