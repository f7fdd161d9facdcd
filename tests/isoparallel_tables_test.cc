// The isoparallel solver's rolling tables and its shape scan's residuals (section 2.2): Magnus
// tables against dopri5 and the closed form, the chord reach bounds of the scan's row skips,
// quaternion tables, the scan residual and its bound against the rotation trick, and the crossings
// of the circle.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

#include "chord_residual.h"
#include "elastica_closed_rolling.h"
#include "elastica_rolling.h"
#include "plateball/elastica.h"
#include "plateball/rolling.h"
#include "plateball/so3.h"
#include "rotation_trick.h"
#include "support/test_support.h"

using namespace plateball;

namespace {

// dopri5 at 1e-14: the reference rolling the tables are compared with.
Eigen::Matrix3d ReferenceRolling(const Elastica& e, double length) {
  IntegrationOptions o;
  o.absolute_tolerance = 1e-14;
  o.relative_tolerance = 1e-14;
  return RollingReorientation([&e](double s) { return e.Tangent(s); }, 0.0, length, {}, o);
}

}  // namespace

TEST(ElasticaRolling, MagnusTableMatchesDopriAndIsSixthOrder) {
  for (const auto& [G, k0] : {std::pair{0.24, 0.3}, std::pair{1.47, 1.5}, std::pair{0.14, 1.2}}) {
    const Elastica e = Elastica::FromInitialState(G, 0.4, 0.1, k0);
    const double length = 2.3 * e.Period();
    const Eigen::Matrix3d ref = ReferenceRolling(e, length);
    const internal::ElasticaRollingTable coarse(e, length, 8, 0.25), fine(e, length, 8, 0.125);
    const double err_coarse = RotationAngle(coarse.Rolling(length), ref);
    const double err_fine = RotationAngle(fine.Rolling(length), ref);
    EXPECT_GT(err_coarse / err_fine, 40.0) << "order 6 gives 64";
    const internal::ElasticaRollingTable polish(e, length, 160, 0.02);
    // The solver's polish accuracy must be below its 1e-12 tolerance: checked against the
    // closed-form rolling (~3e-14 from a Magnus table with steps 0.002), since the adaptive
    // reference's own round-off reaches 1.5e-12 at this length.
    EXPECT_LT(RotationAngle(polish.Rolling(length), internal::ElasticaClosedRolling(e).Rolling(length)), 1e-12);
    EXPECT_LT(RotationAngle(polish.Rolling(length), ref), 3e-12);
  }
}

// The shape scan's node values: Q(0, i h) and x(i h) over several periods, from one period's table
// and the monodromy, against dopri5 and the closed-form position (a polish-accuracy table); and a
// node-pair rolling Q(s0, s0 + L) = Q(0, s0 + L) Q(0, s0)^-1 against dopri5 from s0.
TEST(ElasticaRolling, NodesMatchDopriAndTheClosedForm) {
  const Elastica e = Elastica::FromInitialState(0.6, 0.2, 0.9, 0.4);
  const internal::ElasticaRollingTable table(e, 3.4 * e.Period(), 160, 0.02);
  std::vector<Eigen::Matrix3d> q;
  std::vector<Eigen::Vector2d> x;
  table.Nodes(&q, &x);
  ASSERT_EQ(static_cast<long>(q.size()), table.NodeCount() + 1);
  const double h = table.Step();
  EXPECT_GE(table.NodeCount() * h, 3.4 * e.Period() - 1e-12);
  const long n = table.NodeCount();
  for (long i : {0L, 5L, 159L, 160L, 161L, n / 2, n}) {
    EXPECT_LT((x[i] - e.Position(i * h)).norm(), 1e-11) << i;
    EXPECT_LT(RotationAngle(q[i], ReferenceRolling(e, i * h)), 1e-11) << i;
    EXPECT_LT(RotationAngle(q[i], table.Rolling(i * h)), 1e-13) << i;
  }
  const long i0 = 70, i1 = n - 30;
  ElasticaParameters shifted = e.parameters();
  shifted.phase += shifted.rate * i0 * h;  // the same path from s0 = i0 h
  const Elastica from_s0(shifted);
  EXPECT_LT(RotationAngle(q[i1] * q[i0].transpose(), ReferenceRolling(from_s0, (i1 - i0) * h)), 1e-11);
}

// The shape scan reads the table node by node (ScanShape): NodeRolling at every node of a table of
// several periods against the closed-form rolling (an independent method) and bit for bit against
// Nodes; NodePositions against the closed-form position.
TEST(ElasticaRolling, NodeRollingMatchesTheClosedForm) {
  const Elastica e = Elastica::FromInitialState(0.6, 0.2, 0.9, 0.4);
  const internal::ElasticaRollingTable table(e, 4.3 * e.Period(), 160, 0.02);
  const internal::ElasticaClosedRolling closed(e);
  const std::vector<Eigen::Matrix3d> powers = table.MonodromyPowers();
  ASSERT_EQ(static_cast<long>(powers.size()), table.NodeCount() / table.Steps() + 1);
  std::vector<Eigen::Matrix3d> q;
  std::vector<Eigen::Vector2d> x, positions;
  table.Nodes(&q, &x);
  table.NodePositions(&positions);
  ASSERT_EQ(positions, x);
  double worst = 0.0;
  for (long i = 0; i <= table.NodeCount(); ++i) {
    const Eigen::Matrix3d node = table.NodeRolling(i, powers);
    ASSERT_EQ(node, q[i]) << i;
    worst = std::max(worst, RotationAngle(node, closed.Rolling(i * table.Step())));
    EXPECT_LT((positions[i] - e.Position(i * table.Step())).norm(), 1e-11) << i;
  }
  EXPECT_LT(worst, 1e-11);
  EXPECT_GT(worst, 0.0) << "two methods: not the same numbers";
}

// ChordReach bounds the chord's motion over k nodes (the scan skips nodes by it): brute force over
// every node pair of tables of curled and open shapes, never above k h, and for shapes of many
// periods well below it (the periodic bound is in use).
TEST(ElasticaRolling, ChordReachBoundsEveryNodeChord) {
  std::mt19937_64 rng(10);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int tight = 0;
  for (int trial = 0; trial < 10; ++trial) {  // both regimes and senses, periods ~0.4-3.7
    ElasticaParameters p;
    p.modulus = 0.97 * unit(rng);
    p.rate = (3.0 + 5.0 * unit(rng)) * (trial % 4 < 2 ? 1.0 : -1.0);
    p.regime = trial % 2 == 0 ? PendulumRegime::kOscillating : PendulumRegime::kRotating;
    const Elastica e(p);
    const internal::ElasticaRollingTable table(e, 30.0 + e.Period(), 12, 0.5);  // the scan's accuracy
    ASSERT_TRUE(table.Valid());
    std::vector<Eigen::Vector2d> x;
    table.NodePositions(&x);
    const long count = static_cast<long>(x.size()) - 1 - table.Steps();
    const std::vector<double> reach = internal::ChordReach(x, table.Steps(), count, table.Step());
    ASSERT_EQ(static_cast<long>(reach.size()), count + 1);
    std::vector<double> longest(count + 1, 0.0);  // the longest chord over exactly k nodes
    for (long k = 1; k <= count; ++k)
      for (long j = 0; j + k < static_cast<long>(x.size()); ++j)
        longest[k] = std::max(longest[k], (x[j + k] - x[j]).norm());
    double running = 0.0;
    for (long k = 0; k <= count; ++k) {
      running = std::max(running, longest[k]);
      ASSERT_GE(reach[k], running) << trial << " " << k;
      EXPECT_LE(reach[k], k * table.Step() * (1 + 1e-9) + 1e-12) << trial << " " << k;
      if (k > 0) {
        EXPECT_GE(reach[k], reach[k - 1]);
      }
    }
    if (reach[count] < 0.5 * count * table.Step()) ++tight;
  }
  EXPECT_GE(tight, 5) << "curled shapes of many periods: the periodic bound must be in use";
}

namespace {
// The scan's table of a shape (rate 5, the given modulus) over `length` plus a period: its nodes'
// positions, their ChordReach over every node, the spacing and the nodes per period (no nodes:
// the table is not valid).
struct ReachTable {
  std::vector<Eigen::Vector2d> x;
  std::vector<double> reach;
  double h = 0.0;
  long steps = 0;
};
ReachTable MakeReachTable(double modulus, double length) {
  ElasticaParameters p;
  p.modulus = modulus;
  p.rate = 5.0;
  const Elastica e(p);
  const internal::ElasticaRollingTable table(e, length + e.Period(), 12, 0.5);
  ReachTable t;
  if (!table.Valid()) return t;
  table.NodePositions(&t.x);
  t.h = table.Step();
  t.steps = table.Steps();
  t.reach = internal::ChordReach(t.x, t.steps, static_cast<long>(t.x.size()) - 1, t.h);
  return t;
}
}  // namespace

// FirstReachAtLeast (the scan's galloping search from the guess gap / h) gives std::lower_bound's
// index for every gap: reaches of open and curled shapes, gaps at, between and beyond every entry
// (guesses below, at and far above the answer), and NaN.
TEST(ElasticaRolling, FirstReachAtLeastIsLowerBound) {
  int checked = 0;
  for (const double modulus : {0.3, 0.95}) {
    const ReachTable t = MakeReachTable(modulus, 30.0);
    ASSERT_FALSE(t.x.empty());
    const std::vector<double>& reach = t.reach;
    const double h = t.h;
    std::vector<double> gaps = {0.0, -1.0, 1e300, std::numeric_limits<double>::quiet_NaN(), reach.back() * 2};
    for (std::size_t k = 0; k < reach.size(); ++k)
      for (const double d : {-1e-13, 0.0, 1e-13, 0.5 * h}) gaps.push_back(reach[k] + d);
    for (const double gap : gaps) {
      const long expect = std::lower_bound(reach.begin(), reach.end(), gap) - reach.begin();
      ASSERT_EQ(internal::FirstReachAtLeast(reach, gap, h), expect) << modulus << " " << gap;
      for (const double guess_h : {1e-15 * h, 0.1 * h, 10.0 * h})  // guesses far above and below the answer
        ASSERT_EQ(internal::FirstReachAtLeast(reach, gap, guess_h), expect) << modulus << " " << gap;
      ++checked;
    }
  }
  EXPECT_GT(checked, 100);
}

// ReachSkip (the nodes the shape scan skips): brute force over start nodes j and nodes l of
// tables of an open and a curled shape of many periods, against edges at 1, 2 and 3 (the rotation
// problem's radius 2.24 +- kTangencyMiss): every node l - 1 .. l + k keeps its chord on the side
// of the edge its chord at l is on, and skips do happen.
TEST(ElasticaRolling, ReachSkipKeepsSkippedNodesBeyondTheEdge) {
  long skipped = 0;
  for (const double modulus : {0.3, 0.95}) {
    const ReachTable t = MakeReachTable(modulus, 12.0);
    ASSERT_FALSE(t.x.empty());
    const std::vector<Eigen::Vector2d>& x = t.x;
    const long last = static_cast<long>(x.size()) - 1;
    for (const double edge : {1.0, 2.0, 3.0})
      for (long j = 0; j < t.steps; ++j)
        for (long l = j + 1; l <= last; ++l) {
          const double c = (x[l] - x[j]).norm(), gap = std::abs(c - edge);
          const long k = std::min(internal::ReachSkip(t.reach, gap, t.h), last - l);
          if (k < 1) continue;
          skipped += k;
          for (long m = l - 1; m <= l + k; ++m)
            ASSERT_EQ((x[m] - x[j]).norm() > edge, c > edge)
                << modulus << " " << edge << " " << j << " " << l << " " << m;
        }
  }
  EXPECT_GT(skipped, 1000);
}

// The scan's residual (ChordResidual: B's cos and sin from the normalised chord, the logarithm by
// the trace route) against the rotation trick's (RotationTrickResidual: atan2, sincos, LogSO3 of
// the product) at random targets, chords and rollings over all angles up to pi, a zero chord, and
// TraceLogSO3 against LogSO3 on both sides of its branch (trace 0, angle 2 pi / 3) and near pi.
TEST(Isoparallel, ScanResidualMatchesTheRotationTrick) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  auto random_rotation = [&](double angle) {
    return ExpSO3(angle * Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).normalized());
  };
  double largest = 0.0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Eigen::Matrix3d target = random_rotation(M_PI * std::abs(unit(rng)));
    const Eigen::Matrix3d q = random_rotation(M_PI * std::abs(unit(rng)));
    const double goal_angle = M_PI * unit(rng);
    const Eigen::Vector2d chord = trial == 0 ? Eigen::Vector2d::Zero() : Eigen::Vector2d(3 * unit(rng), 3 * unit(rng));
    const Eigen::Vector3d expected = internal::RotationTrickResidual(target, internal::ChordTurn(goal_angle, chord), q);
    const Eigen::Vector3d got =
        internal::ChordResidual(target.transpose(), {std::cos(goal_angle), std::sin(goal_angle)}, chord, q);
    largest = std::max(largest, expected.norm());
    if (expected.norm() < 3.0) {
      ASSERT_LT((got - expected).norm(), 1e-12) << trial;
    } else {  // near pi the axis' sign is free
      ASSERT_NEAR(got.norm(), expected.norm(), 1e-12) << trial;
    }
  }
  EXPECT_GT(largest, 3.0) << "angles up to pi";
  for (double angle : {0.0, 1e-9, 0.3, 2.0, 2 * M_PI / 3 - 1e-9, 2 * M_PI / 3, 2 * M_PI / 3 + 1e-9, 3.0, M_PI - 1e-6}) {
    const Eigen::Matrix3d r = random_rotation(angle);
    EXPECT_LT((internal::TraceLogSO3(r) - LogSO3(r)).norm(), 1e-12) << angle;
    EXPECT_NEAR(internal::TraceLogSO3(r).norm(), angle, 1e-12) << angle;
  }
}

// The scan stores a crossing's residual as +infinity where LogNormBound proves it above the bound
// without the logarithms: never where |t Log a + (1 - t) Log b| (TraceLogSO3, t on a grid) is at
// most the bound, also near pi where the two logs of close rotations point opposite ways (their
// interpolation small), and it does fire for most pairs clear of the bound and of pi.
TEST(Isoparallel, ScanResidualBoundNeverHidesAStart) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  auto direction = [&] { return Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).normalized(); };
  const internal::LogNormBound bound(1.0);
  int fired = 0, clear = 0, flipped = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const Eigen::Vector3d axis = direction();
    const double angle = trial % 4 == 0 ? M_PI - 0.4 * std::abs(unit(rng)) : 0.8 + 2.4 * std::abs(unit(rng));
    const Eigen::Matrix3d a = ExpSO3(angle * axis);
    const Eigen::Matrix3d b = a * ExpSO3(0.8 * std::abs(unit(rng)) * direction());  // phi up to 0.8
    const Eigen::Vector3d la = internal::TraceLogSO3(a), lb = internal::TraceLogSO3(b);
    double lowest = std::numeric_limits<double>::infinity();
    for (int k = 0; k <= 64; ++k) lowest = std::min(lowest, ((k / 64.0) * la + (1 - k / 64.0) * lb).norm());
    if (la.dot(lb) < 0) ++flipped;
    const bool exceeds = bound.InterpolationExceeds(a, b);
    if (exceeds) {
      ++fired;
      ASSERT_GT(lowest, 1.0) << trial;
    }
    if (lowest > 1.6 && std::max(la.norm(), lb.norm()) < 2.6 && RotationAngle(a, b) < 0.5) {  // tier phi <= 0.5
      ++clear;
      EXPECT_TRUE(exceeds) << trial;
    }
    if (bound.Exceeds(a)) {
      ASSERT_GT(la.norm(), 1.0) << trial;
    }
    if (la.norm() > 1.0 + 2e-6) {
      ASSERT_TRUE(bound.Exceeds(a)) << trial;
    }
  }
  EXPECT_GT(flipped, 100) << "pairs across pi: logs of opposite sign";
  EXPECT_GT(clear, 2000);
  EXPECT_GT(fired, clear);
  for (double angle : {1.0 - 1e-9, 1.0, 1.0 + 1e-7, 1.0 + 2e-6, 2.0, M_PI}) {  // one rotation
    const Eigen::Matrix3d r = ExpSO3(angle * direction());
    EXPECT_EQ(bound.Exceeds(r), angle > 1.0 + 1e-6) << angle;
  }
}

// The scan's table keeps its rotations as unit quaternions (TableRotations::kQuaternions): against
// a matrix table of the same shape and accuracy (the reference path), the same spacing, steps and
// node positions bit for bit, every node's NodeQuaternion the rotation of NodeRolling to round-off,
// still unit; NodePositions bit for bit n D + x_j (D = DriftPerPeriod, i = n N + j) at the scan's
// accuracy; each form's reads throw on the other; a table shorter than a period and a straight
// line. QuaternionExp against ExpSO3 across its Taylor branch (|w| = 0.6) and up to pi.
TEST(ElasticaRolling, QuaternionTableMatchesTheMatrixTable) {
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 8; ++trial) {  // both regimes and senses; the last one shorter than a period
    ElasticaParameters p;
    p.modulus = 0.97 * unit(rng);
    p.rate = (0.5 + 5.0 * unit(rng)) * (trial % 4 < 2 ? 1.0 : -1.0);
    p.regime = trial % 2 == 0 ? PendulumRegime::kOscillating : PendulumRegime::kRotating;
    const Elastica e(p);
    const double length = trial == 7 ? 0.7 * e.Period() : 20.0 + e.Period();
    const internal::ElasticaRollingTable matrices(e, length, 12, 0.5);
    const internal::ElasticaRollingTable quats(e, length, 12, 0.5, 200000, internal::TableRotations::kQuaternions);
    ASSERT_TRUE(matrices.Valid() && quats.Valid()) << trial;
    ASSERT_EQ(quats.Steps(), matrices.Steps());
    ASSERT_EQ(quats.Step(), matrices.Step());
    ASSERT_EQ(quats.NodeCount(), matrices.NodeCount());
    std::vector<Eigen::Vector2d> xm, xq;
    matrices.NodePositions(&xm);
    quats.NodePositions(&xq);
    ASSERT_EQ(xq, xm) << trial;
    const long n_steps = quats.Steps();
    for (long i = 0; trial < 7 && i <= quats.NodeCount(); ++i)
      ASSERT_EQ(xq[i], (static_cast<double>(i / n_steps) * e.DriftPerPeriod() + xq[i % n_steps]).eval())
          << trial << " " << i;
    const std::vector<Eigen::Matrix3d> pm = matrices.MonodromyPowers();
    const std::vector<Eigen::Quaterniond> pq = quats.MonodromyQuaternionPowers();
    ASSERT_EQ(pq.size(), pm.size());
    double worst = 0.0;
    for (long i = 0; i <= quats.NodeCount(); ++i) {
      const Eigen::Quaterniond q = quats.NodeQuaternion(i, pq);
      worst = std::max(worst, (q.toRotationMatrix() - matrices.NodeRolling(i, pm)).cwiseAbs().maxCoeff());
      EXPECT_NEAR(q.norm(), 1.0, 1e-13) << trial << " " << i;
    }
    EXPECT_LT(worst, 1e-13) << trial;
    EXPECT_THROW(quats.Rolling(1.0), std::logic_error);
    EXPECT_THROW(quats.MonodromyPowers(), std::logic_error);
    EXPECT_THROW(matrices.MonodromyQuaternionPowers(), std::logic_error);
  }
  ElasticaParameters line;
  line.rate = 0.0;
  const Elastica straight(line);
  ASSERT_TRUE(straight.IsStraight());
  const internal::ElasticaRollingTable ms(straight, 3.0, 12, 0.5),
      qs(straight, 3.0, 12, 0.5, 200000, internal::TableRotations::kQuaternions);
  const std::vector<Eigen::Quaterniond> none = qs.MonodromyQuaternionPowers();
  EXPECT_LT((qs.NodeQuaternion(1, none).toRotationMatrix() - ms.NodeRolling(1, ms.MonodromyPowers())).norm(), 1e-15);
  std::uniform_real_distribution<double> sym(-1.0, 1.0);
  for (double angle : {0.0, 1e-9, 0.1, 0.2, 0.6 - 1e-12, 0.6, 0.6 + 1e-12, 1.0, 2.5, M_PI}) {
    const Eigen::Vector3d w = angle * Eigen::Vector3d(sym(rng), sym(rng), sym(rng)).normalized();
    const Eigen::Quaterniond q = internal::QuaternionExp(w);
    EXPECT_NEAR(q.norm(), 1.0, 2e-16) << angle;
    EXPECT_LT((q.toRotationMatrix() - ExpSO3(w)).cwiseAbs().maxCoeff(), 1e-15) << angle;
  }
}

// The scan's residual in quaternions (ChordQuaternion, QuaternionLog, LogNormBound on quaternions)
// against the matrix path it replaced (ChordRotation, TraceLogSO3, LogNormBound on matrices) at
// random targets, goals, chords (one zero) and rollings over all angles up to pi: the same logs
// to 1e-12 (near pi, where the axis' sign is free, the same norm), the same bound decisions, and
// for quaternions scaled off the unit sphere (the scale cancels) the same again.
TEST(Isoparallel, ScanQuaternionResidualMatchesTheMatrixPath) {
  std::mt19937_64 rng(14);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  auto random_rotation = [&](double angle) {
    return ExpSO3(angle * Eigen::Vector3d(unit(rng), unit(rng), unit(rng)).normalized());
  };
  const internal::LogNormBound bound(1.0);
  int exceeds = 0, interpolation_exceeds = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    const Eigen::Matrix3d target = random_rotation(M_PI * std::abs(unit(rng)));
    const Eigen::Matrix3d q = random_rotation(M_PI * std::abs(unit(rng)));
    const Eigen::Matrix3d q2 = q * random_rotation(0.8 * std::abs(unit(rng)));  // a neighbouring node
    const double goal_angle = M_PI * unit(rng);
    const internal::GoalDirection goal{std::cos(goal_angle), std::sin(goal_angle)};
    const Eigen::Vector2d chord = trial == 0 ? Eigen::Vector2d::Zero() : Eigen::Vector2d(3 * unit(rng), 3 * unit(rng));
    const Eigen::Vector2d chord2 = chord + Eigen::Vector2d(0.3 * unit(rng), 0.3 * unit(rng));
    const Eigen::Matrix3d ma = internal::ChordRotation(target.transpose(), goal, chord, q);
    const Eigen::Matrix3d mb = internal::ChordRotation(target.transpose(), goal, chord2, q2);
    const double scale = trial % 3 == 0 ? 1.0 : 0.5 + 2.0 * std::abs(unit(rng));
    const Eigen::Quaterniond tc = Eigen::Quaterniond(target).conjugate();
    const Eigen::Quaterniond qa = internal::ChordQuaternion(tc, goal, chord, Eigen::Quaterniond(q));
    const Eigen::Quaterniond qb = internal::ChordQuaternion(tc, goal, chord2, Eigen::Quaterniond(q2));
    const Eigen::Quaterniond sa(scale * qa.coeffs()), sb(scale * qb.coeffs());
    const Eigen::Vector3d expected = internal::TraceLogSO3(ma);
    for (const Eigen::Quaterniond& a : {qa, sa}) {
      const Eigen::Vector3d got = internal::QuaternionLog(a);
      if (expected.norm() < 3.0) {
        ASSERT_LT((got - expected).norm(), 1e-12) << trial;
      } else {
        ASSERT_NEAR(got.norm(), expected.norm(), 1e-12) << trial;
      }
    }
    EXPECT_LT((qa.toRotationMatrix() - ma).cwiseAbs().maxCoeff(), 1e-14) << trial;
    exceeds += bound.Exceeds(ma);
    interpolation_exceeds += bound.InterpolationExceeds(ma, mb);
    ASSERT_EQ(bound.Exceeds(qa), bound.Exceeds(ma)) << trial;
    ASSERT_EQ(bound.Exceeds(sa), bound.Exceeds(ma)) << trial;
    ASSERT_EQ(bound.InterpolationExceeds(qa, qb), bound.InterpolationExceeds(ma, mb)) << trial;
    ASSERT_EQ(bound.InterpolationExceeds(sa, sb), bound.InterpolationExceeds(ma, mb)) << trial;
  }
  EXPECT_GT(exceeds, 1000);
  EXPECT_GT(interpolation_exceeds, 500);
  EXPECT_LT(interpolation_exceeds, exceeds) << "both outcomes of each test";
}

// The search reuses a trial's table for longer lengths only where ServesLength says a table over
// that length would be the same one: a periodic table (the rolling there bit for bit that of a
// table built over the longer length, and near dopri5 at the search accuracy), not a table
// shorter than one period (it tabulates its own length only), nor a shorter length.
TEST(ElasticaRolling, ServesLengthOnlyWhereALongerTableIsTheSame) {
  const Elastica e = Elastica::FromInitialState(0.6, 0.2, 0.9, 0.4);
  const double length = 2.2 * e.Period(), longer = length + 1e-3;
  const internal::ElasticaRollingTable table(e, length, 12, 0.5), rebuilt(e, longer, 12, 0.5);
  ASSERT_TRUE(table.ServesLength(longer));
  EXPECT_FALSE(table.ServesLength(0.5 * length));
  for (double s : {length, longer}) {
    const Eigen::Matrix3d a = table.Rolling(s), b = rebuilt.Rolling(s);
    EXPECT_EQ(a, b) << s;
    EXPECT_LT(RotationAngle(a, ReferenceRolling(e, s)), 1e-3) << s;  // search accuracy (12 steps per period)
  }
  const internal::ElasticaRollingTable part(e, 0.6 * e.Period(), 12, 0.5);
  EXPECT_FALSE(part.ServesLength(0.6 * e.Period() + 1e-3)) << "a table within one period tabulates its own length";
}

TEST(ElasticaRolling, CrossingsLieOnTheCircle) {
  const Elastica e = Elastica::FromInitialState(0.6, 0.2, 0.9, 0.4);
  const internal::ElasticaRollingTable table(e, 40.0, 12, 0.5);
  const auto crossings = table.Crossings(2.5, 100);
  ASSERT_GE(crossings.size(), 2u);
  for (double s : crossings) EXPECT_NEAR(e.Position(s).norm(), 2.5, 1e-12);
  // Independent count: sign changes of |x| - 2.5 on a fine grid of the closed form.
  int changes = 0;
  double prev = -2.5;
  for (int i = 1; i <= 40000; ++i) {
    const double f = e.Position(i * 1e-3).norm() - 2.5;
    if ((f > 0) != (prev > 0)) ++changes;
    prev = f;
  }
  EXPECT_EQ(static_cast<int>(crossings.size()), changes);
}

// The polish finds its crossings on a table of positions only: the same
// nodes and positions as the full table bit for bit, hence the same crossings, numbers and roots;
// its rolling is not there to be used by mistake.
TEST(ElasticaRolling, PositionsOnlyTableHasTheSameCrossingsAndNoRolling) {
  std::mt19937_64 rng(15);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  int crossings_seen = 0;
  for (int trial = 0; trial < 12; ++trial) {
    const Elastica e = Elastica::FromInitialState(0.1 + 1.5 * unit(rng), 0.2, 3.0 * unit(rng), -1.5 + 3.0 * unit(rng));
    if (e.IsStraight()) continue;
    const double radius = 1.0 + 2.0 * unit(rng), limit = 30.0;
    const internal::ElasticaRollingTable full(e, limit, 160, 0.02), positions(e, limit, 160, 0.02, 200000, true);
    ASSERT_TRUE(positions.PositionsOnly());
    ASSERT_EQ(full.Valid(), positions.Valid());
    const std::vector<double> a = full.Crossings(radius, 50), b = positions.Crossings(radius, 50);
    ASSERT_EQ(a, b) << trial;
    crossings_seen += static_cast<int>(a.size());
    for (std::size_t n = 0; n < a.size(); ++n) {
      double s = -1.0;
      ASSERT_TRUE(positions.FindCrossing(radius, static_cast<int>(n + 1), &s));
      EXPECT_EQ(s, a[n]);
      EXPECT_NEAR(e.Position(s).norm(), radius, 1e-12);
      int count = 0;
      double root = -1.0;
      ASSERT_TRUE(positions.NearestCrossing(radius, a[n] + 1e-6, 1e-5, 50, &count, &root));
      EXPECT_EQ(count, static_cast<int>(n + 1));
      EXPECT_EQ(root, a[n]);
    }
  }
  EXPECT_GT(crossings_seen, 20) << "the trials must cross their circles";
  const Elastica e = Elastica::FromInitialState(0.6, 0.2, 0.9, 0.4);
  const internal::ElasticaRollingTable positions(e, 10.0, 12, 0.5, 200000, true);
  EXPECT_THROW(positions.Rolling(1.0), std::logic_error);
  std::vector<Eigen::Matrix3d> q;
  std::vector<Eigen::Vector2d> x;
  EXPECT_THROW(positions.Nodes(&q, &x), std::logic_error);
}
