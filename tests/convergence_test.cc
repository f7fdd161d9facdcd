#include "plateball/convergence.h"

#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <stdexcept>
#include <string>

#include "plateball/task_adapters.h"

using namespace plateball;

namespace {
// Corollary 3: error ~ n^-2; the fitted slope must lie in [-2.2, -1.8].
constexpr double kSlopeLow = -2.2;
constexpr double kSlopeHigh = -1.8;
constexpr double kPassTolerance = 1e-10;

Problem FileProblem(const PathSpec& path) {
  Problem p;
  p.model = BallModel::FromLambda(2.0);
  p.initial = {M_PI / 3, 0.4, 0.1};
  p.mu = 1.0;
  p.plan = PlanTask{};
  p.plan->path = path;
  p.plan->partition = UniformParameter{};
  p.x0 = PathFromSpec(path).StartPoint();
  return p;
}

PathSpec Closed(const std::string& type) {
  if (type == "circle") return {CircleSpec{{-2, 0}, 2, 0, 2 * M_PI}};
  if (type == "ellipse") return {EllipseSpec{{0, 0}, {2, 1}, 0.3, 0, 2 * M_PI}};
  return {LemniscateSpec{{0, 0}, 2, 0.0, 0, 2 * M_PI}};
}

void ExpectConverges(const Problem& p, bool check_slope) {
  const ConvergenceSetup setup = ConvergenceSetupFor(p, {16, 32, 64, 128, 256});
  const ConvergenceStudy study = RunConvergenceStudy(setup.problem, setup.options);
  EXPECT_EQ(study.failed_rows, 0);
  EXPECT_TRUE(study.bound_holds) << study.BriefReport();
  for (const auto& r : study.rows) {
    EXPECT_LE(r.measured_error, r.bound) << "n = " << r.n;
    EXPECT_LE(r.max_pass_miss, kPassTolerance) << "n = " << r.n;
  }
  if (check_slope) {
    ASSERT_TRUE(study.error_slope.has_value()) << study.BriefReport();
    EXPECT_GE(*study.error_slope, kSlopeLow) << study.BriefReport();
    EXPECT_LE(*study.error_slope, kSlopeHigh) << study.BriefReport();
  }
}
}  // namespace

TEST(Convergence, LogLogSlopeOfAPowerLawIsItsExponent) {
  EXPECT_NEAR(*LogLogSlope({1, 2, 4, 8}, {3, 0.75, 0.1875, 0.046875}), -2.0, 1e-14);
  EXPECT_FALSE(LogLogSlope({1}, {1}).has_value());
  EXPECT_FALSE(LogLogSlope({4, 4}, {1, 2}).has_value());  // one distinct x: no line
}

TEST(Convergence, CircleErrorFallsAsInverseSquareOfImpulseCount) {
  ExpectConverges(FileProblem(Closed("circle")), true);
}
TEST(Convergence, EllipseErrorFallsAsInverseSquareOfImpulseCount) {
  ExpectConverges(FileProblem(Closed("ellipse")), true);
}
TEST(Convergence, LemniscateErrorFallsAsInverseSquareOfImpulseCount) {
  ExpectConverges(FileProblem(Closed("lemniscate")), true);
}

TEST(Convergence, PiecewisePathBoundHoldsForEveryN) {
  const PathSpec a{LineSpec{{0, 0}, {2, 0}}};
  const PathSpec arc{CircleSpec{{2, 1}, 1, -M_PI / 2, M_PI / 2}};
  const PathSpec b{SineSpec{{2, 2}, M_PI, 3, 0.3, 1.5}};
  const PathSpec pw{PiecewiseSpec{{a, arc, b}}};
  ExpectConverges(FileProblem(pw), true);
}

TEST(Convergence, ArcLengthPartitionAlsoConverges) {
  Problem p = FileProblem(Closed("ellipse"));
  p.plan->partition = UniformArcLength{};
  ExpectConverges(p, true);
}

namespace {
std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  return "";
}
}  // namespace

// `converge --n 16,16,16` fitted a bound slope of -0.125 from one point.
TEST(Convergence, RepeatedPartitionSizeIsAnInputErrorNamingTheField) {
  const Problem p = FileProblem(Closed("circle"));
  const std::string e = ErrorOf([&] { ConvergenceSetupFor(p, {16, 16, 16}, "--n"); });
  EXPECT_NE(e.find("--n[1]"), std::string::npos) << e;
  EXPECT_NE(e.find("repeated"), std::string::npos) << e;
  ConvergenceProblem q;
  q.ns = {32, 16, 32};
  EXPECT_NE(ErrorOf([&] { RunConvergenceStudy(q); }).find("ns[2]"), std::string::npos);
  q.ns = {};
  EXPECT_NE(ErrorOf([&] { RunConvergenceStudy(q); }).find("ns"), std::string::npos);
}

// `converge --n 16` printed "slope nan".
TEST(Convergence, OnePartitionSizeGivesNoSlopeAndSaysSo) {
  const ConvergenceSetup setup = ConvergenceSetupFor(FileProblem(Closed("circle")), {16});
  const ConvergenceStudy s = RunConvergenceStudy(setup.problem, setup.options);
  ASSERT_EQ(s.rows.size(), 1u);
  EXPECT_EQ(s.rows[0].status, PlanStatus::kSuccess);
  EXPECT_FALSE(s.error_slope.has_value());
  EXPECT_FALSE(s.bound_slope.has_value());
  const std::string report = s.BriefReport();
  EXPECT_EQ(report.find("nan"), std::string::npos) << report;
  EXPECT_NE(report.find("no slope"), std::string::npos) << report;
}

// With an explicit partition `--n` was silently ignored (every row the same).
TEST(Convergence, ExplicitPartitionRejectsPartitionSizes) {
  Problem p = FileProblem(Closed("circle"));
  p.plan->partition = ExplicitTaus{{0.0, M_PI, 2 * M_PI}};
  const std::string with_n = ErrorOf([&] { ConvergenceSetupFor(p, {16, 32}, "--n"); });
  EXPECT_NE(with_n.find("--n"), std::string::npos) << with_n;
  EXPECT_NE(with_n.find("explicit"), std::string::npos) << with_n;
  EXPECT_NE(ErrorOf([&] { ConvergenceSetupFor(p); }).find("plan.partition"), std::string::npos);
  EXPECT_NE(ErrorOf([&] { PlanSetupFor(p, 16, "--n"); }).find("--n"), std::string::npos);
}

// Without timings a study is a deterministic function of its problem (converge --out files).
TEST(Convergence, StudyWithoutTimingsIsReproducible) {
  const ConvergenceSetup setup = ConvergenceSetupFor(FileProblem(Closed("ellipse")), {8, 16});
  const ConvergenceStudy a = RunConvergenceStudy(setup.problem, setup.options);
  const ConvergenceStudy b = RunConvergenceStudy(setup.problem, setup.options);
  EXPECT_EQ(a.BriefReport(), b.BriefReport());
  EXPECT_FALSE(a.time_slope.has_value());
  for (std::size_t i = 0; i < a.rows.size(); ++i) {
    EXPECT_EQ(a.rows[i].plan_seconds, 0.0);
    EXPECT_EQ(a.rows[i].measured_error, b.rows[i].measured_error);
  }
}
