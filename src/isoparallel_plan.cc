#include "plateball/isoparallel_plan.h"

#include <cmath>
#include <memory>
#include <stdexcept>

#include "check.h"
#include "plateball/partition.h"
#include "plateball/so3.h"

namespace plateball {

Path OptimalPath(const IsoparallelSolution& solution) {
  internal::RequirePositive("length", solution.length);
  const auto e = std::make_shared<const Elastica>(solution.parameters);
  const Eigen::Vector2d start = solution.start;
  auto value = [e, start](double s) -> Eigen::Vector2d { return start + e->Position(s); };
  auto derivative = [e](double s) -> Eigen::Vector2d { return e->Tangent(s); };
  auto second = [e](double s) -> Eigen::Vector2d {
    const Eigen::Vector2d t = e->Tangent(s);
    return e->Curvature(s) * Eigen::Vector2d(-t.y(), t.x());
  };
  return Path({SmoothCurve::Custom(value, derivative, second, 0.0, solution.length)});
}

AngleState InitialAnglesFromOrientation(const Eigen::Matrix3d& A0, double psi) {
  internal::RequireFinite("psi", psi);
  if (!IsRotation(A0, 1e-9)) internal::ThrowInvalid("start_orientation", "(matrix)", "not a rotation matrix (to 1e-9)");
  const Eigen::Vector3d z = A0.col(2);
  AngleState a;
  a.theta = std::acos(std::clamp(z.z(), -1.0, 1.0));
  a.phi = std::hypot(z.x(), z.y()) > 0 ? std::atan2(z.y(), z.x()) : 0.0;
  a.psi = psi;
  return a;
}

PlanSummary PlanOptimalPath(const IsoparallelPlanProblem& problem, const PlanOptions& options) {
  internal::RequireCount("impulses", problem.impulses, internal::kMaxPartitionSteps);
  internal::RequireEnergy("mu", problem.mu);
  PlanProblem plan;
  plan.model = problem.model;
  plan.initial = InitialAnglesFromOrientation(problem.A0, problem.psi);
  plan.mu = problem.mu;
  plan.A0 = problem.A0;
  plan.path = OptimalPath(problem.solution);
  plan.partition = {UniformParameter{problem.impulses}};  // tau is arc length already
  return PlanImpulses(plan, options);
}

}  // namespace plateball
