// Golden test of the plan problems in problems/ (as the NIST files in Ceres): each file carries
// its expected values, which come from closed forms (lengths by elliptic integrals, the circle's
// rolling reorientation) or from the paper (Corollary 3: slope -2), never from this code.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

#include "plateball/convergence.h"
#include "plateball/impulse_planner.h"
#include "plateball/path.h"
#include "plateball/problem_io.h"
#include "plateball/so3.h"
#include "plateball/task_adapters.h"
#include "support/test_support.h"

using namespace plateball;

namespace {

void CheckProblem(const std::string& file) {
  const Problem p = ReadProblemFile(plateball::testing::SourcePath("problems/" + file));
  ASSERT_TRUE(p.plan.has_value()) << file;
  ASSERT_FALSE(p.expected.empty()) << file;
  const PlanSetup setup = PlanSetupFor(p);  // what `plateball plan` runs
  const PlanSummary plan = PlanImpulses(setup.problem, setup.options);
  ASSERT_TRUE(plan.IsSolutionUsable()) << file << ": " << plan.BriefReport();
  EXPECT_LE(plan.measured_error, plan.bounds.a_posteriori) << file;
  int checked = 0;
  std::optional<ConvergenceStudy> study;
  for (const auto& [name, e] : p.expected) {
    double value = NAN;
    if (name == "path_length") {
      value = PathFromSpec(p.plan->path).Length();
    } else if (name == "planned_rotation_angle") {
      value = RotationAngle(plan.A_planned, plan.A0);
    } else if (name == "max_pass_miss") {
      value = plan.max_pass_miss;
    } else if (name == "error_slope" || name == "bound_holds") {
      if (!study) {
        const ConvergenceSetup c = ConvergenceSetupFor(p);  // what `plateball converge` runs
        study = RunConvergenceStudy(c.problem, c.options);
      }
      value = name == "error_slope" ? study->error_slope.value_or(NAN) : (study->bound_holds ? 1.0 : 0.0);
    } else {
      ADD_FAILURE() << file << ": unknown expected value '" << name << "'";
      continue;
    }
    EXPECT_NEAR(value, e.value, e.tolerance) << file << ": " << name;
    ++checked;
  }
  EXPECT_EQ(checked, static_cast<int>(p.expected.size()));
}

}  // namespace

TEST(PlanProblems, CircleMatchesItsGoldenValues) { CheckProblem("circle.json"); }
TEST(PlanProblems, EllipseMatchesItsGoldenValues) { CheckProblem("ellipse.json"); }
TEST(PlanProblems, LemniscateMatchesItsGoldenValues) { CheckProblem("lemniscate.json"); }
TEST(PlanProblems, PiecewiseMatchesItsGoldenValues) { CheckProblem("piecewise.json"); }
