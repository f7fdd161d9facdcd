// The "integration", "ball" and "initial" sections: the model (one of three forms) and the start state.
#include <cmath>
#include <limits>
#include <stdexcept>

#include "check.h"
#include "kinematics.h"
#include "problem_io/field_archive.h"
#include "problem_io/section_readers.h"

namespace plateball::internal::problem_io {

void StartStateReader::Integration(const json& j, const std::string& path, IntegrationOptions* o) const {
  ReadSection(*this, j, path, o);
}

void StartStateReader::Ball(const json& j, const std::string& path, Problem* p) const {
  Object(j, path, {"lambda", "alpha", "beta", "physical"});
  const bool has_lambda = Find(j, "lambda"), has_alpha = Find(j, "alpha"), has_beta = Find(j, "beta"),
             has_physical = Find(j, "physical");
  const int forms = int(has_lambda) + int(has_alpha || has_beta) + int(has_physical);
  if (forms != 1) Fail(path, j, "must give exactly one of {lambda}, {alpha, beta} or {physical}");
  if (has_lambda) {
    Positive(j["lambda"], Join(path, "lambda"));
    p->model = BallModel::FromLambda(
        InClosedRange(j["lambda"], Join(path, "lambda"), internal::kMinLambda, internal::kMaxLambda));
    p->physical.reset();
    return;
  }
  if (has_alpha || has_beta) {
    const double alpha = Positive(Require(j, path, "alpha"), Join(path, "alpha"));
    const double beta = NonNegative(Require(j, path, "beta"), Join(path, "beta"));
    RequireLambdaOf(alpha, beta, Join(path, "alpha"), j["alpha"]);
    p->model = BallModel::FromAlphaBeta(alpha, beta);
    p->physical.reset();
    return;
  }
  PhysicalBall(j["physical"], Join(path, "physical"), p);
}

// A ball given by its physical parameters: a rigid body (I3 <= 2 I1) whose mass lies within its
// radius (2 I1 + I3 <= 2 M r^2).
void StartStateReader::PhysicalBall(const json& ph, const std::string& pp, Problem* p) const {
  Object(ph, pp, {"inertia_1", "inertia_3", "ball_mass", "radius", "plate_mass"});
  PhysicalParameters par;
  par.inertia_1 = Positive(Require(ph, pp, "inertia_1"), Join(pp, "inertia_1"));
  par.inertia_3 = Positive(Require(ph, pp, "inertia_3"), Join(pp, "inertia_3"));
  if (par.inertia_3 > 2.0 * par.inertia_1 * (1.0 + 1e-12))
    Fail(Join(pp, "inertia_3"),
         ph["inertia_3"],
         "a rigid body has I3 <= I1 + I2 = 2 inertia_1 = " + NumberText(2.0 * par.inertia_1));
  par.ball_mass = NonNegative(Require(ph, pp, "ball_mass"), Join(pp, "ball_mass"));
  par.radius = Positive(Require(ph, pp, "radius"), Join(pp, "radius"));
  par.plate_mass = NonNegative(Require(ph, pp, "plate_mass"), Join(pp, "plate_mass"));
  const double moment_sum = 2.0 * par.inertia_1 + par.inertia_3;
  if (!(moment_sum <= 2.0 * par.ball_mass * par.radius * par.radius * (1.0 + 1e-12)))
    Fail(Join(pp, "ball_mass"),
         ph["ball_mass"],
         "a rigid ball holds its mass within its radius, 2 I1 + I3 <= 2 ball_mass radius^2 (2 I1 + I3 = " +
             NumberText(moment_sum) + ")");
  RequireLambdaOf(par.inertia_3 / par.inertia_1, par.EffectiveMass() * par.radius * par.radius / par.inertia_1, pp, ph);
  try {
    p->model = BallModel::FromPhysical(par);
  } catch (const std::invalid_argument& e) {
    Fail(pp, ph, e.what());  // e.g. beta = M r^2 / I1 overflows
  }
  p->physical = par;
}

void StartStateReader::RequireLambdaOf(double alpha, double beta, const std::string& path, const json& v) const {
  const double lambda = (alpha + beta) / (1.0 + beta);
  if (!(lambda >= internal::kMinLambda && lambda <= internal::kMaxLambda))
    Fail(path,
         v,
         "gives lambda = " + NumberText(lambda) + ", outside [" + NumberText(internal::kMinLambda) + ", " +
             NumberText(internal::kMaxLambda) + "]");
}

// An angle of the start: finite, and within kMaxAngleMagnitude (beyond it no digit is left modulo
// 2 pi), named by its field here rather than by the solver's internal name later.
double StartStateReader::Angle(const json& j, const std::string& path, const char* key) const {
  const double a = Number(Require(j, path, key), Join(path, key));
  if (std::abs(a) > internal::kMaxAngleMagnitude)
    Fail(Join(path, key), j[key], "an angle beyond 1e15 in magnitude has no significant digits left modulo 2 pi");
  return a;
}

void StartStateReader::Initial(const json& j, const std::string& path, Problem* p) const {
  Object(j, path, {"theta", "phi", "psi", "mu", "x0", "orientation"});
  p->initial.theta = Angle(j, path, "theta");
  p->initial.phi = Angle(j, path, "phi");
  p->initial.psi = Angle(j, path, "psi");
  p->mu = Positive(Require(j, path, "mu"), Join(path, "mu"));
  InClosedRange(j["mu"], Join(path, "mu"), internal::kMinMu, internal::kMaxMu);
  p->x0 = Eigen::Vector2d::Zero();
  if (const json* v = Find(j, "x0")) p->x0 = Point(*v, Join(path, "x0"));
  p->A0 = Eigen::Matrix3d::Identity();
  if (const json* v = Find(j, "orientation")) p->A0 = Orientation(*v, Join(path, "orientation"));
}

}  // namespace plateball::internal::problem_io
