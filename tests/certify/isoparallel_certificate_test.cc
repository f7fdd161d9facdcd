// The whole certificate of a general isoparallel target (isoparallel_certificate.h) and its plan of
// pieces (src/certify/coverage.h). The full certificate of a target at its shortest
// length costs minutes (docs/paper_notes.md, "General targets: the whole certificate in one
// call"); here it runs at caps below the shortest, where an independent bound says what it must
// find, and with tiny budgets, where it must say which piece stayed open.
#include "plateball/isoparallel_certificate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "certify/coverage.h"
#include "certify/tails.h"
#include "plateball/problem_io.h"
#include "plateball/so3.h"
#include "plateball/task_adapters.h"
#include "support/test_support.h"

namespace plateball {
namespace {

using internal::CoveragePiece;
using internal::CoveragePieceKind;
using internal::CoveragePlan;

constexpr double kRotationShortest = 5.99098308;

IsoparallelProblem RotationProblem() {
  const Problem p = ReadProblemFile(testing::SourcePath("problems/isoparallel_rotation.json"));
  return IsoparallelSetupFor(p).problem;
}

// Whether a path (regime, modulus k < 1, rate) lies in a piece (an oscillating path with a negative
// rate is the positive one mirrored).
bool Covered(const CoveragePiece& p, PendulumRegime regime, double k, double rate) {
  if (p.regime != regime || k < p.k_lo || k > p.k_hi) return false;
  const double r =
      regime == PendulumRegime::kOscillating || p.kind != CoveragePieceKind::kWindow ? std::abs(rate) : rate;
  if (p.kind == CoveragePieceKind::kSlowTail) return r <= p.rate_hi;
  return r >= p.rate_lo && r <= p.rate_hi;
}

bool CoveredByAny(const std::vector<CoveragePiece>& pieces, PendulumRegime regime, double k, double rate) {
  for (const CoveragePiece& p : pieces)
    if (Covered(p, regime, k, rate)) return true;
  return false;
}

// A path no piece holds may still be a solution only if its rate is within the averaging lemma's
// bound at its modulus: sample those (k uniform and log-uniform towards 1, the rate uniform up to
// the bound) and find each in a piece; without any one piece some sample is lost.
TEST(IsoparallelCertificate, PlanCoversEveryRateTheLemmaLeaves) {
  const internal::CertifyTarget target = internal::CertifyTargetOf(RotationProblem());
  const double cap = 1.0001 * kRotationShortest, margin = 1e-7;
  const CoveragePlan plan = internal::PlanCoverage(target, cap, margin);
  ASSERT_EQ(plan.message, "");
  ASSERT_TRUE(plan.rate_tail_excluded);
  ASSERT_EQ(plan.pieces.size(), 10u);
  std::mt19937_64 rng(1);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  struct Sample {
    PendulumRegime regime;
    double k, rate;
  };
  std::vector<Sample> samples;
  for (int i = 0; i < 40000; ++i) {
    const PendulumRegime regime = i % 2 ? PendulumRegime::kRotating : PendulumRegime::kOscillating;
    const double k = i % 4 < 2 ? unit(rng) : 1.0 - std::pow(10.0, -12.0 * unit(rng));
    const double a = internal::MaxSolutionRate(target, regime, k, cap, margin);
    ASSERT_TRUE(std::isfinite(a)) << k;
    samples.push_back({regime, k, (2.0 * unit(rng) - 1.0) * a});
  }
  for (const Sample& s : samples)
    ASSERT_TRUE(CoveredByAny(plan.pieces, s.regime, s.k, s.rate))
        << ToString(s.regime) << " k " << s.k << " rate " << s.rate;
  for (std::size_t drop = 0; drop < plan.pieces.size(); ++drop) {
    std::vector<CoveragePiece> without = plan.pieces;
    without.erase(without.begin() + static_cast<long>(drop));
    bool lost = false;
    for (const Sample& s : samples) lost = lost || !CoveredByAny(without, s.regime, s.k, s.rate);
    EXPECT_TRUE(lost) << "not needed: " << plan.pieces[drop].Name();
  }
  // Every piece but the slow tails (|rate| <= 0.5 under the middle and loop pieces) reaches its k
  // range's bound (the lemma excludes the rates above).
  for (const CoveragePiece& p : plan.pieces) {
    if (p.kind == CoveragePieceKind::kSlowTail) continue;
    EXPECT_GE(std::max(std::abs(p.rate_lo), std::abs(p.rate_hi)),
              internal::MaxSolutionRateOver(target, p.regime, p.k_lo, p.k_hi, cap, margin))
        << p.Name();
  }
}

TEST(IsoparallelCertificate, PlanSaysWhenTheLemmaExcludesNothingAndNamesBadInput) {
  internal::CertifyTarget straight = internal::CertifyTargetOf(RotationProblem());
  const Eigen::Vector2d chord(2.0, 1.0);
  straight.target = ExpSO3(Eigen::Vector3d(-chord.y(), chord.x(), 0.0));  // the straight rolling
  const CoveragePlan s = internal::PlanCoverage(straight, 10.0);
  EXPECT_EQ(s.message, "");
  EXPECT_LT(s.straight_residual, 1e-12);
  EXPECT_FALSE(s.rate_tail_excluded);
  EXPECT_TRUE(s.pieces.empty());
  EXPECT_NE(internal::PlanCoverage(straight, 1.0).message.find("cap"), std::string::npos);  // below |x1 - x0|
  EXPECT_NE(internal::PlanCoverage(straight, 10.0, -1.0).message.find("margin"), std::string::npos);
}

// A summary of the problem without a solve: the certificate only reads the problem, the solver's
// options (tolerance, threads) and its solutions.
IsoparallelSummary Unsolved(const IsoparallelProblem& problem) {
  IsoparallelSummary s;
  s.problem = problem;
  return s;
}

// The target rotation is 3 rad about e3, 0.2 from the start: rolling turns the ball by at most the
// length rolled (|omega| = 1 per unit length), so no solution is shorter than 3. The certificate at
// the cap 0.25 must close every piece and prove none.
IsoparallelProblem ShortChordHalfTurn() {
  IsoparallelProblem p;
  p.goal = Eigen::Vector2d(0.2, 0.0);
  p.goal_orientation = ExpSO3(Eigen::Vector3d(0.0, 0.0, 3.0));
  return p;
}

TEST(IsoparallelCertificate, ProvesNoSolutionBelowTheTurningBound) {
  IsoparallelCertificateOptions o;
  o.length_cap = 0.25;
  std::vector<int> order;
  o.progress = [&](const IsoparallelCertificatePiece&, int done, int total) {
    EXPECT_EQ(total, 10);
    order.push_back(done);
  };
  const IsoparallelCertificate c = CertifyIsoparallel(Unsolved(ShortChordHalfTurn()), o);
  ASSERT_TRUE(c.IsComplete()) << c.FullReport();
  EXPECT_TRUE(c.IsSolutionUsable());
  EXPECT_EQ(c.message, "");
  EXPECT_EQ(c.length_cap, 0.25);
  EXPECT_TRUE(c.solutions.empty());
  EXPECT_TRUE(c.solver_unproved.empty());
  ASSERT_EQ(c.pieces.size(), 10u);
  long boxes = 0;
  for (const IsoparallelCertificatePiece& p : c.pieces) {
    EXPECT_TRUE(p.closed) << p.name << ": " << p.result;
    EXPECT_GT(p.boxes, 0) << p.name;
    EXPECT_EQ(p.proved, 0);
    boxes += p.boxes;
  }
  EXPECT_EQ(c.boxes, boxes);
  EXPECT_EQ(order, (std::vector<int>{1, 2, 3, 4, 5, 6, 7, 8, 9, 10}));
  EXPECT_NE(c.BriefReport().find("complete, length cap 0.25, 0 solution(s) proved"), std::string::npos)
      << c.BriefReport();
  // The same pieces and boxes on two threads.
  o.threads = 2;
  o.progress = nullptr;
  const IsoparallelCertificate two = CertifyIsoparallel(Unsolved(ShortChordHalfTurn()), o);
  ASSERT_EQ(two.pieces.size(), c.pieces.size());
  for (std::size_t i = 0; i < c.pieces.size(); ++i) {
    EXPECT_EQ(two.pieces[i].name, c.pieces[i].name);
    EXPECT_EQ(two.pieces[i].boxes, c.pieces[i].boxes);
  }
}

TEST(IsoparallelCertificate, ABudgetTooSmallNamesTheOpenPiece) {
  IsoparallelCertificateOptions o;
  o.length_cap = 0.25;
  o.max_boxes = 50;
  const IsoparallelCertificate c = CertifyIsoparallel(Unsolved(ShortChordHalfTurn()), o);
  EXPECT_EQ(c.status, IsoparallelCertificateStatus::kIncomplete);
  EXPECT_FALSE(c.IsSolutionUsable());
  EXPECT_EQ(ToString(c.status), "incomplete");
  ASSERT_FALSE(c.pieces.empty());
  const IsoparallelCertificatePiece* open = nullptr;
  for (const IsoparallelCertificatePiece& p : c.pieces) {
    EXPECT_LE(p.boxes, 50) << p.name;
    if (!p.closed && !open) open = &p;
  }
  ASSERT_NE(open, nullptr);
  EXPECT_EQ(c.message, "not closed: " + open->name + ": " + open->result);
  EXPECT_NE(open->result.find("budget exhausted"), std::string::npos) << open->result;
  EXPECT_NE(c.FullReport().find("OPEN   " + open->name), std::string::npos) << c.FullReport();
}

TEST(IsoparallelCertificate, SaysWhenItDoesNotApply) {
  // Identity target: the family enumeration is complete already.
  IsoparallelProblem identity;
  identity.goal = Eigen::Vector2d(3.0, 3.0);
  IsoparallelCertificate c = CertifyIsoparallel(Unsolved(identity));
  EXPECT_EQ(c.status, IsoparallelCertificateStatus::kNotApplicable);
  EXPECT_EQ(ToString(c.status), "not_applicable");
  EXPECT_NE(c.message.find("identity"), std::string::npos) << c.message;
  // No solution to take the cap from, and none given.
  c = CertifyIsoparallel(Unsolved(RotationProblem()));
  EXPECT_EQ(c.status, IsoparallelCertificateStatus::kNotApplicable);
  EXPECT_NE(c.message.find("length_cap"), std::string::npos) << c.message;
  // The straight rolling as target: the averaging lemma bounds no rate.
  IsoparallelProblem straight;
  straight.goal = Eigen::Vector2d(2.0, 1.0);
  straight.goal_orientation = ExpSO3(Eigen::Vector3d(-1.0, 2.0, 0.0));
  IsoparallelCertificateOptions o;
  o.length_cap = 5.0;
  c = CertifyIsoparallel(Unsolved(straight), o);
  EXPECT_EQ(c.status, IsoparallelCertificateStatus::kNotApplicable);
  EXPECT_NE(c.message.find("straight rolling"), std::string::npos) << c.message;
  EXPECT_TRUE(c.pieces.empty());
}

TEST(IsoparallelCertificate, InvalidOptionsNameTheField) {
  const IsoparallelSummary s = Unsolved(ShortChordHalfTurn());
  auto message = [&](IsoparallelCertificateOptions o) {
    return testing::InvalidArgumentMessage([&] { CertifyIsoparallel(s, o); }, "no exception");
  };
  IsoparallelCertificateOptions o;
  o.cap_factor = 0.5;
  EXPECT_NE(message(o).find("cap_factor: value 0.5"), std::string::npos) << message(o);
  o = {};
  o.length_cap = -1.0;
  EXPECT_NE(message(o).find("length_cap: value -1"), std::string::npos) << message(o);
  o = {};
  o.length_cap = 0.1;  // below |x1 - x0| = 0.2: no path reaches the goal
  EXPECT_NE(message(o).find("cap: value 0.1"), std::string::npos) << message(o);
  o = {};
  o.max_boxes = 0;
  EXPECT_NE(message(o).find("max_boxes: value 0"), std::string::npos) << message(o);
  o = {};
  o.threads = 0;
  EXPECT_NE(message(o).find("threads: value 0"), std::string::npos) << message(o);
  o = {};
  o.length_cap = std::nan("");
  EXPECT_NE(message(o).find("length_cap"), std::string::npos) << message(o);
}

// The solver's solution that is a proved path: the same regime and canonical coordinates, the
// phase modulo its period; a path 1e-4 longer, or of the other regime, is not it.
TEST(IsoparallelCertificate, MatchesAProvedPathToTheSolversSolution) {
  IsoparallelSolution shortest;
  shortest.parameters.regime = PendulumRegime::kOscillating;
  shortest.parameters.rate = 1.13211769411;
  shortest.parameters.modulus = 0.792357396832;
  shortest.parameters.phase = 1.81505706519;
  shortest.length = 5.99098307967;
  IsoparallelSolution other = shortest;
  other.parameters.regime = PendulumRegime::kRotating;
  const std::vector<IsoparallelSolution> list = {other, shortest};
  internal::CertifyPoint p = internal::CanonicalSolution(shortest.parameters, shortest.length);
  EXPECT_EQ(internal::MatchingSolution(list, PendulumRegime::kOscillating, p, 1e-6), 1);
  p[internal::kCertifyPhase] +=
      internal::PhasePeriod(PendulumRegime::kOscillating, p[internal::kCertifyModulus]) - 1e-8;
  EXPECT_EQ(internal::MatchingSolution(list, PendulumRegime::kOscillating, p, 1e-6), 1);
  p[internal::kCertifyLength] += 1e-4;
  EXPECT_EQ(internal::MatchingSolution(list, PendulumRegime::kOscillating, p, 1e-6), -1);
  EXPECT_EQ(internal::MatchingSolution({other},
                                       PendulumRegime::kOscillating,
                                       internal::CanonicalSolution(shortest.parameters, shortest.length),
                                       1e-6),
            -1);
}

// The rotation problem's whole certificate at 1.0001 x its shortest length costs 209M boxes
// (minutes of CPU): a stop must end each piece within kInterruptPollBoxes boxes of the question
// that said stop. Every piece of the plan, run alone with a hook that says stop at its second
// question (the first is asked before the first box), examines exactly one round of boxes and
// reports "interrupted", not closed: windows, slow tails and loop families alike. (The budget
// of four rounds makes a piece that ignored the stop end "budget exhausted" at 4 rounds instead.)
constexpr long kStopBudget = 4 * internal::kInterruptPollBoxes;

TEST(IsoparallelCertificate, AStopEndsEveryKindOfPieceAtItsNextQuestion) {
  const internal::CertifyTarget target = internal::CertifyTargetOf(RotationProblem());
  const double cap = 1.0001 * kRotationShortest;
  const CoveragePlan plan = internal::PlanCoverage(target, cap);
  ASSERT_EQ(plan.pieces.size(), 10u);
  std::vector<CoveragePieceKind> kinds;
  for (const CoveragePiece& piece : plan.pieces) {
    int asked = 0;
    const internal::CoveragePieceResult r =
        internal::RunCoveragePiece(target, piece, cap, kStopBudget, [&] { return ++asked == 2; });
    EXPECT_EQ(asked, 2) << piece.Name();
    EXPECT_TRUE(r.interrupted) << piece.Name() << ": " << r.result;
    EXPECT_FALSE(r.closed) << piece.Name();
    EXPECT_EQ(r.boxes, internal::kInterruptPollBoxes) << piece.Name();
    EXPECT_EQ(r.result.rfind("interrupted", 0), 0u) << r.result;
    kinds.push_back(piece.kind);
  }
  for (CoveragePieceKind kind : {CoveragePieceKind::kWindow, CoveragePieceKind::kSlowTail, CoveragePieceKind::kLoops})
    EXPECT_NE(std::find(kinds.begin(), kinds.end(), kind), kinds.end()) << ToString(kind);
}

// The whole certificate, stopped while its first piece runs (one thread: the hook is asked before
// the piece, at its first box and after one round of boxes, where it says stop): the first piece
// ends after one round, the others are not run, nothing is claimed.
TEST(IsoparallelCertificate, AStopWhileRunningClaimsNothing) {
  IsoparallelCertificateOptions o;
  o.length_cap = 1.0001 * kRotationShortest;
  o.max_boxes = kStopBudget;
  int asked = 0;
  o.interrupted = [&] { return ++asked == 3; };
  int ended = 0;
  o.progress = [&](const IsoparallelCertificatePiece&, int, int) { ++ended; };
  const IsoparallelCertificate c = CertifyIsoparallel(Unsolved(RotationProblem()), o);
  EXPECT_EQ(asked, 3);
  EXPECT_EQ(c.status, IsoparallelCertificateStatus::kInterrupted);
  EXPECT_EQ(ToString(c.status), "interrupted");
  EXPECT_FALSE(c.IsSolutionUsable());
  EXPECT_EQ(c.message, "interrupted: 0 of 10 pieces closed before the stop; nothing is claimed about the others");
  EXPECT_TRUE(c.solutions.empty());
  ASSERT_EQ(c.pieces.size(), 10u);
  EXPECT_EQ(c.boxes, internal::kInterruptPollBoxes);
  EXPECT_EQ(c.pieces[0].boxes, internal::kInterruptPollBoxes);
  EXPECT_EQ(ended, 1);  // the interrupted piece reports its end; the pieces not run do not
  for (std::size_t i = 1; i < c.pieces.size(); ++i) {
    EXPECT_FALSE(c.pieces[i].closed);
    EXPECT_EQ(c.pieces[i].boxes, 0);
    EXPECT_EQ(c.pieces[i].result, "not run: interrupted");
    EXPECT_FALSE(c.pieces[i].name.empty());
  }
  EXPECT_NE(c.BriefReport().find("interrupted, length cap"), std::string::npos) << c.BriefReport();
}

// A stop requested before the start, on two threads: no piece runs, no box is examined.
TEST(IsoparallelCertificate, AStopBeforeTheStartRunsNoPiece) {
  IsoparallelCertificateOptions o;
  o.length_cap = 1.0001 * kRotationShortest;
  o.threads = 2;
  o.interrupted = [] { return true; };
  const IsoparallelCertificate c = CertifyIsoparallel(Unsolved(RotationProblem()), o);
  EXPECT_EQ(c.status, IsoparallelCertificateStatus::kInterrupted);
  EXPECT_EQ(c.boxes, 0);
  ASSERT_EQ(c.pieces.size(), 10u);
  for (const IsoparallelCertificatePiece& p : c.pieces) EXPECT_EQ(p.result, "not run: interrupted") << p.name;
}

}  // namespace
}  // namespace plateball
