// The first plan in C++ (docs/getting_started/first_plan.md): read a problem file, follow its path
// with impulses exactly as `plateball plan PROBLEM.json` does, and print the error and its bound.
//   first_plan problems/circle.json
#include <cstdio>
#include <exception>

#include "plateball/impulse_planner.h"
#include "plateball/problem_io.h"
#include "plateball/task_adapters.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: first_plan PROBLEM.json\n");
    return 2;
  }
  try {
    const plateball::Problem problem = plateball::ReadProblemFile(argv[1]);
    const plateball::PlanSetup setup = plateball::PlanSetupFor(problem);  // what `plateball plan` solves
    const plateball::PlanSummary plan = plateball::PlanImpulses(setup.problem, setup.options);
    if (!plan.IsSolutionUsable()) {
      std::fprintf(stderr, "%s\n", plan.BriefReport().c_str());
      return 4;
    }
    std::printf("status %s, %d impulses, measured error %.6g <= bound %.6g\n",
                plateball::ToString(plan.status).c_str(),
                plan.segments,
                plan.measured_error,
                plan.bounds.a_posteriori);
    return 0;
  } catch (const std::exception& e) {  // an unreadable or invalid problem file names the field
    std::fprintf(stderr, "first_plan: %s\n", e.what());
    return 3;
  }
}
