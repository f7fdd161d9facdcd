// The documented limits (README, "Limits") and the reproductions that used to run for
// minutes, exhaust memory, lose precision silently or blame the wrong input: each must now end at
// once in a std::invalid_argument naming the field, the value and the limit.
#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "plateball/ball_model.h"
#include "plateball/ball_state.h"
#include "plateball/integration_options.h"
#include "plateball/isoparallel.h"
#include "plateball/isoparallel_families.h"
#include "plateball/isoparallel_plan.h"
#include "plateball/join.h"
#include "plateball/partition.h"
#include "plateball/path.h"
#include "plateball/problem.h"
#include "plateball/problem_io.h"
#include "plateball/reach.h"
#include "support/test_support.h"

namespace plateball {
namespace {

using testing::InvalidArgumentMessage;

// Asserts that `message` contains every part.
void ExpectNames(const std::string& message, const std::vector<std::string>& parts) {
  ASSERT_FALSE(message.empty()) << "no std::invalid_argument";
  for (const std::string& p : parts) EXPECT_NE(message.find(p), std::string::npos) << message << "\nmissing: " << p;
}

std::string ParseMessage(const std::string& text) {
  return InvalidArgumentMessage([&] { ParseProblem(text, "limits.json"); });
}

// ------------------------------------------------------------------ the problem-file reader
TEST(Limits, ManyEmptyObjectsAreRejectedInOnePass) {
  // 350,000 empty objects (1 MB): 21.8 s with the old duplicate-key check, linear now.
  std::string text = "[";
  for (int i = 0; i < 350000; ++i) text += i ? ",{}" : "{}";
  text += "]";
  ExpectNames(ParseMessage(text), {"limits.json: (document): value [array of 350000]", "must be a JSON object"});
}

TEST(Limits, ManyKeysInOneObjectStillFindTheDuplicate) {
  std::string text = "{";
  for (int i = 0; i < 100000; ++i) text += "\"k" + std::to_string(i) + "\": {}, ";
  text += "\"k7\": 1}";
  ExpectNames(ParseMessage(text), {"limits.json: k7: value (duplicate)", "more than once"});
}

TEST(Limits, NestingDeeperThan64IsRejectedNamingTheLimit) {
  // 1e5 nested brackets cost ~270 bytes of memory per byte before; now the parser stops at 64.
  ExpectNames(ParseMessage(std::string(100000, '[') + std::string(100000, ']')),
              {"limits.json: [0][0]", "nested deeper than 64 levels"});
  // 64 levels are within the limit (then rejected as not an object).
  ExpectNames(ParseMessage(std::string(64, '[') + std::string(64, ']')), {"must be a JSON object"});
}

TEST(Limits, NulByteAndGarbageAfterTheDocumentAreRejected) {
  const std::string good = R"({"ball": {"lambda": 2}, "initial": {"theta": 1, "phi": 0, "psi": 0, "mu": 1}})";
  EXPECT_NO_THROW(ParseProblem(good, "limits.json"));
  ExpectNames(ParseMessage(good + std::string(1, '\0') + "garbage"),
              {"NUL byte at offset " + std::to_string(good.size())});
}

TEST(Limits, FileLargerThan16MiBIsBadInputNotAnIoError) {
  const std::string path = std::string(PLATEBALL_BINARY_DIR) + "/limits_test_big.json";
  {
    std::ofstream out(path, std::ios::binary);
    out << "{\"description\": \"" << std::string((16u << 20) + 16, 'x') << "\"}";
  }
  try {
    ReadProblemFile(path);
    ADD_FAILURE() << "no error";
  } catch (const ProblemFileReadError& e) {
    ADD_FAILURE() << "reported as an I/O error (exit 5): " << e.what();
  } catch (const std::invalid_argument& e) {
    ExpectNames(e.what(), {path + ": (file)", "16 MiB limit of a problem file"});
  }
  std::remove(path.c_str());
}

// ------------------------------------------------------------------ documented ranges
TEST(Limits, LambdaOutsideItsRangeIsRefusedNamingIt) {
  // lambda 1e12 drifted in energy from 0.9999986 to 1.00029 by t = 10 at tolerance 1e-12; 1e-300
  // ended in "step size underflow".
  ExpectNames(InvalidArgumentMessage([] { BallModel::FromLambda(1e12); }), {"lambda: value 1e+12", "[0.001, 1000]"});
  ExpectNames(InvalidArgumentMessage([] { BallModel::FromLambda(1e-300); }), {"lambda: value 1e-300"});
  EXPECT_NO_THROW(BallModel::FromLambda(1e-3));
  EXPECT_NO_THROW(BallModel::FromLambda(1e3));
  ExpectNames(InvalidArgumentMessage([] { BallModel::FromAlphaBeta(1e-9, 0.0); }), {"lambda: value 1e-09"});
}

TEST(Limits, EnergyOutsideItsRangeIsRefusedNamingMu) {
  const BallModel m = BallModel::FromLambda(2.0);
  ExpectNames(InvalidArgumentMessage([&] {
                StateFromAngles({1, 0, 0}, 1e50, m);
              }),
              {"mu: value 1e+50", "[1e-12, 1e+12]"});
  ExpectNames(InvalidArgumentMessage([&] { StateFromAngles({1, 0, 0}, 1e-310, m); }), {"mu: value 1e-310"});
  EXPECT_NO_THROW(StateFromAngles({1, 0, 0}, 1e12, m));
  EXPECT_NO_THROW(StateFromAngles({1, 0, 0}, 1e-12, m));
}

TEST(Limits, TolerancesBelowDoublePrecisionAreRefusedNamingThem) {
  IntegrationOptions o;
  o.absolute_tolerance = 1e-300;  // was "integration step size underflow"
  EXPECT_EQ(o.Validate(), "absolute_tolerance: value 1e-300: must be in [1e-15, 1)");
  o.absolute_tolerance = 1e-15;
  EXPECT_EQ(o.Validate(), "");
  o.relative_tolerance = 1;
  EXPECT_EQ(o.Validate(), "relative_tolerance: value 1: must be in [1e-15, 1)");
}

TEST(Limits, JoinResidualToleranceHasARange) {
  JoinOptions o;
  o.residual_tolerance = 0.999;  // called every target the start
  EXPECT_EQ(o.Validate(), "residual_tolerance: value 0.999: must be in [1e-15, 1e-3]");
  o.residual_tolerance = 1e-300;
  EXPECT_EQ(o.Validate(), "residual_tolerance: value 1e-300: must be in [1e-15, 1e-3]");
  o.residual_tolerance = 1e-3;
  EXPECT_EQ(o.Validate(), "");
}

TEST(Limits, DistinctSamplePointsAreNotCalledRepeated) {
  const std::string m = InvalidArgumentMessage([] { SmoothCurve::Samples({{0, 0}, {1e-170, 0}, {1, 1}}); });
  ExpectNames(m, {"points[1]: value (1e-170, 0)", "distinct from the previous sample point"});
  EXPECT_EQ(m.find("repeats"), std::string::npos) << m;
  ExpectNames(InvalidArgumentMessage([] { SmoothCurve::Samples({{0, 0}, {0, 0}, {1, 1}}); }), {"repeats the previous"});
}

// ------------------------------------------------------------------ isoparallel work and precision
TEST(Limits, IsoparallelGoalFarAwayIsRefusedUpFront) {
  // Identity target, goal 100, 1000 or 1e9 away: more than 10 minutes of family search before.
  for (double d : {100.0, 1000.0}) {
    IsoparallelProblem p;
    p.goal = {d, 0};
    ExpectNames(InvalidArgumentMessage([&] { SolveIsoparallel(p); }), {"goal: value", "must be <= 40"});
  }
  IsoparallelProblem p;
  p.goal = {1e9, 0};
  ExpectNames(InvalidArgumentMessage([&] { SolveIsoparallel(p); }), {"goal[0]: value 1e+09", "<= 1e+06"});
  ExpectNames(InvalidArgumentMessage([] { EnumerateIdentityFamilies(100.0, {}); }), {"chord: value 100", "<= 40"});
}

TEST(Limits, IsoparallelCoordinatesThatLosePrecisionAreRefused) {
  // The start at (1e15, 1e15) ended 0.328 off instead of 0.298 while reporting endpoint error 0.
  IsoparallelProblem p;
  p.start = {1e15, 1e15};
  p.goal = {1e15 + 2, 1e15};
  ExpectNames(InvalidArgumentMessage([&] { SolveIsoparallel(p); }), {"start[0]: value 1e+15", "<= 1e+06"});
  p.start = {1e155, 0};
  ExpectNames(InvalidArgumentMessage([&] { SolveIsoparallel(p); }), {"start[0]: value 1e+155"});
}

TEST(Limits, IsoparallelMultiStartBudgetScalesWithTheChord) {
  IsoparallelProblem p;
  p.goal = {40, 0};
  IsoparallelOptions o;
  o.starts = 10000;
  ExpectNames(InvalidArgumentMessage([&] { SolveIsoparallel(p, o); }),
              {"starts: value 10000", "starts x |goal - start| = 4e+05 exceeds the multi-start budget 350000"});
}

TEST(Limits, IsoparallelOptionLimitsAreNamed) {
  IsoparallelOptions o;
  o.starts = 1000000;  // about 13 minutes before
  EXPECT_EQ(o.Validate(), "starts: value 1000000: must be in [1, 10000]");
  o = {};
  o.length_cap_factor = 1000;  // past a minute before
  EXPECT_EQ(o.Validate(), "length_cap_factor: value 1000: must be in [1, 10]");
  o = {};
  EXPECT_EQ(o.Validate(), "");
  FamilySearchOptions f;
  f.max_length = 10;
  f.length_cap_factor = 1000;
  EXPECT_EQ(f.Validate(), "length_cap_factor: value 1000: must be 0 (no cap) or in [1, 10]");
}

TEST(Limits, ImpulseAndPartitionCountsAreBounded) {
  // plan --n 1000000: 95 s and 11 GB before; isoparallel with 1e6 impulses: more than 13.9 GB.
  const SmoothCurve c = SmoothCurve::Circle({0, 0}, 1, 0, 6.283185307179586);
  ExpectNames(InvalidArgumentMessage([&] { UniformParameterPartition(c, 1000000); }),
              {"partition.n: value 1000000", "must be <= 10000"});
  EXPECT_NO_THROW(UniformParameterPartition(c, 10000));
  IsoparallelPlanProblem iso;
  iso.model = BallModel::FromLambda(2);
  iso.solution.length = 1.0;
  iso.impulses = 1000000;
  ExpectNames(InvalidArgumentMessage([&] { PlanOptimalPath(iso); }), {"impulses: value 1000000", "[1, 10000]"});
  // Every piece gets n steps: 3 pieces of n = 5000 are 15000 steps.
  const Path path(
      {SmoothCurve::Line({0, 0}, {1, 0}), SmoothCurve::Line({1, 0}, {2, 0}), SmoothCurve::Line({2, 0}, {3, 0})});
  ExpectNames(InvalidArgumentMessage([&] { MakePartition(path, {UniformParameter{5000}}, "plan.partition"); }),
              {"plan.partition (n x 3 pieces): value 15000", "steps over all pieces must be <= 10000"});
}

// ------------------------------------------------------------------ reach work budget
TEST(Limits, ReachHorizonTimesWorkIsBounded) {
  // reach --lambda 1e-6 --horizon-periods 1e4: more than a minute and 3.1 GB before.
  ReachOptions o;
  o.horizon_periods = 1e4;
  ExpectNames(o.Validate(), {"horizon_periods: value 10000", "exceeds the refinement budget 25600"});
  o.horizon_periods = 100;
  EXPECT_EQ(o.Validate(), "");
  o.scan_directions = 100000;
  ExpectNames(o.Validate(), {"exceeds the scan budget"});
  ReachProblem p;
  p.target = {6, 0};
  p.start = {1, 0, 0};
  ReachOptions bad;
  bad.horizon_periods = 1e4;
  ExpectNames(InvalidArgumentMessage([&] { Reach(p, bad); }), {"horizon_periods: value 10000"});
}

}  // namespace
}  // namespace plateball
