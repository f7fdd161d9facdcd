#include "plateball/isoparallel.h"

#include <ceres/tiny_solver.h>

#include <Eigen/Geometry>
#include <Eigen/SVD>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <optional>
#include <mutex>
#include <random>
#include <sstream>
#include <stdexcept>

#include "check.h"
#include "chord_residual.h"
#include "circle_crossings.h"
#include "dynamics.h"
#include "elastica_closed_rolling.h"
#include "elastica_rolling.h"
#include "isoparallel_conjugate.h"
#include "isoparallel_twin.h"
#include "parallel_for.h"
#include "plateball/isoparallel_families.h"
#include "plateball/rolling.h"
#include "plateball/so3.h"
#include "rotation_trick.h"

namespace plateball {
namespace {

// The nodes of a table: Magnus steps per curvature period and longest step. The rolling along a
// candidate is the closed form (ElasticaClosedRolling, ~1e-13 at any length, ~1 us) everywhere
// but in the shape scan (ScanShape: one Magnus table at kSearch over all its nodes); the
// crossings of the circle are found on the nodes of a table of positions only.
struct Accuracy {
  int steps_per_period;
  double max_step;
};
// Search: the shape scan's table, rolling errors ~2e-5 rad median, up to 3e-4 (60 random elastica
// of 1-4 periods against dopri5 at 1e-14), and the coarse crossing nodes. kPolish: the fine
// crossing nodes of the hand-off near a tangency (those of the former polish: the same crossing
// numbers).
constexpr Accuracy kSearch{12, 0.5};
constexpr Accuracy kPolish{160, 0.02};
// A search run stops below kSearchStop (the search accuracy) and is polished when below
// kSearchAccept; runs that do not get there in kSearchIterations are abandoned.
constexpr double kSearchStop = 3e-6;
constexpr double kSearchAccept = 1e-4;
// Runs still searching after 20 iterations rarely converge: a longer search finds no solution
// more on the ten targets of docs/paper_notes.md and costs up to 2x the evaluations.
constexpr int kSearchIterations = 20;
// Triage: a search run whose residual is still above kHopelessResidual after kTriageIterations
// is dropped: such runs almost never converge, and dropping them saves most of the search's cost
// while losing nothing on the ten targets of docs/paper_notes.md ("General targets").
constexpr int kTriageIterations = 8;
constexpr double kHopelessResidual = 0.5;
// A free-length search run is handed to the crossing formulation only when its residual is below
// kHandOffResidual (100x kSearchAccept: the crossing residual differs from the free-length one by
// the chord miss times the rolling's Lipschitz constant).
constexpr double kHandOffResidual = 1e-2;
// A run whose chord has no crossing of the circle near its length (a near-tangency: the solution
// ends next to the chord's extremum, and a nearby path's chord may just miss the radius) is handed
// off at its own length when its free-length residual is below kTangentHandOff; the polish, which
// needs no crossing, decides (every reported path's crossing number is counted on it).
constexpr double kTangentHandOff = 1e-3;
// Relative tolerance for "the same solution" between a search result and a polished one.
constexpr double kSearchSameTol = 1e-4;
// Relative tolerances for "same solution" (lengths, G, E) and for "whole number of periods".
constexpr double kSameTol = 1e-7;
constexpr double kWholePeriodTol = 1e-6;
// A path whose length is within kStraightTol (relative) of its chord is the straight segment.
constexpr double kStraightTol = 1e-9;
// Residual bound under which a phase-shifted path still counts as a solution (family test).
constexpr double kFamilyTol = 1e-8;
constexpr int kMaxCrossingsPerStart = 12;
// Shape scan (SearchShape): scan points with a rotation residual up to kScanResidual (rad) start
// a search; near-tangencies count when the chord misses the radius by less than kTangencyMiss.
constexpr double kScanResidual = 1.0;
// The residual a scan point gets where LogNormBound proves it above kScanResidual (no logarithm).
constexpr double kAboveScanResidual = std::numeric_limits<double>::infinity();
constexpr double kTangencyMiss = 0.3;
// Shapes are searched in batches of kShapeBatch (the first one kFirstShapeBatch: the cap is
// unknown until then); between batches the search length shrinks to the cap (times
// 1 + kCapMargin) of the solutions found so far.
constexpr int kFirstShapeBatch = 32;
constexpr int kShapeBatch = 256;
constexpr double kCapMargin = 1e-6;

// TwinSearches: the continuation's step (in the unknowns rate, atanh k, phase, L), its number of
// steps each way, the corrector's tolerance on |H| and its number of steps, and the |g| at which
// a branch is given up.
constexpr double kTwinStep = 0.15;
constexpr int kTwinSteps = 8;
constexpr double kTwinCurveTol = 1e-3;
constexpr int kTwinCorrections = 4;
constexpr double kTwinGiveUp = 1.0;
// The continuation moves by at most kTwinStep per step (a unit tangent; the corrector's steps are
// small), so a twin's start lies within kTwinSteps kTwinStep of its solution's length: the twins of
// a solution longer than the cap by more than twice that are not searched (nothing past the cap
// is reported, and the cap only shrinks as solutions are found).
constexpr double kTwinReach = 2 * kTwinSteps * kTwinStep;
// A search run whose residual is below kDuplicateResidual and whose Gauss-Newton root estimate
// lies within kDuplicateTol (relative) of a solution known before its batch is stopped there: it
// would converge to that solution (docs/paper_notes.md, "General targets", point 8).
constexpr double kDuplicateResidual = 0.1;
constexpr double kDuplicateTol = 3e-3;
// The search's rate and modulus columns are Broyden (secant) updates while the residual is above
// kSecantResidual (two closed-form rollings fewer per Jacobian; docs/paper_notes.md, "General
// targets", points 9 and 10: 0.1 with the search tables; with the closed form 0.1 loses T7's
// 14.27603954, 0.2 and 0.3 keep every solution of the ten targets).
constexpr double kSecantResidual = 0.3;
// A search run stalls when its residual at each of its last two accepted points fell by less than
// a factor kStallRatio while still above kStallFloor: it is stopped there (docs/paper_notes.md,
// "General targets", point 12: such runs end beyond the hand-off or at a nonzero minimum; a root
// reached at a fold, where Newton converges linearly, still halves the residual per step).
constexpr double kStallRatio = 0.95;
constexpr double kStallFloor = 1e-5;
// The valley polish (ValleyPolish) starts from a polish that ended above the tolerance but below
// kValleyResidual; it takes at most kValleySteps secant steps in the rate (each an LM solve of at
// most kValleyInnerIterations in the other unknowns), each within a factor kValleyMaxFactor.
constexpr double kValleyResidual = 1e-5;
constexpr int kValleySteps = 12;
constexpr int kValleyInnerIterations = 15;
constexpr double kValleyMaxFactor = 1.5;

struct Context {
  Eigen::Matrix3d target;  // A1 A0^-1
  double radius;           // |x1 - x0|
  double goal_angle;       // direction of x1 - x0
  double s_limit;
  // Identity target (the shooting there is only a comparison with the enumeration): the starts
  // are shifted by the seed. Any other target: unshifted, the same for every seed.
  bool identity = false;
};

ElasticaParameters ToParameters(PendulumRegime regime, const double* x) {
  ElasticaParameters p;
  p.regime = regime;
  p.rate = x[0];
  p.modulus = std::tanh(x[1]);
  p.phase = x[2];
  p.heading_w = M_PI / 2;  // pendulum frame = plane frame; B supplies the rotation freedom
  return p;
}

struct Evaluation {
  double s = 0.0;     // arc length at the crossing
  double beta = 0.0;  // rotation B = RotationZ(beta)
  Eigen::Vector3d residual = Eigen::Vector3d::Zero();
};

// Whether the closed-form rolling takes e's parameters (finite G and V^2) and arc lengths up to
// s_max (rate s + phase finite): else ElasticaClosedRolling would throw.
bool ClosedFormApplies(const Elastica& e, double s_max) {
  const ElasticaParameters& p = e.parameters();
  return std::abs(p.rate) <= internal::ElasticaClosedRolling::kMaxRate &&
         std::isfinite(std::abs(p.rate) * (std::abs(s_max) + 1.0) + std::abs(p.phase));
}

// The rotation trick of section 2.2 at arc length s of e (the rolling in closed form).
bool EvaluateAt(const Context& ctx, const Elastica& e, double s, Evaluation* out) {
  const Eigen::Vector2d xs = e.Position(s);
  if (xs.norm() == 0.0 || !ClosedFormApplies(e, s)) return false;
  out->s = s;
  out->beta = internal::ChordTurn(ctx.goal_angle, xs);
  out->residual = internal::RotationTrickResidual(ctx.target, out->beta, internal::ElasticaClosedRolling(e).Rolling(s));
  return out->residual.allFinite();
}

// A table of positions only over [0, s_limit] with acc's nodes: the crossings of the circle.
internal::ElasticaRollingTable CrossingTable(const Elastica& e, double s_limit, const Accuracy& acc) {
  return internal::ElasticaRollingTable(e, s_limit, acc.steps_per_period, acc.max_step, 200000, true);
}

// Which crossing of the circle |x - x0| = |x1 - x0| ends a path of the given length (its end lies
// on the circle to the tolerance): 1 + the crossings before it, counted with a proof
// (circle_crossings.h; a pair between two table nodes counts too), up to 1e-9 (1 + length) short
// of the end (the end's own crossing, moved by the residual, is not counted twice).
int CrossingCount(const Context& ctx, const Elastica& e, double length) {
  return 1 + internal::CountCircleCrossings(e, ctx.radius, length - 1e-9 * (1 + length));
}

bool Admissible(const ElasticaParameters& p) {
  return std::isfinite(p.rate) && std::isfinite(p.modulus) && std::isfinite(p.phase) && std::abs(p.modulus) < 1.0;
}

// The rotation trick of section 2.2 at arc length `length` of the elastica with parameters p.
bool Evaluate(const Context& ctx, const ElasticaParameters& p, double length, Evaluation* out) {
  return Admissible(p) && EvaluateAt(ctx, Elastica(p), length, out);
}

// TinySolver's functor call for a residual f.Residual(x, r) of N unknowns and N residuals:
// forward differences (the shifted points by f.Shifted(x, r)); a trial point without a residual
// (no n-th crossing, an invalid modulus) gets NaN, which makes TinySolver reject the step.
template <int N, class F>
bool ForwardDifferences(const F& f, const double* x, double* r, double* jacobian) {
  if (!f.Residual(x, r, jacobian != nullptr)) {
    for (int i = 0; i < N; ++i) r[i] = std::numeric_limits<double>::quiet_NaN();
    return jacobian == nullptr;
  }
  if (jacobian == nullptr) return true;
  for (int j = 0; j < N; ++j) {
    const double h = 1e-6 * (1.0 + std::abs(x[j]));
    double xp[N], rp[N];
    std::copy(x, x + N, xp);
    xp[j] += h;
    if (!f.Shifted(xp, rp)) return false;
    for (int i = 0; i < N; ++i) jacobian[j * N + i] = (rp[i] - r[i]) / h;  // column-major
  }
  return true;
}

struct LocalResult {
  bool converged = false;
  PendulumRegime regime = PendulumRegime::kOscillating;
  double x[3] = {0, 0, 0};
  bool searched = false;  // handed to the polish: within kSearchAccept, or kTangentHandOff at a near-tangency
  bool duplicate = false;  // the search stopped at a solution known before its batch
  Evaluation ev;
  long evaluations = 0;
};

// A known solution in the free-length search's unknowns (rate, atanh k, phase, L).
struct SearchRoot {
  PendulumRegime regime;
  Eigen::Vector4d x;
};

// Whether y (free-length unknowns) is the root `root` to kDuplicateTol: the same regime and
// modulus sign, rate, atanh k and length, the phase modulo the curvature period in u (the path
// from phase u0 and from u0 plus a period is the same).
bool SameRoot(PendulumRegime regime, const Eigen::Vector4d& y, const SearchRoot& root) {
  if (regime != root.regime) return false;
  for (int i : {0, 1, 3})
    if (!(std::abs(y[i] - root.x[i]) <= kDuplicateTol * (1 + std::abs(root.x[i])))) return false;
  const double u_period = (regime == PendulumRegime::kOscillating ? 4.0 : 2.0) *
                          internal::CompleteEllipticK(std::abs(std::tanh(root.x[1])));
  return std::abs(std::remainder(y[2] - root.x[2], u_period)) <= kDuplicateTol * (1 + u_period);
}

// The rotation trick without the crossing: the length L is a fourth unknown and |x(L)| - |x1 - x0|
// a fourth residual. Smooth where the crossing formulation jumps (a tangency adding or removing a
// pair of crossings, near which solutions often lie).
struct FreeLengthFunctor {
  using Scalar = double;
  enum { NUM_RESIDUALS = 4, NUM_PARAMETERS = 4 };
  FreeLengthFunctor(const Context* c, PendulumRegime r) : ctx(c), regime(r) {}
  const Context* ctx;
  PendulumRegime regime;
  mutable long evaluations = 0;
  // Solutions known before this run (nullptr: none checked) and whether the run reached one.
  const std::vector<SearchRoot>* known = nullptr;
  mutable bool duplicate = false;
  bool secant = true;  // SecantColumns allowed (the twin continuation needs the exact columns)
  // Whether a stalled run stops (Stalls: the searches; not the polish or the curve following).
  bool stall_stop = false;
  mutable bool stalled = false;
  mutable double accepted[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  // TinySolver's cost_threshold when this functor drives a TinySolver run (0: none): a point below
  // it ends the run in the Update that asks for its Jacobian, which is then not computed (Converged).
  double cost_threshold = 0.0;

  // Whether the residual r ends the TinySolver run (its test: cost |r|^2 / 2 below the threshold).
  bool Converged(const double* r) const { return Eigen::Map<const Eigen::Vector4d>(r).squaredNorm() / 2 < cost_threshold; }

  bool Admissible(const ElasticaParameters& p, double length) const {
    return std::isfinite(p.rate) && std::isfinite(p.modulus) && std::isfinite(p.phase) && std::isfinite(length) &&
           std::abs(p.modulus) < 1.0 && length > 0 && length <= 2.0 * ctx->s_limit;
  }

  // The residual of a path with chord xs and rolling q.
  bool ResidualOf(const Eigen::Vector2d& xs, const Eigen::Matrix3d& q, double* r) const {
    if (xs.norm() == 0.0) return false;
    const Eigen::Vector3d rot = internal::RotationTrickResidual(ctx->target, internal::ChordTurn(ctx->goal_angle, xs), q);
    r[0] = xs.norm() - ctx->radius;
    for (int i = 0; i < 3; ++i) r[i + 1] = rot[i];
    return rot.allFinite();
  }

  // The residual of the path from 0 to `length` of the rolling's elastica (x(0) = 0), Q(0, L) in
  // closed form; its chord and rolling are kept in `last`.
  bool ResidualFrom(const Elastica& e, const internal::ElasticaClosedRolling& rolling, double length, double* r) const {
    ++evaluations;
    last.end = rolling.Path(e, length);
    return ResidualOf(last.end.chord, last.end.q, r);
  }

  // The residuals of the last path (length L) shifted by s0 along its elastica (the phase shifted
  // by rate s0: chord x(s0 + L) - x(s0), rolling Q(s0, s0 + L)) and lengthened by h, from its chord
  // and rolling and the tangents and curvatures at 0 and L: the chords to second order, the
  // rollings by dQ(s0, s1)/ds1 = hat(w(s1)) Q and dQ/ds0 = -Q hat(w(s0)) (w = e3 x x') with w at
  // the step's midpoint (error O(h^3), as the chord's): the phase and length columns without the
  // two positions and two closed-form rollings they took (docs/paper_notes.md, "General targets",
  // point 12).
  bool ShiftedResiduals(const Elastica& e, double length, double s0, double h, double* rp, double* rl) const {
    Eigen::Vector2d t0, t1;
    double k0 = 0, k1 = 0;
    e.TangentAndCurvature(0.0, &t0, &k0);
    e.TangentAndCurvature(length, &t1, &k1);
    const Eigen::Vector2d n0 = k0 * Eigen::Vector2d(-t0.y(), t0.x()), n1 = k1 * Eigen::Vector2d(-t1.y(), t1.x());
    const auto spin = [](const Eigen::Vector2d& t, double step) { return ExpSO3(step * Eigen::Vector3d(-t.y(), t.x(), 0.0)); };
    const Eigen::Vector2d chord_p = last.end.chord + s0 * (t1 - t0) + 0.5 * s0 * s0 * (n1 - n0);
    const Eigen::Matrix3d q_p = spin(t1 + 0.5 * s0 * n1, s0) * last.end.q * spin(t0 + 0.5 * s0 * n0, -s0);
    const Eigen::Vector2d chord_l = last.end.chord + h * t1 + 0.5 * h * h * n1;
    return ResidualOf(chord_p, q_p, rp) && ResidualOf(chord_l, spin(t1 + 0.5 * h * n1, h) * last.end.q, rl);
  }

  // The last residual evaluated (TinySolver evaluates every accepted point twice: as a trial
  // without Jacobian, then again with it): its point, path, rolling and residual.
  struct LastResidual {
    bool ok = false;
    double x[4] = {0, 0, 0, 0};
    double r[4] = {0, 0, 0, 0};
    std::optional<Elastica> path;  // in place: no allocation per residual
    std::optional<internal::ElasticaClosedRolling> rolling;
    internal::ElasticaClosedRolling::PathEnd end;  // its chord and rolling, and what AnalyticColumns needs
  };
  mutable LastResidual last;

  bool Shifted(const double* x, double* r) const { return Residual(x, r); }

  // `base`: an elastica of x's modulus and phase (another rate), whose rate-free parts the path shares.
  bool Residual(const double* x, double* r, bool = false, const Elastica* base = nullptr) const {
    const ElasticaParameters p = ToParameters(regime, x);
    last.rolling.reset();
    if (!Admissible(p, x[3])) return false;
    if (base != nullptr)
      last.path.emplace(base->WithRate(p.rate));
    else
      last.path.emplace(p);
    if (!ClosedFormApplies(*last.path, 2.0 * ctx->s_limit)) return false;  // every length Admissible takes, and L + h
    last.rolling.emplace(*last.path);
    last.ok = ResidualFrom(*last.path, *last.rolling, x[3], r);
    std::copy(x, x + 4, last.x);
    if (last.ok) std::copy(r, r + 4, last.r);
    return last.ok;
  }

  // Whether the last residual was evaluated at x.
  bool LastAt(const double* x) const { return last.rolling.has_value() && last.ok && std::equal(x, x + 4, last.x); }

  // The residual at x, the last one when it was evaluated there (a run that ended on an accepted point).
  bool ResidualAt(const double* x, double* r) const {
    if (!LastAt(x)) return Residual(x, r);
    std::copy(last.r, last.r + 4, r);
    return true;
  }

  // Forward differences, but one closed-form rolling (one per (rate, k)) serves the residual and
  // the phase and length columns: only the rate and modulus columns build new ones.
  bool operator()(const double* x, double* r, double* jacobian) const {
    if (duplicate || stalled) return StopRun(r, jacobian);
    if (jacobian != nullptr && kept.valid && std::equal(x, x + 4, kept.x)) {  // the triage's last point
      std::copy(kept.r, kept.r + 4, r);
      std::copy(kept.jacobian, kept.jacobian + 16, jacobian);
      return true;
    }
    if (!Evaluate(x, r, jacobian)) return false;
    if (jacobian != nullptr && ReachesKnown(x, r, jacobian)) {
      duplicate = true;
      return StopRun(r, jacobian);
    }
    if (jacobian != nullptr && Stalls(Eigen::Map<const Eigen::Vector4d>(r).norm())) {
      stalled = true;
      return StopRun(r, jacobian);
    }
    if (jacobian != nullptr) {
      kept.valid = true;
      std::copy(x, x + 4, kept.x);
      std::copy(r, r + 4, kept.r);
      std::copy(jacobian, jacobian + 16, kept.jacobian);
    }
    return true;
  }

  // The last Jacobian evaluated (a run resumed after the triage starts at its point).
  struct KeptJacobian {
    bool valid = false;
    double x[4] = {0, 0, 0, 0};
    double r[4] = {0, 0, 0, 0};
    double jacobian[16] = {};
  };
  mutable KeptJacobian kept;

  // Whether the run stalls at an accepted point of residual norm `norm` (TinySolver evaluates the
  // Jacobian exactly at the accepted points): see kStallRatio.
  bool Stalls(double norm) const {
    const bool stall = stall_stop && norm >= kStallFloor && norm > kStallRatio * accepted[1] &&
                       accepted[1] > kStallRatio * accepted[0];
    accepted[0] = accepted[1];
    accepted[1] = norm;
    return stall;
  }

  // A run that reached a known solution (or stalled): a zero residual and Jacobian end TinySolver's loop at
  // once (cost below its threshold); the caller drops the run by `duplicate` (or `stalled`).
  static bool StopRun(double* r, double* jacobian) {
    std::fill(r, r + 4, 0.0);
    if (jacobian != nullptr) std::fill(jacobian, jacobian + 16, 0.0);
    return true;
  }

  // Whether the Gauss-Newton step from x lands on a known solution (only near a root).
  bool ReachesKnown(const double* x, const double* r, const double* jacobian) const {
    if (known == nullptr || known->empty()) return false;
    const Eigen::Map<const Eigen::Vector4d> res(r);
    if (!(res.norm() <= kDuplicateResidual)) return false;
    const Eigen::Map<const Eigen::Matrix4d> jac(jacobian);
    // At a converged point (no Jacobian computed: Converged) the point itself, within kSearchStop
    // of a root, stands for the Gauss-Newton step.
    const Eigen::Vector4d y = Converged(r) ? Eigen::Vector4d(Eigen::Map<const Eigen::Vector4d>(x))
                                           : Eigen::Vector4d(Eigen::Map<const Eigen::Vector4d>(x) - jac.fullPivLu().solve(res));
    if (!y.allFinite()) return false;
    for (const SearchRoot& root : *known)
      if (SameRoot(regime, y, root)) return true;
    return false;
  }

  // Far from a root (|r| > kSecantResidual), the rate and modulus columns by a Broyden update of
  // the last Jacobian of the run (its phase and length columns already replaced by this point's).
  // Not at an identity target: its comparison shooting (random starts, no shape scan) then misses
  // Figure 7's shortest path with 512 starts.
  bool SecantColumns(const double* x, const double* r, double* jacobian) const {
    if (!secant || ctx->identity || !kept.valid || !(Eigen::Map<const Eigen::Vector4d>(r).norm() > kSecantResidual)) return false;
    const Eigen::Map<const Eigen::Matrix4d> old(kept.jacobian);
    const Eigen::Vector4d dx = Eigen::Map<const Eigen::Vector4d>(x) - Eigen::Map<const Eigen::Vector4d>(kept.x);
    const Eigen::Vector4d dr = Eigen::Map<const Eigen::Vector4d>(r) - Eigen::Map<const Eigen::Vector4d>(kept.r);
    const double dx2 = dx.squaredNorm();
    if (!(dx2 > 0)) return false;
    const Eigen::Matrix4d updated = old + (dr - old * dx) * dx.transpose() / dx2;
    Eigen::Map<Eigen::Matrix4d> jac(jacobian);
    jac.leftCols<2>() = updated.leftCols<2>();
    return jac.allFinite();
  }

  // The rate and modulus columns from the closed-form derivatives of the last path's chord and
  // rolling (ElasticaClosedRolling::Sensitivity): the residual of the chord and rolling moved along
  // them by the forward-difference step, like the phase and length columns, without the two
  // elasticas and closed rollings whole-path differences build (docs/paper_notes.md, "General
  // targets", point 12). False where Sensitivity declines (the caller then
  // differences paths).
  bool AnalyticColumns(const double* x, const double* r, double* jacobian) const {
    internal::ElasticaClosedRolling::PathSensitivity sens;
    if (!last.rolling->Sensitivity(last.end, &sens)) return false;
    const double modulus = last.path->parameters().modulus;
    const double dmodulus = (1.0 - modulus) * (1.0 + modulus);  // d tanh(atanh k) / d atanh k
    for (int j = 0; j < 2; ++j) {
      const double h = 1e-6 * (1.0 + std::abs(x[j])), step = j == 0 ? h : h * dmodulus;
      const Eigen::Vector2d chord = last.end.chord + step * (j == 0 ? sens.chord_rate : sens.chord_modulus);
      const Eigen::Matrix3d q = last.end.q * ExpSO3(step * (j == 0 ? sens.spin_rate : sens.spin_modulus));
      double rj[4];
      if (!ResidualOf(chord, q, rj)) return false;
      for (int i = 0; i < 4; ++i) jacobian[j * 4 + i] = (rj[i] - r[i]) / h;
    }
    return true;
  }

  bool Evaluate(const double* x, double* r, double* jacobian) const {
    const ElasticaParameters p = ToParameters(regime, x);
    const double h_phase = 1e-6 * (1.0 + std::abs(x[2])), h_length = 1e-6 * (1.0 + std::abs(x[3]));
    const double s0 = h_phase / std::abs(p.rate);  // phase + sign(rate) h_phase (infinite at rate 0)
    if (jacobian == nullptr || !std::isfinite(s0 + x[3] + h_length) || !Admissible(p, x[3]))
      return ForwardDifferences<4>(*this, x, r, jacobian);
    if (!LastAt(x) && !Residual(x, r)) {  // else the trial's rolling and residual at this point
      for (int i = 0; i < 4; ++i) r[i] = std::numeric_limits<double>::quiet_NaN();
      return false;
    }
    std::copy(last.r, last.r + 4, r);
    if (Converged(r)) {  // the run ends here: TinySolver never uses this Jacobian
      std::fill(jacobian, jacobian + 16, 0.0);
      return true;
    }
    double rp[4], rl[4];
    if (!ShiftedResiduals(*last.path, x[3], s0, h_length, rp, rl)) return false;
    const double signed_phase_step = p.rate > 0 ? h_phase : -h_phase;
    for (int i = 0; i < 4; ++i) {
      jacobian[2 * 4 + i] = (rp[i] - r[i]) / signed_phase_step;
      jacobian[3 * 4 + i] = (rl[i] - r[i]) / h_length;
    }
    if (SecantColumns(x, r, jacobian) || AnalyticColumns(x, r, jacobian)) return true;
    const Elastica path = std::move(*last.path);  // the rate and modulus columns reuse `last`
    last.path.reset();
    last.rolling.reset();
    for (int j = 0; j < 2; ++j) {
      const double h = 1e-6 * (1.0 + std::abs(x[j]));
      double xp[4] = {x[0], x[1], x[2], x[3]}, rj[4];
      xp[j] += h;
      if (!Residual(xp, rj, false, j == 0 ? &path : nullptr)) return false;  // the rate: path's k, K, phase terms
      for (int i = 0; i < 4; ++i) jacobian[j * 4 + i] = (rj[i] - r[i]) / h;
    }
    return true;
  }
};

// Hands a free-length result (length L) to the crossing formulation: the crossing of the circle
// nearest to L on the nodes of the given accuracy over the search length, if within
// kSearchSameTol, and the residual there (at most kSearchAccept).
bool HandOff(const Context& ctx, double length, const Accuracy& acc, LocalResult* r) {
  const ElasticaParameters p = ToParameters(r->regime, r->x);
  if (!Admissible(p)) return false;
  const Elastica e(p);
  const internal::ElasticaRollingTable table = CrossingTable(e, ctx.s_limit, acc);
  double s = 0.0;
  int n = 0;
  if (!table.Valid() ||
      !table.NearestCrossing(ctx.radius, length, kSearchSameTol * (1 + length), kMaxCrossingsPerStart * 4, &n, &s))
    return false;
  return EvaluateAt(ctx, e, s, &r->ev) && r->ev.residual.norm() <= kSearchAccept;
}

// Search stage on the free-length formulation from a start and one of its crossings; the result
// is handed off (at the crossing nearest its length, the residual checked there) to the
// polish. A run that reaches one of the `known` solutions stops there (LocalResult::duplicate), a
// run that stalls (kStallRatio) too.
LocalResult SearchLocalFreeLength(const Context& ctx, PendulumRegime regime, const double* x0, double length0,
                                  const IsoparallelOptions& options, const std::vector<SearchRoot>* known = nullptr) {
  LocalResult out;
  out.regime = regime;
  FreeLengthFunctor f{&ctx, regime};
  f.known = known;
  f.stall_stop = true;
  Eigen::Vector4d v(x0[0], x0[1], x0[2], length0);
  ceres::TinySolver<FreeLengthFunctor> solver;
  solver.options.max_num_iterations = std::min(options.max_iterations, kSearchIterations);
  solver.options.gradient_tolerance = 0.0;
  solver.options.parameter_tolerance = 1e-15;
  solver.options.function_tolerance = 0.0;
  solver.options.cost_threshold = 0.5 * kSearchStop * kSearchStop;
  f.cost_threshold = solver.options.cost_threshold;
  double r0[4];
  if (f.Residual(v.data(), r0)) {
    // A run still far from a root after a few iterations is abandoned (such runs rarely
    // converge; their solutions are reached from other starts).
    const int total = solver.options.max_num_iterations;
    const double hopeless = kHopelessResidual;
    const int triage = kTriageIterations;
    solver.options.max_num_iterations = std::min(total, triage);
    solver.Solve(f, &v);
    if (v.allFinite() && solver.summary.final_cost > 0.5 * kSearchStop * kSearchStop &&
        solver.summary.final_cost <= 0.5 * hopeless * hopeless && total > triage) {
      solver.options.max_num_iterations = total - triage;
      solver.Solve(f, &v);
    }
  }
  out.evaluations = f.evaluations;
  out.duplicate = f.duplicate;
  std::copy(v.data(), v.data() + 3, out.x);
  if (out.duplicate || f.stalled) return out;
  if (!v.allFinite() || !(v[3] > 0) || std::abs(std::tanh(v[1])) >= 1.0) return out;
  // Runs that stopped far from a root are not handed off (the hand-off's tables over the whole
  // search length were a fifth of the time on the rotation problem, mostly spent on such runs).
  const double cost = solver.summary.final_cost;
  if (!(cost >= 0 && cost <= 0.5 * kHandOffResidual * kHandOffResidual)) return out;
  // The crossing formulation's n: the crossing nearest to L on the search table, else on the
  // polish table (a near-tangency, the chord just reaching the radius between two coarse nodes).
  out.searched = HandOff(ctx, v[3], kSearch, &out) || HandOff(ctx, v[3], kPolish, &out);
  if (!out.searched && !ctx.identity && std::sqrt(2 * cost) <= kTangentHandOff &&  // cf. PolishLocal
      Evaluate(ctx, ToParameters(regime, v.data()), v[3], &out.ev)) {
    out.searched = true;
  }
  return out;
}

// The free-length residual at a fixed rate, in the other three unknowns (atanh k, phase, L).
struct FixedRateFunctor {
  using Scalar = double;
  enum { NUM_RESIDUALS = 4, NUM_PARAMETERS = 3 };
  const FreeLengthFunctor* f;
  double rate;
  bool operator()(const double* y, double* r, double* jacobian) const {
    const double x[4] = {rate, y[0], y[1], y[2]};
    double full[16];
    if (!f->Evaluate(x, r, jacobian != nullptr ? full : nullptr)) return false;
    if (jacobian != nullptr) std::copy(full + 4, full + 16, jacobian);  // column-major: drop the rate's
    return true;
  }
};

// The rest of the residual after an LM solve in (atanh k, phase, L) at the given rate (y: the
// start, then the solve's point); false where it is not finite.
bool SolveAtRate(const FreeLengthFunctor& f, double rate, Eigen::Vector3d* y, Eigen::Vector4d* r) {
  const FixedRateFunctor g{&f, rate};
  ceres::TinySolver<FixedRateFunctor> solver;
  solver.options.max_num_iterations = kValleyInnerIterations;
  solver.options.gradient_tolerance = 0.0;
  solver.options.parameter_tolerance = 1e-15;
  solver.options.function_tolerance = 0.0;
  solver.Solve(g, y);
  return y->allFinite() && g(y->data(), r->data(), nullptr) && r->allFinite();
}

// Valley polish, for a polish that stalls near the straight rolling (docs/paper_notes.md, "General
// targets: the valley of nearly straight short arcs"): a short arc near a turning point of the
// heading is fixed to second order by two curvature moments, so the residual is ~1e-9 along a
// whole curve of (rate, k, phase) and Newton's step along it is noise. Along that curve the rate
// is the coordinate: at each rate the other three unknowns are solved by LM, the residual left
// over keeps its direction u, and the secant method finds the rate where u.r vanishes. The point
// reached is handed back to the polish (true), or false when the secant leaves the rate's sign or
// a solve fails.
bool ValleyPolish(const FreeLengthFunctor& f, Eigen::Vector4d* v) {
  Eigen::Vector3d y = v->tail<3>();
  Eigen::Vector4d r;
  if (!SolveAtRate(f, (*v)[0], &y, &r) || r.norm() == 0.0) return false;
  const Eigen::Vector4d u = r.normalized();
  double a = (*v)[0], ga = u.dot(r), b = a * (1 + 2e-2);
  Eigen::Vector3d yb = y;
  if (!SolveAtRate(f, b, &yb, &r)) return false;
  double gb = u.dot(r);
  for (int step = 0; step < kValleySteps && gb != ga && std::abs(b - a) > 1e-15 * std::abs(b); ++step) {
    // The secant step, within a factor kValleyMaxFactor of b: the rate keeps its sign.
    const double near = b / kValleyMaxFactor, far = b * kValleyMaxFactor;
    const double c = std::clamp(b - gb * (b - a) / (gb - ga), std::min(near, far), std::max(near, far));
    if (!std::isfinite(c)) return false;
    a = b;
    ga = gb;
    b = c;
    if (!SolveAtRate(f, b, &yb, &r)) return false;
    gb = u.dot(r);
  }
  *v << b, yb;
  return true;
}

// Polish stage: LM (in effect Newton) on the free-length formulation with exact Jacobians (no
// Broyden columns), from the handed-off point (the search's parameters, L at its crossing), to
// options.tolerance on all four residuals: the chord miss and the rotation residual there (the
// crossing number is counted on the reported path: CrossingCount). (The crossing formulation's
// polish found the crossing on a table of positions over the whole search length at kPolish
// nodes, ~250,000 instructions per evaluation against ~7,000 here: 170M of the rotation problem's
// 1.76G; the roots are the same to the tolerance, the same 31 lengths to 10 digits;
// docs/paper_notes.md, "General targets", point 12.)
void PolishLocal(const Context& ctx, const IsoparallelOptions& options, LocalResult* r) {
  FreeLengthFunctor f{&ctx, r->regime};
  f.secant = false;
  Eigen::Vector4d v(r->x[0], r->x[1], r->x[2], r->ev.s);
  ceres::TinySolver<FreeLengthFunctor> solver;
  // options.max_iterations (default 100), no smaller cap: near the straight rolling the search ends
  // where the Jacobian is nearly singular and Newton needs 13-100 steps; with 12, 6 of 60 random
  // targets made from short paths lost their optimum (1 with 100), while on the ten targets no
  // polish needs more (the same lists and evaluations; docs/paper_notes.md, "General targets: the
  // whole certificate in one call").
  solver.options.max_num_iterations = options.max_iterations;
  solver.options.gradient_tolerance = 0.0;
  solver.options.parameter_tolerance = 1e-15;
  solver.options.function_tolerance = 0.0;
  solver.options.cost_threshold = 0.5 * std::pow(0.1 * options.tolerance, 2);
  f.cost_threshold = solver.options.cost_threshold;
  solver.Solve(f, &v);
  double res[4];
  const auto residual = [&]() {
    return v.allFinite() && f.ResidualAt(v.data(), res) ? Eigen::Map<const Eigen::Vector4d>(res).norm() : NAN;
  };
  double norm = residual();
  // Not at an identity target: every solution there is a family (a phase shift), its polishes
  // stall on that degeneracy, and its shooting is only a comparison with the enumeration.
  if (!ctx.identity && norm > options.tolerance && norm < kValleyResidual && ValleyPolish(f, &v)) {
    solver.Solve(f, &v);
    norm = residual();
  }
  r->converged = norm <= options.tolerance;
  r->evaluations += f.evaluations;
  if (!r->converged) return;
  std::copy(v.data(), v.data() + 3, r->x);
  r->converged = Evaluate(ctx, ToParameters(r->regime, r->x), v[3], &r->ev);
}

// Radical-inverse (Halton): deterministic, portable.
double Halton(long index, int base) {
  double f = 1.0, r = 0.0;
  for (long i = index; i > 0; i /= base) {
    f /= base;
    r += f * static_cast<double>(i % base);
  }
  return r;
}

struct Start {
  PendulumRegime regime;
  double x[3];
};

// The first options.starts points of the Halton sequence (bases 2, 3, 5, 7). General targets:
// unshifted shapes (phase 0: SearchShape scans the phase), so the solution list does not depend
// on the seed; identity target (shooting only as a comparison with the enumeration): starts with
// a Cranley-Patterson shift drawn from the seed.
std::vector<Start> MakeStarts(const IsoparallelOptions& options, double s_limit, double radius, bool seeded,
                              bool shapes) {
  std::mt19937_64 rng(options.seed);
  auto unit = [&rng]() { return static_cast<double>(rng() >> 11) * 0x1.0p-53; };
  double shift[4] = {0, 0, 0, 0};
  if (seeded)
    for (double& v : shift) v = unit();
  std::vector<Start> starts;
  // Curvature periods from a tenth of the chord to twice the longest path searched.
  const double t_min = std::max(0.25, 0.1 * radius), t_max = 2.0 * s_limit;
  for (int i = 0; i < options.starts; ++i) {
    double u[4];
    const int bases[4] = {2, 3, 5, 7};
    for (int d = 0; d < 4; ++d) u[d] = std::fmod(Halton(i + 1, bases[d]) + shift[d], 1.0);
    Start s;
    // u0: regime and sense (two quarters each).
    s.regime = u[0] < 0.5 ? PendulumRegime::kOscillating : PendulumRegime::kRotating;
    const double sign = std::fmod(2.0 * u[0], 1.0) < 0.5 ? 1.0 : -1.0;
    // Shapes: denser towards the separatrix (k = 0.97 sin(pi u / 2)), where long solutions have
    // narrow basins in atanh k; starts: uniform in k.
    const double k = shapes ? 0.97 * std::sin(0.5 * M_PI * u[2]) : 0.97 * u[2];
    const double kk = internal::CompleteEllipticK(k);
    const double period = t_min * std::pow(t_max / t_min, u[1]);
    const double u_period = s.regime == PendulumRegime::kOscillating ? 4.0 * kk : 2.0 * kk;
    s.x[0] = sign * u_period / period;
    s.x[1] = std::atanh(k);
    s.x[2] = shapes ? 0.0 : u[3] * u_period;
    starts.push_back(s);
  }
  return starts;
}

struct Candidate {
  IsoparallelSolution solution;
  std::vector<Eigen::Vector2d> signature;  // world positions at s = L/3, 2L/3
};

// Length, G, E and world-frame signature of a search result, without the family test.
Candidate MakeRoughCandidate(const Context&, const IsoparallelProblem& problem, const LocalResult& r) {
  Candidate c;
  ElasticaParameters p = ToParameters(r.regime, r.x);
  const Elastica e(p);
  c.solution.length = r.ev.s;
  c.solution.G = e.G();
  c.solution.energy = e.Energy();
  p.heading_w += r.ev.beta;
  c.solution.parameters = p;
  c.solution.start = problem.start;
  c.signature = {c.solution.PositionAt(r.ev.s / 3), c.solution.PositionAt(2 * r.ev.s / 3)};
  return c;
}

// The straight segment from start to goal (p with rate 0, heading along the chord), as a solution
// of the given length (the chord) and residual.
Candidate StraightCandidate(const Context& ctx, const IsoparallelProblem& problem, ElasticaParameters p, double length,
                            double residual) {
  Candidate c;
  IsoparallelSolution& sol = c.solution;
  p.rate = 0.0;
  p.modulus = 0.0;
  p.heading_w = ctx.goal_angle + M_PI / 2;
  sol.parameters = p;
  sol.length = length;
  sol.shooting_residual = residual;
  sol.start = problem.start;
  c.signature = {sol.PositionAt(sol.length / 3), sol.PositionAt(2 * sol.length / 3)};
  return c;
}

// Builds the reported solution from a converged local result: world frame, family test. A result
// as long as the chord (to kStraightTol) is the straight segment: only a straight path is as
// short as its chord, and the shooting's parameters degenerate there (modulus -> 0 with any rate
// and phase: every such run polishes to a slightly different near-straight path, once listed
// several times). When the segment itself solves the target to `tolerance`, it is reported
// instead, the same candidate for every such run.
Candidate MakeCandidate(const Context& ctx, const IsoparallelProblem& problem, const LocalResult& r, double tolerance) {
  if (std::abs(r.ev.s - ctx.radius) <= kStraightTol * (1 + ctx.radius)) {
    const double residual =
        LogSO3(ctx.target.transpose() * RollAlongSegment(problem.start, problem.goal)).norm();
    if (residual <= tolerance) return StraightCandidate(ctx, problem, ElasticaParameters{}, ctx.radius, residual);
  }
  Candidate c;
  IsoparallelSolution& sol = c.solution;
  ElasticaParameters p = ToParameters(r.regime, r.x);
  Evaluation ev = r.ev;
  const Elastica e(p);
  sol.length = ev.s;
  sol.G = e.G();
  sol.energy = e.Energy();
  sol.periods = e.IsStraight() ? 0.0 : ev.s / e.Period();
  const double whole = std::round(sol.periods);
  if (!e.IsStraight() && whole >= 1 && std::abs(sol.periods - whole) < kWholePeriodTol * whole) {
    // Family test: shift the starting phase, keep the length (a whole number of periods).
    const double u_period = (r.regime == PendulumRegime::kOscillating ? 2.0 : 1.0) * 2.0 *
                            internal::CompleteEllipticK(std::abs(p.modulus));
    bool family = true;
    for (double frac : {0.31, 0.67}) {
      ElasticaParameters q = p;
      q.phase += frac * u_period;
      Evaluation evq;
      if (!Evaluate(ctx, q, ev.s, &evq) || evq.residual.norm() > kFamilyTol) family = false;
    }
    if (family) {
      ElasticaParameters q = p;
      q.phase = 0.0;  // canonical member
      Evaluation evq;
      if (Evaluate(ctx, q, ev.s, &evq)) {
        sol.family = true;
        p = q;
        ev = evq;
      }
    }
  }
  sol.shooting_residual = ev.residual.norm();
  p.heading_w += ev.beta;
  sol.parameters = p;
  sol.start = problem.start;
  c.signature = {sol.PositionAt(sol.length / 3), sol.PositionAt(2 * sol.length / 3)};
  return c;
}

// `a` is a known (polished) candidate; `b` a new one, possibly rough (family not yet tested).
bool SameSolution(const Candidate& a, const Candidate& b, double tol) {
  const IsoparallelSolution &x = a.solution, &y = b.solution;
  const double scale = 1.0 + x.length;
  if (std::abs(x.length - y.length) > tol * scale) return false;
  if (x.family) {
    const bool rot_x = x.parameters.regime == PendulumRegime::kRotating;
    const bool rot_y = y.parameters.regime == PendulumRegime::kRotating;
    if (rot_x != rot_y) return false;
    if (rot_x && (x.parameters.rate > 0) != (y.parameters.rate > 0)) return false;
    return std::abs(x.G - y.G) <= tol * (1 + x.G) && std::abs(x.energy - y.energy) <= tol * (1 + std::abs(x.energy));
  }
  if (y.family) return false;
  for (std::size_t i = 0; i < a.signature.size(); ++i)
    if ((a.signature[i] - b.signature[i]).norm() > tol * scale) return false;
  return true;
}

void ValidateProblem(const IsoparallelProblem& problem) {
  internal::RequireCoordinates("start", problem.start);
  internal::RequireCoordinates("goal", problem.goal);
  internal::RequireFinite("start_orientation", problem.start_orientation);
  internal::RequireFinite("goal_orientation", problem.goal_orientation);
  const double chord = (problem.goal - problem.start).norm();
  if (chord == 0.0) internal::ThrowInvalid("goal", "(equal to start)", "the isoparallel rotation trick needs |x1 - x0| > 0");
  if (chord > internal::kMaxIsoparallelChord)  // the family search grows like chord^3 (README, "Limits")
    internal::ThrowInvalid("goal", chord, "|goal - start| must be <= " + internal::FormatNumber(internal::kMaxIsoparallelChord));
  if (!IsRotation(problem.start_orientation, 1e-9))
    internal::ThrowInvalid("start_orientation", "(matrix)", "not a rotation matrix (R^T R = I, det R = 1 to 1e-9)");
  if (!IsRotation(problem.goal_orientation, 1e-9))
    internal::ThrowInvalid("goal_orientation", "(matrix)", "not a rotation matrix (R^T R = I, det R = 1 to 1e-9)");
}

// A reported solution from an enumerated family (sense = +-1: the mirror image of a rotating
// family), rotated so that its end lands on the goal.
Candidate FamilyCandidate(const Context& ctx, const IsoparallelProblem& problem, const ElasticaFamily& f, double sense) {
  Candidate c;
  IsoparallelSolution& sol = c.solution;
  ElasticaParameters p = f.Parameters();
  p.rate *= sense;
  sol.length = f.length;
  sol.shooting_residual = f.residual;
  sol.start = problem.start;
  if (f.periods == 0) return StraightCandidate(ctx, problem, p, f.length, f.residual);  // chord a multiple of 2 pi
  const Elastica e(p);
  sol.G = e.G();
  sol.energy = e.Energy();
  sol.periods = f.periods;
  sol.family = true;
  const Eigen::Vector2d drift = e.DriftPerPeriod();
  p.heading_w += internal::ChordTurn(ctx.goal_angle, drift);
  sol.parameters = p;
  c.signature = {sol.PositionAt(sol.length / 3), sol.PositionAt(2 * sol.length / 3)};
  return c;
}

// Identity target: every solution is a family (isoparallel_families.h); enumerate them.
std::vector<Candidate> SolveByFamilies(Context* ctx, const IsoparallelProblem& problem,
                                       const IsoparallelOptions& options, IsoparallelSummary* summary) {
  FamilySearchOptions fo;
  fo.length_cap_factor = options.length_cap_factor;
  fo.tolerance = options.tolerance;
  fo.threads = options.threads;
  if (options.progress) fo.progress = [&options](int m) { options.progress(m, 0); };
  FamilySearch search;
  for (int pass = 0; pass < 4; ++pass) {
    fo.max_length = ctx->s_limit;
    search = EnumerateIdentityFamilies(ctx->radius, fo);
    summary->evaluations += search.evaluations;
    if (!search.families.empty() || options.max_length > 0) break;
    ctx->s_limit *= 2.0;  // nothing this short: search longer paths
  }
  summary->method = IsoparallelMethod::kFamilyEnumeration;
  summary->complete = search.complete;
  summary->periods_searched = search.periods_searched;
  std::vector<Candidate> found;
  for (const ElasticaFamily& f : search.families) {
    found.push_back(FamilyCandidate(*ctx, problem, f, 1.0));
    if (f.regime == PendulumRegime::kRotating) found.push_back(FamilyCandidate(*ctx, problem, f, -1.0));
  }
  ctx->s_limit = search.families.empty() ? ctx->s_limit : search.searched_length;
  return found;
}

// The search context: the target reorientation, the circle of the rotation trick and the
// first search length.
Context MakeContext(const IsoparallelProblem& problem, const IsoparallelOptions& options) {
  Context ctx;
  ctx.target = problem.goal_orientation * problem.start_orientation.transpose();
  const Eigen::Vector2d chord = problem.goal - problem.start;
  ctx.radius = chord.norm();
  ctx.goal_angle = std::atan2(chord.y(), chord.x());
  // Automatic search length: the cap factor times a multiple of the chord long enough to turn
  // the ball through any angle (a loop of length 2 pi rolls it through a full turn).
  ctx.s_limit = options.max_length > 0 ? options.max_length
                                       : options.length_cap_factor * std::max(2.0 * ctx.radius, ctx.radius + 2 * M_PI);
  return ctx;
}

// Runs search(i) for the starts or shapes i in [first, first + count) of `total` on the option's
// threads (results per index do not depend on the thread count) and reports progress.
template <class Search>
std::vector<std::vector<LocalResult>> SearchAll(int first, int count, int total, const IsoparallelOptions& options,
                                                Search&& search) {
  std::vector<std::vector<LocalResult>> results(count);
  std::mutex progress_mutex;
  int done = first;
  internal::ParallelFor(count, options.threads, [&](int i) {
    results[i] = search(first + i);
    if (options.progress) {
      std::lock_guard<std::mutex> lock(progress_mutex);
      options.progress(++done, total);
    }
  });
  return results;
}

// Local searches from every start, over the crossings beyond `covered` (the identity target's
// comparison shooting).
std::vector<std::vector<LocalResult>> SearchStarts(const Context& ctx, const IsoparallelOptions& options,
                                                   double covered) {
  const std::vector<Start> starts = MakeStarts(options, ctx.s_limit, ctx.radius, ctx.identity, false);
  const int n = static_cast<int>(starts.size());
  return SearchAll(0, n, n, options, [&](int i) {
    const Start& st = starts[i];
    const Elastica e(ToParameters(st.regime, st.x));
    const internal::ElasticaRollingTable table = CrossingTable(e, ctx.s_limit, kSearch);
    std::vector<LocalResult> out;
    for (double crossing : table.Crossings(ctx.radius, kMaxCrossingsPerStart))
      if (crossing > covered) out.push_back(SearchLocalFreeLength(ctx, st.regime, st.x, crossing, options));
    return out;
  });
}

// A shape's table in the form the scan reads it: the node positions, and the rolling at a node
// on demand as a unit quaternion (Q(0, i h) = Q(0, j h) P^n, i = n N + j, a table of quaternions:
// ElasticaRollingTable::NodeQuaternion).
struct ShapeNodes {
  const internal::ElasticaRollingTable* table;
  std::vector<Eigen::Quaterniond> powers;
  std::vector<Eigen::Vector2d> x;
  Eigen::Quaterniond target_conj;
  internal::GoalDirection goal;
  internal::LogNormBound bound{kScanResidual};
};

// The rotation (a quaternion) whose log is the residual of the path from node i0 to node i of a
// shape's table (the rotation trick with B from the chord's direction; q0c = Q(0, s0)'s conjugate,
// Q(s0, s) = Q(0, s) Q(0, s0)^T).
Eigen::Quaterniond NodeResidualRotation(const ShapeNodes& nodes, const Eigen::Quaterniond& q0c, long i0, long i) {
  return internal::ChordQuaternion(nodes.target_conj, nodes.goal, nodes.x[i] - nodes.x[i0],
                                   nodes.table->NodeQuaternion(i, nodes.powers) * q0c);
}

// |residual| of a crossing between nodes i0 + l - 1 and i0 + l (interpolated with weight t on the
// later node; node i0 + 1's alone for l = 1), +infinity where LogNormBound proves it above
// kScanResidual (SearchShape reads no residual beyond it, and such a neighbour never undercuts one
// below it), without the logarithms.
double CrossingResidual(const ShapeNodes& nodes, const Eigen::Quaterniond& q0c, long i0, long l, double t) {
  const Eigen::Quaterniond a = NodeResidualRotation(nodes, q0c, i0, i0 + l);
  if (l == 1) return nodes.bound.Exceeds(a) ? kAboveScanResidual : internal::QuaternionLog(a).norm();
  const Eigen::Quaterniond b = NodeResidualRotation(nodes, q0c, i0, i0 + l - 1);
  if (nodes.bound.InterpolationExceeds(a, b)) return kAboveScanResidual;
  return (t * internal::QuaternionLog(a) + (1 - t) * internal::QuaternionLog(b)).norm();
}

// A point of a shape's (s0, L) scan where the chord |x(s0 + L) - x(s0)| crosses the radius
// |x1 - x0| (or comes within kTangencyMiss of it at a node, a near-tangency).
struct ScanPoint {
  double length = 0.0;
  double residual = 0.0;  // |rotation residual| (interpolated between nodes), with the chord miss
};

// A shape's scan: the points of row i0 (start node s0 = i0 h) are points[row_end[i0 - 1] ..
// row_end[i0]) (row_end[-1] = 0), in order of L.
struct ShapeScan {
  std::vector<ScanPoint> points;
  std::vector<std::size_t> row_end;
  double step = 0.0;
  std::size_t RowBegin(long i0) const { return i0 == 0 ? 0 : row_end[i0 - 1]; }
  std::size_t RowSize(long i0) const { return row_end[i0] - RowBegin(i0); }
};

// One row of the scan: start node i0, lengths up to node l_end; `limit` is the search length.
// While |chord| at node l exceeds the near-tangency band's outer edge (radius + kTangencyMiss,
// loosened as the band test is by 1e-9) by more than reach[k] (ChordReach), or falls below its
// inner edge by more, nodes l - 1 .. l + k lie outside the band on the same side of the radius:
// no crossing between them and no near-tangency at them, and the k nodes after l are skipped (the
// row resumes with the crossing between nodes l + k and l + k + 1 and the extremum test at l + k).
// Elsewhere the squared chord against precomputed bounds decides, with a square root only where a
// skip or an event is possible.
// Not inlined: ScanShape's loop over rows would crowd its registers (the node loop spills).
constexpr long kMinSkip = 3;  // ScanRow: the fewest nodes a skip is tried for
[[gnu::noinline]] void ScanRow(const Context& ctx, const ShapeNodes& nodes, const std::vector<double>& reach,
                               double h, long i0, long l_end, double limit, std::vector<ScanPoint>* row) {
  const std::vector<Eigen::Vector2d>& x = nodes.x;
  const Eigen::Quaterniond q0c = nodes.table->NodeQuaternion(i0, nodes.powers).conjugate();
  const Eigen::Vector2d x0 = x[i0];
  const double r2 = ctx.radius * ctx.radius, far = ctx.radius + kTangencyMiss, near = ctx.radius - kTangencyMiss;
  // The band (loosened by 1e-9) where an extremum is a near-tangency; chords beyond its edges
  // (loosened by 1e-9 more) by more than reach[k] stay out of it for k nodes; squared chords beyond
  // which a skip of kMinSkip nodes is possible.
  const double band_lo = near > 0 ? near * near * (1 - 1e-9) : -1.0, band_hi = far * far * (1 + 1e-9);
  const double out_edge = far * (1 + 1e-9), in_edge = near * (1 - 1e-9);
  const double skip_out = (out_edge + reach[kMinSkip]) * (out_edge + reach[kMinSkip]);
  const double skip_in = in_edge - reach[kMinSkip] > 0 ? (in_edge - reach[kMinSkip]) * (in_edge - reach[kMinSkip]) : -1.0;
  const std::size_t first = row->size();
  double f_prev = -r2, f_prev2 = -r2;  // |chord|^2 - radius^2 at the two previous nodes
  for (long l = 1; l <= l_end; ++l) {
    double f = (x[i0 + l] - x0).squaredNorm() - r2;
    if ((f + r2 > skip_out && f_prev > 0) || (f + r2 < skip_in && f_prev < 0)) {
      const double c = std::sqrt(f + r2), gap = f > 0 ? c - out_edge : in_edge - c;
      // reach[k] < gap for k <= skip, and the row's end not passed.
      const long skip = std::min(internal::ReachSkip(reach, gap, h), l_end - l - 2);
      if (skip > 0) {  // resume with the two nodes before the next one
        l += skip;
        f_prev2 = (x[i0 + l - 1] - x0).squaredNorm() - r2;
        f_prev = (x[i0 + l] - x0).squaredNorm() - r2;
        ++l;
        f = (x[i0 + l] - x0).squaredNorm() - r2;
      }
    }
    if ((f > 0) != (f_prev > 0)) {
      const double t = f_prev / (f_prev - f);  // linear interpolation between the nodes
      if ((l - 1 + t) * h > limit) break;
      row->push_back({(l - 1 + t) * h, CrossingResidual(nodes, q0c, i0, l, t)});
      if (row->size() - first >= static_cast<std::size_t>(kMaxCrossingsPerStart)) break;
    } else if (l >= 2 && f_prev + r2 > band_lo && f_prev + r2 < band_hi &&
               ((f_prev > f_prev2 && f_prev >= f && f_prev < 0) || (f_prev < f_prev2 && f_prev <= f && f_prev > 0))) {
      const double miss = std::sqrt(f_prev + r2) - ctx.radius;  // an extremum at node l - 1
      if (std::abs(miss) < kTangencyMiss) {
        const Eigen::Quaterniond a = NodeResidualRotation(nodes, q0c, i0, i0 + l - 1);
        const double r = nodes.bound.Exceeds(a) ? kAboveScanResidual : internal::QuaternionLog(a).norm();
        row->push_back({(l - 1) * h, std::hypot(miss, r)});
      }
    }
    f_prev2 = f_prev;
    f_prev = f;
  }
}

// The (s0, L) scan of one shape (rate, k; phase 0): ONE rolling table over [0, T + s_limit], and
// for every start node s0 = i0 h of one period (a whole-period shift gives the same path) the
// crossings and near-tangencies of the chord along L <= s_limit, from the table's nodes only
// (Q(s0, s0 + L) = Q(0, s0 + L) Q(0, s0)^-1).
ShapeScan ScanShape(const Context& ctx, const Elastica& e) {
  ShapeScan scan;
  if (e.IsStraight() || !std::isfinite(e.Period())) return scan;
  const internal::ElasticaRollingTable table(e, ctx.s_limit + e.Period(), kSearch.steps_per_period, kSearch.max_step,
                                             200000, internal::TableRotations::kQuaternions);
  if (!table.Valid()) return scan;
  ShapeNodes nodes{&table, table.MonodromyQuaternionPowers(), {}, Eigen::Quaterniond(ctx.target).conjugate(),
                   {std::cos(ctx.goal_angle), std::sin(ctx.goal_angle)}};
  table.NodePositions(&nodes.x);
  const double h = table.Step();
  scan.step = h;
  const long last = static_cast<long>(nodes.x.size()) - 1;
  // The rows' last node: the first l with (l - 1) h >= s_limit, less one.
  long l_limit = std::max(1L, static_cast<long>(ctx.s_limit / h) - 2);
  while ((l_limit - 1) * h < ctx.s_limit) ++l_limit;
  --l_limit;
  const std::vector<double> reach = internal::ChordReach(nodes.x, table.Steps(), l_limit + 3, h);
  scan.row_end.reserve(table.Steps());
  scan.points.reserve(2 * table.Steps());  // about two points a row on the rotation problem
  for (long i0 = 0; i0 < table.Steps(); ++i0) {
    ScanRow(ctx, nodes, reach, h, i0, std::min(last - i0, l_limit), ctx.s_limit, &scan.points);
    scan.row_end.push_back(scan.points.size());
  }
  return scan;
}

// Search from one shape: every scan point with a residual below kScanResidual that is a local
// minimum over s0 (against the point of the same index in the two neighbouring rows, cyclic)
// starts the free-length search with phase rate s0 and length L.
std::vector<LocalResult> SearchShape(const Context& ctx, const Start& shape, const IsoparallelOptions& options,
                                     double covered, const std::vector<SearchRoot>& known) {
  std::vector<LocalResult> out;
  const ShapeScan scan = ScanShape(ctx, Elastica(ToParameters(shape.regime, shape.x)));
  const long n_rows = static_cast<long>(scan.row_end.size());
  for (long i0 = 0; i0 < n_rows; ++i0) {
    for (std::size_t n = 0; n < scan.RowSize(i0); ++n) {
      const ScanPoint& p = scan.points[scan.RowBegin(i0) + n];
      if (p.residual > kScanResidual || p.length <= covered) continue;
      bool minimum = true;
      for (long d : {-1L, 1L}) {
        const long nb = (i0 + d + n_rows) % n_rows;
        if (n < scan.RowSize(nb) && scan.points[scan.RowBegin(nb) + n].residual < p.residual) minimum = false;
      }
      if (!minimum) continue;
      const double x[3] = {shape.x[0], shape.x[1], shape.x[0] * i0 * scan.step};
      out.push_back(SearchLocalFreeLength(ctx, shape.regime, x, p.length, options, &known));
    }
  }
  return out;
}

bool Known(const std::vector<Candidate>& found, const Candidate& c, double tol) {
  for (const Candidate& f : found)
    if (SameSolution(f, c, tol)) return true;
  return false;
}

// The twin continuation (TwinSearches): from a solution x*, the curve H(x) = W^T F(x) = 0 (the
// free-length residual F without its component along u, the left singular vector of the smallest
// singular value of J(x*); W the other three) is followed through x* in both directions, and a root
// of F is where g = u.F changes sign along it.
struct CurvePoint {
  Eigen::Vector4d x, r;
  Eigen::Matrix4d jac;
};
using CurveFrame = Eigen::Matrix<double, 4, 3>;

// det [W^T J; t^T]: its sign orients a tangent t of the curve.
double TangentOrientation(const CurveFrame& w, const Eigen::Matrix4d& jac, const Eigen::Vector4d& t) {
  Eigen::Matrix4d m;
  m.topRows<3>() = w.transpose() * jac;
  m.row(3) = t.transpose();
  return m.determinant();
}

// The unit tangent of the curve at a point (the null vector of W^T J), oriented so that
// det [W^T J; t^T] has the sign `orientation`: the same orientation all along the branch, also
// through a turning point in one of the unknowns, where the tangent turns by more than a right
// angle within a step and its dot product with the previous tangent is no guide (T4's pair).
Eigen::Vector4d CurveTangent(const CurveFrame& w, const Eigen::Matrix4d& jac, double orientation) {
  const Eigen::Matrix<double, 3, 4> a = w.transpose() * jac;
  const Eigen::JacobiSVD<Eigen::Matrix<double, 3, 4>> svd(a, Eigen::ComputeFullV);
  const Eigen::Vector4d t = svd.matrixV().col(3);
  return TangentOrientation(w, jac, t) * orientation < 0 ? -t : t;
}

// Corrector: minimum-norm Newton steps on H from y (false: |H| still above kTwinCurveTol after
// kTwinCorrections steps), the first with the Jacobian `previous` of the last curve point (one
// residual), the others with the Jacobian where they start: next to a tangency of the chord with
// the circle (where fold pairs sit) it changes quickly along L. `out` gets the Jacobian at the end.
bool CorrectOntoCurve(const FreeLengthFunctor& f, const CurveFrame& w, const Eigen::Matrix4d& previous,
                      Eigen::Vector4d y, CurvePoint* out) {
  out->jac = previous;
  for (int i = 0;; ++i) {
    const bool fresh = i > 0;
    if (!(fresh ? f(y.data(), out->r.data(), out->jac.data()) : f.Residual(y.data(), out->r.data()))) return false;
    if (!out->r.allFinite() || !out->jac.allFinite()) return false;
    const Eigen::Vector3d h = w.transpose() * out->r;
    if (h.norm() <= kTwinCurveTol) {
      if (!fresh && (!f(y.data(), out->r.data(), out->jac.data()) || !out->jac.allFinite())) return false;
      break;
    }
    if (i == kTwinCorrections) return false;
    const Eigen::Matrix<double, 3, 4> a = w.transpose() * out->jac;
    y -= a.transpose() * (a * a.transpose()).ldlt().solve(h);
  }
  out->x = y;
  return true;
}

// Follows the curve from x* (`start`) along `direction` (+-v) for up to kTwinSteps steps; where
// g = u.F changes sign, the point interpolated between the two curve points is a start for the
// twin's search (true).
bool FollowCurve(const FreeLengthFunctor& f, const CurveFrame& w, const Eigen::Vector4d& u, const CurvePoint& start,
                 const Eigen::Vector4d& direction, Eigen::Vector4d* twin_start) {
  CurvePoint p = start;
  const double orientation = TangentOrientation(w, start.jac, direction);
  // Next to x*, g grows like s t along +v (J v = s u): a first point of the other sign has passed a root.
  double g_prev = u.dot(start.jac * direction);
  for (int step = 0; step < kTwinSteps; ++step) {
    const Eigen::Vector4d tangent = CurveTangent(w, p.jac, orientation);
    CurvePoint q;
    double h = kTwinStep;  // halved (at most twice) where the corrector fails: the curve bends
    while (!CorrectOntoCurve(f, w, p.jac, p.x + h * tangent, &q))
      if ((h *= 0.5) < 0.2 * kTwinStep) return false;
    const double g = u.dot(q.r);
    if (g * g_prev <= 0) {
      *twin_start = step == 0 ? q.x : (p.x + (g_prev / (g_prev - g)) * (q.x - p.x)).eval();
      return true;
    }
    if (std::abs(g) > kTwinGiveUp) return false;
    p = q;
    g_prev = g;
  }
  return false;
}

// Solutions of a general target often come in close pairs born at a fold (T4 of
// docs/paper_notes.md: 22.73757780 and 22.75708870), and a start near the pair converges to one of
// them. From each new solution x* the curve of FollowCurve is followed both ways; a sign change of
// g starts a search (at most two: `twins`).
std::vector<LocalResult> TwinSearches(const Context& ctx, const LocalResult& r, const IsoparallelOptions& options,
                                      long* evaluations) {
  std::vector<LocalResult> twins;
  FreeLengthFunctor f{&ctx, r.regime};
  f.secant = false;
  CurvePoint start;
  start.x = Eigen::Vector4d(r.x[0], r.x[1], r.x[2], r.ev.s);
  if (!f(start.x.data(), start.r.data(), start.jac.data()) || !start.jac.allFinite()) return twins;
  const Eigen::JacobiSVD<Eigen::Matrix4d> svd(start.jac, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector4d u = svd.matrixU().col(3), v = svd.matrixV().col(3);
  const CurveFrame w = svd.matrixU().leftCols<3>();
  for (double sign : {1.0, -1.0}) {
    Eigen::Vector4d y;
    if (!FollowCurve(f, w, u, start, sign * v, &y)) continue;
    twins.push_back(SearchLocalFreeLength(ctx, r.regime, y.data(), y[3], options, nullptr));
  }
  *evaluations += f.evaluations;
  return twins;
}

// Adds a search result to `found` when it polishes to a new solution; true if it did.
bool MergeResult(const Context& ctx, const IsoparallelProblem& problem, const IsoparallelOptions& options,
                 LocalResult* r, std::vector<Candidate>* found, IsoparallelSummary* summary) {
  ++summary->local_solves;
  summary->evaluations += r->evaluations;
  if (r->duplicate) ++summary->converged_solves;
  if (!r->searched) return false;
  // Polish only what is not already known (compared at the search accuracy).
  if (Known(*found, MakeRoughCandidate(ctx, problem, *r), kSearchSameTol)) {
    ++summary->converged_solves;
    return false;
  }
  const long before = r->evaluations;
  PolishLocal(ctx, options, r);
  summary->evaluations += r->evaluations - before;
  if (!r->converged) return false;
  ++summary->converged_solves;
  const Candidate c = MakeCandidate(ctx, problem, *r, options.tolerance);
  if (Known(*found, c, kSameTol)) return false;
  found->push_back(c);
  return true;
}

// The longest length reported: length_cap_factor times the shortest solution found.
double CapLength(const IsoparallelOptions& options, const std::vector<Candidate>& found) {
  double shortest = std::numeric_limits<double>::infinity();
  for (const Candidate& c : found) shortest = std::min(shortest, c.solution.length);
  return options.length_cap_factor * shortest;
}

// Polishes the searched results that are not known yet and adds the new distinct solutions; for
// a general target, each new solution's twin across a fold (TwinSearch) is tried at once, unless
// the solution lies beyond the cap by more than kTwinReach.
void MergeResults(const Context& ctx, const IsoparallelProblem& problem, const IsoparallelOptions& options,
                  std::vector<std::vector<LocalResult>> per_start, std::vector<Candidate>* found,
                  IsoparallelSummary* summary) {
  for (auto& results : per_start) {
    for (LocalResult& r : results) {
      if (!MergeResult(ctx, problem, options, &r, found, summary) || ctx.identity) continue;
      std::vector<LocalResult> pending{r};  // new solutions whose twins are still to be searched
      while (!pending.empty()) {
        const LocalResult from = pending.back();
        pending.pop_back();
        if (from.ev.s > CapLength(options, *found) + kTwinReach) continue;
        for (LocalResult& twin : TwinSearches(ctx, from, options, &summary->evaluations))
          if (MergeResult(ctx, problem, options, &twin, found, summary)) pending.push_back(twin);
      }
    }
  }
}

// The found solutions as roots of the free-length search (the straight segment, rate 0, is not
// one: the search cannot stop at it).
std::vector<SearchRoot> SearchRoots(const std::vector<Candidate>& found) {
  std::vector<SearchRoot> roots;
  for (const Candidate& c : found) {
    const ElasticaParameters& p = c.solution.parameters;
    if (p.rate == 0.0) continue;
    roots.push_back({p.regime, Eigen::Vector4d(p.rate, std::atanh(p.modulus), p.phase, c.solution.length)});
  }
  return roots;
}

// General targets: the shapes are the first options.starts Halton points (regime and sense, log
// period, modulus; the phase is scanned), unshifted: the same for every seed. They are searched
// in batches (kFirstShapeBatch, then kShapeBatch); after each batch the search length shrinks to
// the cap of the solutions found so far (nothing longer is reported), deterministically for any
// thread count.
void SearchShapes(Context* ctx, const IsoparallelProblem& problem, const IsoparallelOptions& options, double covered,
                  std::vector<Candidate>* found, IsoparallelSummary* summary) {
  const std::vector<Start> shapes = MakeStarts(options, ctx->s_limit, ctx->radius, false, true);
  const int total = static_cast<int>(shapes.size());
  for (int first = 0, count = 0; first < total; first += count) {
    count = std::min(first == 0 ? kFirstShapeBatch : kShapeBatch, total - first);
    const std::vector<SearchRoot> known = SearchRoots(*found);  // fixed for the batch: any thread count
    MergeResults(*ctx, problem, options, SearchAll(first, count, total, options, [&](int i) {
                   return SearchShape(*ctx, shapes[i], options, covered, known);
                 }), found, summary);
    if (!found->empty()) ctx->s_limit = std::min(ctx->s_limit, CapLength(options, *found) * (1 + kCapMargin));
  }
}

// Shooting passes: search, merge, then lengthen the search until the cap is covered.
void SolveByShooting(Context* ctx, const IsoparallelProblem& problem, const IsoparallelOptions& options,
                     std::vector<Candidate>* found, IsoparallelSummary* summary) {
  double covered = 0.0;  // crossings up to this length were already searched
  for (int pass = 0; pass < 3; ++pass) {
    if (ctx->identity)
      MergeResults(*ctx, problem, options, SearchStarts(*ctx, options, covered), found, summary);
    else
      SearchShapes(ctx, problem, options, covered, found, summary);
    covered = ctx->s_limit;
    if (found->empty()) {
      if (options.max_length > 0) break;
      ctx->s_limit *= 2.0;
      continue;
    }
    const double needed = CapLength(options, *found);
    if (needed <= ctx->s_limit * (1 + 1e-12)) break;
    ctx->s_limit = needed;
  }
}

// For an identity target, the index of the solution of which each solution is the mirror image
// (a rotating family with rate -> -rate), else -1. The mirror path is the reflection S of the
// path in a vertical plane; rolling along it gives S Q S^-1 (hat(e3 x S t) = S hat(e3 x t) S^-1
// for a reflection S with S e3 = e3), as far from the identity as Q in angle and in every
// orthogonally invariant norm: verifying one of the two verifies both (docs/paper_notes.md).
std::vector<int> MirrorImages(const std::vector<IsoparallelSolution>& sols, IsoparallelMethod method) {
  std::vector<int> mirror(sols.size(), -1);
  if (method != IsoparallelMethod::kFamilyEnumeration) return mirror;
  for (std::size_t i = 0; i < sols.size(); ++i) {
    const ElasticaParameters& p = sols[i].parameters;
    if (!sols[i].family || p.regime != PendulumRegime::kRotating || p.rate >= 0) continue;
    for (std::size_t j = 0; j < sols.size() && mirror[i] < 0; ++j) {
      const ElasticaParameters& q = sols[j].parameters;
      if (sols[j].family && q.regime == PendulumRegime::kRotating && q.rate == -p.rate && q.modulus == p.modulus &&
          sols[j].length == sols[i].length)
        mirror[i] = static_cast<int>(j);
    }
  }
  return mirror;
}

// The first conjugate time of the solution's extremal and Jacobi's condition.
void SetConjugateTime(IsoparallelSolution* sol) {
  const internal::ConjugateTime c = internal::FirstConjugateTime(
      internal::ConjugateProblem::kPlateBall, internal::ExtremalDataOf(sol->parameters), kConjugateSearchFactor * sol->length);
  sol->conjugate_time = c.found ? c.time : std::numeric_limits<double>::infinity();
  sol->locally_optimal = sol->conjugate_time >= sol->length * (1 - kConjugateEndTolerance);
}

// The pairs of solutions of equal length (sorted by length: neighbours in runs).
std::vector<MaxwellPair> MaxwellPairs(const std::vector<IsoparallelSolution>& sols) {
  std::vector<MaxwellPair> pairs;
  for (std::size_t i = 0; i < sols.size(); ++i)
    for (std::size_t j = i + 1; j < sols.size() && sols[j].length <= sols[i].length * (1 + kMaxwellLengthTolerance); ++j)
      pairs.push_back({static_cast<int>(i), static_cast<int>(j)});
  return pairs;
}

// The solutions up to the length cap, sorted, each verified independently by rolling (dopri5
// along the path, spread over the threads; a failed integration is rethrown here).
void ReportVerified(const Context& ctx, const IsoparallelProblem& problem, const IsoparallelOptions& options,
                    std::vector<Candidate> found, IsoparallelSummary* summary) {
  std::stable_sort(found.begin(), found.end(),
                   [](const Candidate& a, const Candidate& b) { return a.solution.length < b.solution.length; });
  if (found.empty()) return;
  const double cap = options.length_cap_factor * found.front().solution.length * (1 + 1e-12);
  for (const Candidate& c : found) {
    if (c.solution.length > cap) break;
    summary->solutions.push_back(c.solution);
  }
  std::vector<IsoparallelSolution>& sols = summary->solutions;
  const std::vector<int> mirror = MirrorImages(sols, summary->method);
  internal::ParallelFor(static_cast<int>(sols.size()), options.threads, [&](int i) {
    IsoparallelSolution& sol = sols[i];
    sol.endpoint_error = (sol.PositionAt(sol.length) - problem.goal).norm();
    sol.crossing = CrossingCount(ctx, Elastica(sol.parameters), sol.length);
    SetConjugateTime(&sol);
    if (mirror[i] >= 0) return;
    const Eigen::Matrix3d r = VerifyRolling(sol, options.integration);
    sol.orientation_residual = LogSO3(ctx.target.transpose() * r).norm();
    sol.orientation_error = OperatorNormDistance(problem.goal_orientation, r * problem.start_orientation);
  });
  for (std::size_t i = 0; i < sols.size(); ++i) {
    if (mirror[i] < 0) continue;
    sols[i].orientation_residual = sols[mirror[i]].orientation_residual;
    sols[i].orientation_error = sols[mirror[i]].orientation_error;
  }
  summary->maxwell_pairs = MaxwellPairs(sols);
}

}  // namespace

namespace internal {

std::vector<IsoparallelSolution> IsoparallelTwins(const IsoparallelProblem& problem, const IsoparallelSolution& solution,
                                                  const IsoparallelOptions& options) {
  ValidateProblem(problem);
  ThrowIfInvalid(options.Validate());
  Context ctx = MakeContext(problem, options);
  ctx.s_limit = std::max(ctx.s_limit, 2.0 * solution.length);
  const ElasticaParameters& p = solution.parameters;
  LocalResult r;
  r.regime = p.regime;
  r.x[0] = p.rate;
  r.x[1] = std::atanh(p.modulus);
  r.x[2] = p.phase;
  r.ev.s = solution.length;
  Candidate given;
  given.solution = solution;
  given.signature = {solution.PositionAt(solution.length / 3), solution.PositionAt(2 * solution.length / 3)};
  std::vector<Candidate> found{given};
  IsoparallelSummary summary;
  for (LocalResult& twin : TwinSearches(ctx, r, options, &summary.evaluations))
    MergeResult(ctx, problem, options, &twin, &found, &summary);
  std::vector<IsoparallelSolution> twins;
  for (std::size_t i = 1; i < found.size(); ++i) twins.push_back(found[i].solution);
  return twins;
}

}  // namespace internal

// The verification runs at a tenth of the integration tolerances (clamped to 1e-15): the
// Runge-Kutta-Fehlberg 7(8) pair, controlled by its local error estimate, accumulates ~10x the
// tolerance over these lengths (Figure 7's shortest: 1.2e-12 rad at 1e-12, 1.4e-13 at 1e-13).
IntegrationOptions VerifyTolerances(const IntegrationOptions& integration) {
  IntegrationOptions o = integration;
  o.absolute_tolerance = std::max(internal::kMinTolerance, 0.1 * o.absolute_tolerance);
  o.relative_tolerance = std::max(internal::kMinTolerance, 0.1 * o.relative_tolerance);
  return o;
}

std::string IsoparallelOptions::Validate() const {
  using internal::InvalidValueMessage;
  if (starts < 1 || starts > kMaxStarts)
    return InvalidValueMessage("starts", starts, "must be in [1, " + std::to_string(kMaxStarts) + "]");
  if (!(length_cap_factor >= 1.0 && length_cap_factor <= kMaxLengthCapFactor))
    return InvalidValueMessage("length_cap_factor", length_cap_factor,
                               "must be in [1, " + internal::FormatNumber(kMaxLengthCapFactor) + "]");
  if (max_iterations < 1 || max_iterations > kMaxIterations)
    return InvalidValueMessage("max_iterations", max_iterations, "must be in [1, " + std::to_string(kMaxIterations) + "]");
  if (!(tolerance >= internal::kMinTolerance && tolerance < 1))
    return InvalidValueMessage("tolerance", tolerance, "must be in [1e-15, 1)");
  if (threads < 1 || threads > kMaxThreads)
    return InvalidValueMessage("threads", threads, "must be in [1, " + std::to_string(kMaxThreads) + "]");
  if (!(std::isfinite(max_length) && max_length >= 0))
    return InvalidValueMessage("max_length", max_length, "must be finite and >= 0 (0 = automatic)");
  return integration.Validate();
}

std::string ToString(IsoparallelMethod method) {
  switch (method) {
    case IsoparallelMethod::kShooting:
      return "shooting";
    case IsoparallelMethod::kFamilyEnumeration:
      return "family_enumeration";
  }
  return "unknown";
}

std::string ToString(IsoparallelStatus status) {
  switch (status) {
    case IsoparallelStatus::kNotRun:
      return "not_run";
    case IsoparallelStatus::kSolved:
      return "solved";
    case IsoparallelStatus::kNoSolution:
      return "no_solution";
    case IsoparallelStatus::kIntegrationFailure:
      return "integration_failure";
  }
  return "unknown";
}

const IsoparallelSolution& IsoparallelSummary::Shortest() const {
  if (solutions.empty())
    throw std::logic_error("IsoparallelSummary::Shortest: no solution (status " + ToString(status) + ")");
  return solutions.front();
}

Eigen::Matrix3d VerifyRolling(const IsoparallelSolution& solution, const IntegrationOptions& integration) {
  internal::ThrowIfInvalid(integration.Validate());
  const Elastica e = solution.Path();
  const internal::RollingRhs rhs{[&e](double s) { return e.Tangent(s); }};
  // A family covers m whole curvature periods of a T-periodic tangent: Q(0, m T) = P^m with the
  // one-period rolling P, integrated once (errors grow like m, as over the whole length).
  // (Only when the length is m T to round-off: the enumerated families; a shooting solution is a
  // whole number of periods only to its own tolerance and is integrated over its whole length.)
  const long whole = solution.family && !e.IsStraight() ? std::lround(solution.length / e.Period()) : 1;
  const int m = whole >= 2 && std::abs(solution.length - whole * e.Period()) <= 1e-13 * solution.length
                    ? static_cast<int>(whole) : 1;
  const double span = solution.length / m;
  internal::RowMajor3x3 y{1, 0, 0, 0, 1, 0, 0, 0, 1};
  using Stepper = boost::numeric::odeint::runge_kutta_fehlberg78<internal::RowMajor3x3>;
  if (span > 0)
    internal::IntegrateAdaptive<Stepper>(rhs, y, 0.0, span, span / 16.0, VerifyTolerances(integration),
                                         [](double, const internal::RowMajor3x3&) {});
  const Eigen::Matrix3d p = ProjectToSO3(internal::MatrixFromRowMajor(y.data()));
  Eigen::Matrix3d q = p;
  for (int i = 1; i < std::max(m, 1); ++i) q = p * q;
  return ProjectToSO3(q);
}

IsoparallelSummary SolveIsoparallel(const IsoparallelProblem& problem, const IsoparallelOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  ValidateProblem(problem);
  internal::ThrowIfInvalid(options.Validate());
  const double start_work = options.starts * (problem.goal - problem.start).norm();  // README, "Limits"
  if (start_work > internal::kMaxStartsTimesChord)
    internal::ThrowInvalid("starts", options.starts, "starts x |goal - start| = " + internal::FormatNumber(start_work) +
                                                         " exceeds the multi-start budget " +
                                                         internal::FormatNumber(internal::kMaxStartsTimesChord));

  IsoparallelSummary summary;
  summary.problem = problem;
  summary.options = options;
  Context ctx = MakeContext(problem, options);
  std::vector<Candidate> found;
  const bool identity = LogSO3(ctx.target).norm() <= options.tolerance;
  ctx.identity = identity;
  summary.seeded = identity;
  if (identity && options.enumerate_families) found = SolveByFamilies(&ctx, problem, options, &summary);
  if (summary.method == IsoparallelMethod::kShooting) SolveByShooting(&ctx, problem, options, &found, &summary);
  summary.searched_length = ctx.s_limit;
  try {
    ReportVerified(ctx, problem, options, std::move(found), &summary);
    summary.status = summary.solutions.empty() ? IsoparallelStatus::kNoSolution : IsoparallelStatus::kSolved;
    summary.message = summary.solutions.empty() ? "no start converged to a verified solution" : "";
  } catch (const std::runtime_error& e) {
    summary.status = IsoparallelStatus::kIntegrationFailure;
    summary.message = std::string("verification by rolling: ") + e.what();
    summary.solutions.clear();
  }
  summary.time_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return summary;
}

std::string IsoparallelSummary::BriefReport() const {
  std::ostringstream os;
  os << "Isoparallel: " << ToString(status) << ", " << solutions.size() << " solution(s)";
  if (!solutions.empty()) {
    os << std::setprecision(10) << ", shortest length " << solutions.front().length << std::setprecision(3)
       << ", verified residual " << solutions.front().orientation_residual;
  }
  os << std::setprecision(4) << ", " << local_solves << " local solves, " << time_seconds << " s";
  return os.str();
}

std::string IsoparallelSummary::FullReport() const {
  std::ostringstream os;
  os << BriefReport() << "\n";
  os << "  start (" << problem.start.transpose() << "), goal (" << problem.goal.transpose() << "), method "
     << ToString(method);
  if (method == IsoparallelMethod::kShooting)
    os << ", starts " << options.starts
       << (seeded ? ", seed " + std::to_string(options.seed) : std::string(", deterministic (no seed)"));
  else
    os << ", periods searched " << periods_searched << (complete ? ", complete" : ", NOT certified complete");
  os << ", searched length " << searched_length << "\n";
  for (std::size_t i = 0; i < solutions.size(); ++i) {
    const IsoparallelSolution& s = solutions[i];
    os << std::setprecision(10) << "  #" << i + 1 << " length " << s.length << " " << ToString(s.parameters.regime)
       << " G " << s.G << " E " << s.energy << " periods " << s.periods << (s.family ? " family" : "")
       << std::setprecision(3) << " crossing " << s.crossing << " residual " << s.orientation_residual
       << " endpoint " << s.endpoint_error << " conjugate " << s.conjugate_time
       << (s.locally_optimal ? " locally optimal" : " NOT locally optimal") << "\n";
  }
  os << "  Maxwell pairs (equal length, same goal): " << maxwell_pairs.size() << "\n";
  return os.str();
}

}  // namespace plateball
