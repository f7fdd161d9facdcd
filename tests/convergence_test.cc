#include "plateball/convergence.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace plateball;

namespace {
// Corollary 3: error ~ n^-2; the fitted slope must lie in [-2.2, -1.8] (issue 3).
constexpr double kSlopeLow = -2.2;
constexpr double kSlopeHigh = -1.8;
constexpr double kPassTolerance = 1e-10;

Problem PlanProblem(const PathSpec& path) {
  Problem p;
  p.model = BallModel::FromLambda(2.0);
  p.initial_angles = {M_PI / 3, 0.4, 0.1};
  p.mu = 1.0;
  p.plan = PlanTask{};
  p.plan->path = path;
  p.plan->partition.type = "uniform_parameter";
  p.x0 = Path::FromSpec(path).StartPoint();
  return p;
}

PathSpec Closed(const std::string& type) {
  PathSpec s;
  s.type = type;
  s.tau_begin = 0;
  s.tau_end = 2 * M_PI;
  if (type == "circle") s.center = {-2, 0}, s.radius = 2;
  if (type == "ellipse") s.semi_axes = {2, 1}, s.rotation = 0.3;
  if (type == "lemniscate") s.scale = 2;
  return s;
}

void ExpectConverges(const Problem& p, bool check_slope) {
  const ConvergenceStudy study = RunConvergenceStudy(p, {16, 32, 64, 128, 256});
  EXPECT_EQ(study.failed_rows, 0);
  EXPECT_TRUE(study.bound_holds) << study.BriefReport();
  for (const auto& r : study.rows) {
    EXPECT_LE(r.measured_error, r.bound) << "n = " << r.n;
    EXPECT_LE(r.max_pass_miss, kPassTolerance) << "n = " << r.n;
  }
  if (check_slope) {
    EXPECT_GE(study.error_slope, kSlopeLow) << study.BriefReport();
    EXPECT_LE(study.error_slope, kSlopeHigh) << study.BriefReport();
  }
}
}  // namespace

TEST(Convergence, LogLogSlopeOfAPowerLawIsItsExponent) {
  EXPECT_NEAR(LogLogSlope({1, 2, 4, 8}, {3, 0.75, 0.1875, 0.046875}), -2.0, 1e-14);
  EXPECT_TRUE(std::isnan(LogLogSlope({1}, {1})));
}

TEST(Convergence, CircleErrorFallsAsInverseSquareOfImpulseCount) { ExpectConverges(PlanProblem(Closed("circle")), true); }
TEST(Convergence, EllipseErrorFallsAsInverseSquareOfImpulseCount) { ExpectConverges(PlanProblem(Closed("ellipse")), true); }
TEST(Convergence, LemniscateErrorFallsAsInverseSquareOfImpulseCount) {
  ExpectConverges(PlanProblem(Closed("lemniscate")), true);
}

TEST(Convergence, PiecewisePathBoundHoldsForEveryN) {
  PathSpec a, arc, b;
  a.type = "line";
  a.from = {0, 0};
  a.to = {2, 0};
  arc.type = "circle";
  arc.center = {2, 1};
  arc.radius = 1;
  arc.tau_begin = -M_PI / 2;
  arc.tau_end = M_PI / 2;
  b.type = "sine";
  b.from = {2, 2};
  b.rotation = M_PI;
  b.length = 3;
  b.amplitude = 0.3;
  b.wavelength = 1.5;
  PathSpec pw;
  pw.type = "piecewise";
  pw.pieces = {a, arc, b};
  ExpectConverges(PlanProblem(pw), true);
}

TEST(Convergence, ArcLengthPartitionAlsoConverges) {
  Problem p = PlanProblem(Closed("ellipse"));
  p.plan->partition.type = "uniform_arc_length";
  ExpectConverges(p, true);
}
