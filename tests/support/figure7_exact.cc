#include "support/figure7_exact.h"

#include <stdexcept>

#include "plateball/isoparallel_plan.h"
#include "plateball/problem_io.h"
#include "plateball/task_adapters.h"
#include "support/test_support.h"

namespace plateball::testing {

namespace {
const Problem& Figure7File() {
  static const Problem file = ReadProblemFile(SourcePath("problems/figure7.json"));
  return file;
}
}  // namespace

const IsoparallelSummary& Figure7Isoparallel() {
  static const IsoparallelSummary solved = [] {
    const IsoparallelSetup iso = IsoparallelSetupFor(Figure7File());
    IsoparallelSummary s = SolveIsoparallel(iso.problem, iso.options);
    if (!s.IsSolutionUsable()) throw std::runtime_error(s.BriefReport());
    return s;
  }();
  return solved;
}

const ExactArrivalProblem& Figure7ExactArrival() {
  static const ExactArrivalProblem problem = [] {
    const IsoparallelSetup iso = IsoparallelSetupFor(Figure7File());
    const IsoparallelSummary& solved = Figure7Isoparallel();
    const IsoparallelPlanSetup plan = IsoparallelPlanSetupFor(Figure7File(), solved.Shortest());
    ExactArrivalProblem p;
    p.model = plan.problem.model;
    p.initial = InitialAnglesFromOrientation(plan.problem.A0, plan.problem.psi);
    p.mu = plan.problem.mu;
    p.A0 = plan.problem.A0;
    p.x0 = iso.problem.start;
    p.reference = OptimalPath(solved.Shortest());
    p.impulses = plan.problem.impulses;
    p.x1 = iso.problem.goal;
    p.A1 = iso.problem.goal_orientation;
    return p;
  }();
  return problem;
}

}  // namespace plateball::testing
