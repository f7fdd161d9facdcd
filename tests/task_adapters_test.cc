// The task adapters (task_adapters.h): the one mapping from a problem file to each solver's
// problem and options. Paths and partitions of the file become library values with the field
// names of the file in every message, and the file's sections (integration, seed, solver) reach
// the options of the solver they configure.
#include "plateball/task_adapters.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <variant>

#include "plateball/problem_io.h"
#include "support/test_support.h"

using namespace plateball;

namespace {

std::string ErrorOf(const std::function<void()>& f) { return plateball::testing::InvalidArgumentMessage(f, ""); }

Problem Read(const std::string& file) { return ReadProblemFile(plateball::testing::SourcePath("problems/" + file)); }

}  // namespace

TEST(TaskAdapters, PathFromSpecBuildsEveryTypeAndPiecewiseChains) {
  const PathSpec pw{
      PiecewiseSpec{{PathSpec{LineSpec{{0, 0}, {2, 0}}}, PathSpec{CircleSpec{{2, 1}, 1, -M_PI / 2, M_PI / 2}}}}};
  EXPECT_EQ(ToString(pw), "piecewise");
  const Path p = PathFromSpec(pw);
  EXPECT_EQ(p.PieceCount(), 2);
  EXPECT_NEAR(p.Length(), 2.0 + M_PI, 1e-12);  // 2 + a half circle of radius 1
  EXPECT_LT((p.EndPoint() - Eigen::Vector2d(2, 2)).norm(), 1e-15);
  EXPECT_EQ(PathFromSpec(PathSpec{EllipseSpec{}}).pieces()[0].kind(), CurveKind::kEllipse);
  EXPECT_EQ(PathFromSpec(PathSpec{LemniscateSpec{}}).pieces()[0].kind(), CurveKind::kLemniscate);
  EXPECT_NEAR(PathFromSpec(PathSpec{SineSpec{{0, 0}, 0.0, 3.0, 0.0, 1.0}}).Length(), 3.0, 1e-12);  // amplitude 0
  EXPECT_NEAR(PathFromSpec(PathSpec{SamplesSpec{{{0, 0}, {3, 4}}}}).Length(), 5.0, 1e-12);
}

TEST(TaskAdapters, BadSpecsNameTheField) {
  EXPECT_NE(ErrorOf([] {
              PathFromSpec(PathSpec{CircleSpec{{0, 0}, 0.0, 0.0, 1.0}}, "plan.path");
            }).find("plan.path.radius"),
            std::string::npos);
  EXPECT_NE(ErrorOf([] {
              PathFromSpec(PathSpec{CircleSpec{{0, 0}, 1.0, 0.0, 0.0}}, "plan.path");
            }).find("plan.path.tau_end"),
            std::string::npos);
  EXPECT_NE(ErrorOf([] { PathFromSpec(PathSpec{LineSpec{{1, 1}, {1, 1}}}); }).find("zero speed"), std::string::npos);
  EXPECT_NE(ErrorOf([] { PathFromSpec(PathSpec{LineSpec{{1, 1}, {NAN, 0}}}); }).find("path.to"), std::string::npos);
  EXPECT_NE(ErrorOf([] {
              PathFromSpec(PathSpec{SamplesSpec{{{0, 0}, {1, 1}, {1, 1}, {2, 0}}}});
            }).find("points[2]"),
            std::string::npos);
  EXPECT_NE(ErrorOf([] {
              PathFromSpec(PathSpec{SamplesSpec{{{0, 0}, {INFINITY, 1}}}});
            }).find("must be finite"),
            std::string::npos);
  EXPECT_NE(ErrorOf([] {
              PathFromSpec(PathSpec{SineSpec{{0, 0}, 0.0, 1.0, 0.5, 0.0}});
            }).find("path.wavelength"),
            std::string::npos);
  // A gap between pieces; no pieces; nested pieces.
  const PathSpec a{LineSpec{{0, 0}, {1, 0}}};
  EXPECT_NE(ErrorOf([&] {
              PathFromSpec(PathSpec{PiecewiseSpec{{a, PathSpec{LineSpec{{1, 0.5}, {2, 0}}}}}});
            }).find("pieces[1]"),
            std::string::npos);
  EXPECT_NE(ErrorOf([] { PathFromSpec(PathSpec{PiecewiseSpec{}}); }).find("pieces"), std::string::npos);
  EXPECT_NE(
      ErrorOf([&] { PathFromSpec(PathSpec{PiecewiseSpec{{PathSpec{PiecewiseSpec{{a}}}}}}); }).find("may not nest"),
      std::string::npos);
}

TEST(TaskAdapters, PlanSetupIsTheFilesPlanWithItsIntegrationSection) {
  Problem p = Read("circle.json");
  const PlanSetup s = PlanSetupFor(p);
  EXPECT_EQ(s.problem.path.PieceCount(), 1);
  EXPECT_NEAR(s.problem.path.Length(), 4 * M_PI, 1e-12);  // circle of radius 2
  ASSERT_EQ(s.problem.partition.size(), 1u);
  EXPECT_EQ(ToString(s.problem.partition[0]), ToString(p.plan->partition));
  EXPECT_EQ(s.options.integration.max_steps, p.integration.max_steps);
  EXPECT_EQ(s.options.join.integration.absolute_tolerance, p.integration.absolute_tolerance);
  // --n replaces a uniform n.
  const PlanSetup n8 = PlanSetupFor(p, 8);
  const auto* uniform = std::get_if<UniformParameter>(&n8.problem.partition[0]);
  ASSERT_NE(uniform, nullptr);
  EXPECT_EQ(uniform->n, 8);
  p.x0 = {5, 5};
  EXPECT_NE(ErrorOf([&] { PlanSetupFor(p); }).find("initial.x0: value"), std::string::npos);
}

TEST(TaskAdapters, SolverSectionsReachTheirOptions) {
  Problem p = Read("figure7.json");
  p.seed = 42;
  p.integration.max_steps = 777;
  const IsoparallelSetup iso = IsoparallelSetupFor(p);
  EXPECT_EQ(iso.problem.goal, p.isoparallel->goal);
  EXPECT_EQ(iso.options.starts, p.isoparallel->solver.starts);
  EXPECT_EQ(iso.options.seed, 42u);
  EXPECT_EQ(iso.options.integration.max_steps, 777);
  EXPECT_EQ(IsoparallelPlanSetupFor(p, IsoparallelSolution{}).problem.impulses, p.isoparallel->impulses);
  EXPECT_EQ(IsoparallelPlanSetupFor(p, IsoparallelSolution{}, 5).problem.impulses, 5);
  EXPECT_EQ(IsoparallelPlanSetupFor(p, IsoparallelSolution{}).options.integration.max_steps, 777);
  const ReachSetup reach = ReachSetupFor(Read("figure8_reach.json"), {6, 0});
  EXPECT_EQ(reach.options.horizon_periods, Read("figure8_reach.json").reach->horizon_periods);
  EXPECT_EQ(reach.problem.target, Eigen::Vector2d(6, 0));
  EXPECT_EQ(JoinSetupFor(p, {1, 0}).options.integration.max_steps, 777);
  Problem none = p;
  none.isoparallel.reset();
  EXPECT_NE(ErrorOf([&] { IsoparallelSetupFor(none); }).find("figure7.json: isoparallel: value (missing)"),
            std::string::npos);
}
