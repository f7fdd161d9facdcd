// Identity targets (isoparallel_families.h): the costate transport behind the reduction, the axis
// of the one-period rolling, the Figure 7 families against dopri5 and against the independent
// multi-start shooting, certificate, determinism, the straight segment and input errors.
#include "plateball/isoparallel_families.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "elastica_rolling.h"
#include "plateball/elastica.h"
#include "plateball/isoparallel.h"
#include "plateball/rolling.h"
#include "plateball/so3.h"
#include "support/test_support.h"

using namespace plateball;

namespace {

const double kChord = 3.0 * std::sqrt(2.0);  // Figure 7: (0, 0) -> (3, 3)

Eigen::Matrix3d Dopri(const Elastica& e, double a, double b) {
  IntegrationOptions o;
  o.absolute_tolerance = 1e-13;
  o.relative_tolerance = 1e-13;
  return RollingReorientation([&e](double s) { return e.Tangent(s); }, a, b, {}, o);
}

FamilySearch Figure7Families(double cell = 0.5, int certified_run = 3) {
  FamilySearchOptions o;
  o.max_length = 3.0 * std::max(2.0 * kChord, kChord + 2 * M_PI);  // the solver's automatic length
  o.length_cap_factor = 3.0;
  o.cell = cell;
  o.certified_run = certified_run;
  return EnumerateIdentityFamilies(kChord, o);
}

}  // namespace

TEST(CostateTransport, RollingCarriesTheCostateAlongEveryElastica) {
  // v(s) = Q(0, s) v(0) with Q by dopri5 and v from the closed forms, at arbitrary s (not whole
  // periods), oscillating and rotating, both senses.
  for (const auto& [G, hw, h0, k0] : {std::tuple{0.62, 0.3, 0.1, 0.4},
                                      std::tuple{1.3, -1.0, 2.0, 2.9},
                                      std::tuple{0.2, 2.0, -0.5, -1.4},
                                      std::tuple{0.05, 0.0, 1.0, 0.05}}) {
    const Elastica e = Elastica::FromInitialState(G, hw, h0, k0);
    const Eigen::Vector3d v0 = ElasticaCostate(e, 0.0);
    for (double s : {0.37, 2.9, 7.31}) {
      const Eigen::Vector3d vs = ElasticaCostate(e, s);
      EXPECT_LT((Dopri(e, 0.0, s) * v0 - vs).norm(), 1e-10 * (1 + v0.norm())) << G << " " << s;
    }
  }
}

TEST(CostateTransport, OnePeriodRollingTurnsAboutTheCostate) {
  // P v(0) = v(0): the axis of P is v(0), so the signed angle about it is the whole rotation.
  for (const auto& [G, k0] : {std::pair{0.62, 0.4}, std::pair{1.3, 2.9}, std::pair{0.2, -1.4}}) {
    const Elastica e = Elastica::FromInitialState(G, 0.7, 0.2, k0);
    const Eigen::Matrix3d p = Dopri(e, 0.0, e.Period());
    const Eigen::Vector3d n = ElasticaCostate(e, 0.0).normalized();
    EXPECT_LT((p * n - n).norm(), 1e-10) << G;
    const double phi = SignedRotationAngle(p, n);
    EXPECT_LT(RotationAngle(p, ExpSO3(phi * n)), 1e-10) << G;
  }
}

TEST(IdentityFamilies, Figure7FamiliesAreVerifiedByDopriAtAnyPhase) {
  const FamilySearch f = Figure7Families();
  ASSERT_TRUE(f.complete);
  ASSERT_EQ(f.families.size(), 30u);  // 13 oscillating + 17 rotating (each rotating one twice: mirror)
  EXPECT_NEAR(f.families.front().length, 9.41277243, 1e-8);
  EXPECT_LE(f.families.back().length, 3.0 * f.families.front().length);
  int rotating = 0;
  for (const ElasticaFamily& fam : f.families) {
    rotating += fam.regime == PendulumRegime::kRotating;
    EXPECT_LT(fam.residual, 1e-12);
    ElasticaParameters p = fam.Parameters();
    const Elastica e0(p);
    EXPECT_NEAR(fam.length, fam.periods * e0.Period(), 1e-12 * fam.length);
    // The chord: m periods drift exactly |x1 - x0|.
    EXPECT_NEAR(e0.Position(fam.length).norm(), kChord, 1e-9);
    // Any phase: the rolling over the whole path is the identity (dopri5 only).
    for (double shift : {0.0, 0.37}) {
      p.phase = shift * e0.Period() * std::abs(p.rate);
      const Elastica e(p);
      EXPECT_LT(RotationAngle(Dopri(e, 0.0, fam.length), Eigen::Matrix3d::Identity()), 1e-10)
          << fam.length << " shift " << shift;
      EXPECT_NEAR(e.Position(fam.length).norm(), kChord, 1e-9);
    }
  }
  EXPECT_EQ(rotating, 17);
}

TEST(IdentityFamilies, DenserSamplingAndLongerCertificateFindTheSameFamilies) {
  const FamilySearch f = Figure7Families();
  const FamilySearch dense = Figure7Families(0.05, 8);
  ASSERT_TRUE(dense.complete);
  EXPECT_GT(dense.periods_searched, f.periods_searched);
  ASSERT_EQ(dense.families.size(), f.families.size());
  for (std::size_t i = 0; i < f.families.size(); ++i) {
    EXPECT_EQ(dense.families[i].periods, f.families[i].periods) << i;
    EXPECT_NEAR(dense.families[i].length, f.families[i].length, 1e-9) << i;
  }
}

TEST(IdentityFamilies, IndependentMultiStartShootingFindsNothingElse) {
  // The shooting (another method: 3 unknowns, Levenberg-Marquardt, any crossing) with many starts
  // and two seeds: every solution it finds is one of the enumerated families, and it finds no
  // path that is not a whole number of periods (as the costate transport predicts).
  IsoparallelProblem problem;
  problem.goal = {3.0, 3.0};
  const IsoparallelSummary enumerated = SolveIsoparallel(problem);
  ASSERT_EQ(enumerated.method, IsoparallelMethod::kFamilyEnumeration);
  ASSERT_TRUE(enumerated.complete);
  ASSERT_EQ(enumerated.solutions.size(), 47u);
  int matched_total = 0;
  for (std::uint64_t seed : {7u, 987654321u}) {
    IsoparallelOptions shoot;
    shoot.enumerate_families = false;
    shoot.starts = 512;
    shoot.seed = seed;
    const IsoparallelSummary s = SolveIsoparallel(problem, shoot);
    ASSERT_EQ(s.method, IsoparallelMethod::kShooting);
    ASSERT_TRUE(s.IsSolutionUsable());
    EXPECT_NEAR(s.Shortest().length, enumerated.Shortest().length, 1e-7);
    for (const IsoparallelSolution& sol : s.solutions) {
      EXPECT_NEAR(sol.periods, std::round(sol.periods), 1e-6) << sol.length;
      bool matched = false;
      for (const IsoparallelSolution& e : enumerated.solutions)
        matched = matched || (std::abs(e.length - sol.length) < 1e-7 && std::abs(e.G - sol.G) < 1e-6 &&
                              std::abs(e.energy - sol.energy) < 1e-6);
      EXPECT_TRUE(matched) << "shooting found a solution the enumeration does not have: length " << sol.length;
      matched_total += matched;
    }
  }
  EXPECT_GT(matched_total, 40);
}

TEST(IdentityFamilies, LongChordAgreesWithTheShootingIncludingNearTheSeparatrix) {
  // Chord 12: the shooting (512 starts) found a one-period rotating family with 1 - k ~ 1e-7,
  // where one ulp of k moves m phi by ~1e-11; the enumeration must have it (and all others).
  IsoparallelProblem problem;
  problem.goal = {12.0, 0.0};
  const IsoparallelSummary enumerated = SolveIsoparallel(problem);
  ASSERT_TRUE(enumerated.complete);
  bool separatrix_family = false;
  for (const IsoparallelSolution& e : enumerated.solutions) {
    EXPECT_LT(e.orientation_residual, 1e-9) << e.length;
    separatrix_family = separatrix_family ||
                        (std::abs(e.length - 15.36243998) < 1e-7 && e.parameters.regime == PendulumRegime::kRotating);
  }
  EXPECT_TRUE(separatrix_family);
  IsoparallelOptions shoot;
  shoot.enumerate_families = false;
  shoot.starts = 512;
  shoot.seed = 5;
  const IsoparallelSummary s = SolveIsoparallel(problem, shoot);
  ASSERT_TRUE(s.IsSolutionUsable());
  EXPECT_NEAR(s.Shortest().length, enumerated.Shortest().length, 1e-7);
  for (const IsoparallelSolution& sol : s.solutions) {
    bool matched = false;
    for (const IsoparallelSolution& e : enumerated.solutions)
      matched = matched || (std::abs(e.length - sol.length) < 1e-6 && std::abs(e.G - sol.G) < 1e-5);
    EXPECT_TRUE(matched) << "not enumerated: length " << sol.length << " G " << sol.G;
  }
  EXPECT_LT(s.solutions.size(), enumerated.solutions.size());
}

TEST(IdentityFamilies, SolverReportsVerifiedFamiliesAndMirrorPairs) {
  IsoparallelProblem problem;
  problem.start = {1.0, -2.0};
  problem.goal = {4.0, 1.0};  // Figure 7 translated: same chord, same lengths
  const Eigen::Matrix3d a0 = ExpSO3({0.3, -0.2, 1.0});
  problem.start_orientation = a0;
  problem.goal_orientation = a0;
  const IsoparallelSummary s = SolveIsoparallel(problem);
  ASSERT_TRUE(s.IsSolutionUsable());
  ASSERT_EQ(s.solutions.size(), 47u);
  EXPECT_NEAR(s.Shortest().length, 9.41277243, 1e-8);
  for (std::size_t i = 0; i < s.solutions.size(); ++i) {
    const IsoparallelSolution& sol = s.solutions[i];
    EXPECT_TRUE(sol.family);
    EXPECT_LT(sol.orientation_residual, 1e-9) << i;
    EXPECT_LT(sol.endpoint_error, 1e-9) << i;
    if (sol.parameters.regime == PendulumRegime::kRotating) {
      // Its mirror image (the other sense) is reported next to it, same length.
      const bool prev = i > 0 && std::abs(s.solutions[i - 1].length - sol.length) < 1e-12 &&
                        s.solutions[i - 1].parameters.rate == -sol.parameters.rate;
      const bool next = i + 1 < s.solutions.size() && std::abs(s.solutions[i + 1].length - sol.length) < 1e-12 &&
                        s.solutions[i + 1].parameters.rate == -sol.parameters.rate;
      EXPECT_TRUE(prev || next) << i;
    }
  }
}

TEST(IdentityFamilies, ProgressReportsEachPeriodCount) {
  IsoparallelProblem problem;
  problem.goal = {3.0, 3.0};
  IsoparallelOptions o;
  std::vector<std::pair<int, int>> calls;
  o.progress = [&calls](int done, int total) { calls.emplace_back(done, total); };
  const IsoparallelSummary s = SolveIsoparallel(problem, o);
  ASSERT_EQ(static_cast<int>(calls.size()), s.periods_searched);
  for (std::size_t i = 0; i < calls.size(); ++i) {
    EXPECT_EQ(calls[i].first, static_cast<int>(i) + 1);
    EXPECT_EQ(calls[i].second, 0);
  }
}

TEST(IdentityFamilies, ResultsDoNotDependOnTheThreadCount) {
  FamilySearchOptions o;
  o.max_length = 25.0;
  const FamilySearch a = EnumerateIdentityFamilies(kChord, o);
  o.threads = 2;
  const FamilySearch b = EnumerateIdentityFamilies(kChord, o);
  ASSERT_EQ(a.families.size(), b.families.size());
  for (std::size_t i = 0; i < a.families.size(); ++i) {
    EXPECT_EQ(a.families[i].modulus, b.families[i].modulus);
    EXPECT_EQ(a.families[i].length, b.families[i].length);
  }
  EXPECT_EQ(a.evaluations, b.evaluations);
}

TEST(IdentityFamilies, ChordOfTwoPiGivesTheStraightSegmentFirst) {
  FamilySearchOptions o;
  o.max_length = 12.0;
  o.length_cap_factor = 1.5;
  o.max_periods = 40;
  const FamilySearch f = EnumerateIdentityFamilies(2.0 * M_PI, o);
  ASSERT_FALSE(f.families.empty());
  EXPECT_EQ(f.families.front().periods, 0);
  EXPECT_NEAR(f.families.front().length, 2.0 * M_PI, 1e-15);
  EXPECT_FALSE(f.complete) << "no certificate when the chord is a multiple of 2 pi";
  // m phi vanishes at k = 0 for every m here: the degenerate roots near k = 0 are the straight
  // segment again (as long as the chord), never a family of their own.
  for (std::size_t i = 1; i < f.families.size(); ++i)
    EXPECT_GT(f.families[i].length, 2.0 * M_PI * (1 + 1e-9)) << "family " << i << " of k " << f.families[i].modulus;
  IsoparallelProblem p;
  p.goal = {2.0 * M_PI, 0.0};
  IsoparallelOptions so;
  so.length_cap_factor = 1.2;
  const IsoparallelSummary s = SolveIsoparallel(p, so);
  ASSERT_TRUE(s.IsSolutionUsable());
  EXPECT_NEAR(s.Shortest().length, 2.0 * M_PI, 1e-12);
  EXPECT_LT(s.Shortest().orientation_residual, 1e-9);
  // Every family within the 1.2 cap is a distinct path: the straight one is listed once.
  int straight = 0;
  for (const IsoparallelSolution& sol : s.solutions) straight += sol.length <= 2.0 * M_PI * (1 + 1e-9);
  EXPECT_EQ(straight, 1);
}

TEST(IdentityFamilies, ShortCapsFindNothingAndSayComplete) {
  FamilySearchOptions o;
  o.max_length = 0.9 * kChord;  // no path is shorter than the chord
  const FamilySearch f = EnumerateIdentityFamilies(kChord, o);
  EXPECT_TRUE(f.families.empty());
  EXPECT_TRUE(f.complete);
}

TEST(IdentityFamilies, HugeLengthCapsAreClampedAndCertifiedOnlyWhenTheCapShrinks) {
  // max_length = 1e300 is clamped (max(64 chord, 200)); with the 3x cap the search shrinks far
  // below the clamp, so the result is the complete Figure 7 set; without a cap it is not complete.
  FamilySearchOptions o;
  o.max_length = 1e300;
  o.length_cap_factor = 3.0;
  const FamilySearch f = EnumerateIdentityFamilies(kChord, o);
  EXPECT_TRUE(f.complete);
  EXPECT_EQ(f.families.size(), Figure7Families().families.size());
  o.length_cap_factor = 0.0;
  o.max_periods = 2;
  const FamilySearch g = EnumerateIdentityFamilies(kChord, o);
  EXPECT_FALSE(g.complete);
  ASSERT_FALSE(g.families.empty());
  EXPECT_NEAR(g.families.front().length, 9.41277243, 1e-8);
  EXPECT_LE(g.families.back().length, 64.0 * kChord);
}

TEST(IdentityFamilies, InvalidInputNamesTheField) {
  FamilySearchOptions o;
  o.max_length = 10.0;
  EXPECT_NE(plateball::testing::InvalidArgumentMessage([&] { EnumerateIdentityFamilies(-1.0, o); }).find("chord"),
            std::string::npos);
  EXPECT_NE(
      plateball::testing::InvalidArgumentMessage([&] { EnumerateIdentityFamilies(std::nan(""), o); }).find("chord"),
      std::string::npos);
  o.max_length = std::nan("");
  EXPECT_NE(plateball::testing::InvalidArgumentMessage([&] { EnumerateIdentityFamilies(1.0, o); }).find("max_length"),
            std::string::npos);
  o.max_length = 10.0;
  o.length_cap_factor = 0.5;
  EXPECT_NE(
      plateball::testing::InvalidArgumentMessage([&] { EnumerateIdentityFamilies(1.0, o); }).find("length_cap_factor"),
      std::string::npos);
  o.length_cap_factor = 0.0;
  o.cell = 0.0;
  EXPECT_NE(plateball::testing::InvalidArgumentMessage([&] { EnumerateIdentityFamilies(1.0, o); }).find("cell"),
            std::string::npos);
}
