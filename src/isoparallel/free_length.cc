// The rotation trick of section 2.2 on a candidate elastica (the rolling in closed form), and the
// free-length residual (FreeLengthFunctor) that the search, the polish and the twin search solve.
#include <Eigen/Geometry>
#include <Eigen/LU>
#include <cmath>
#include <limits>

#include "chord_residual.h"
#include "circle_crossings.h"
#include "isoparallel/stages.h"
#include "jacobi_elliptic.h"
#include "plateball/so3.h"
#include "rotation_trick.h"

namespace plateball::internal::isoparallel {
namespace {

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
    const double h = kDifferenceStep * (1.0 + std::abs(x[j]));
    double xp[N], rp[N];
    std::copy(x, x + N, xp);
    xp[j] += h;
    if (!f.Shifted(xp, rp)) return false;
    for (int i = 0; i < N; ++i) jacobian[j * N + i] = (rp[i] - r[i]) / h;  // column-major
  }
  return true;
}

}  // namespace

ElasticaParameters ToParameters(PendulumRegime regime, const double* x) {
  ElasticaParameters p;
  p.regime = regime;
  p.rate = x[0];
  p.modulus = std::tanh(x[1]);
  p.phase = x[2];
  p.heading_w = M_PI / 2;  // pendulum frame = plane frame; B supplies the rotation freedom
  return p;
}

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
  return internal::ElasticaRollingTable(e, s_limit, acc.steps_per_period, acc.max_step, kTableMaxSteps, true);
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

bool FreeLengthFunctor::Admissible(const ElasticaParameters& p, double length) const {
  return std::isfinite(p.rate) && std::isfinite(p.modulus) && std::isfinite(p.phase) && std::isfinite(length) &&
         std::abs(p.modulus) < 1.0 && length > 0 && length <= 2.0 * ctx->s_limit;
}

// The residual of a path with chord xs and rolling q.
bool FreeLengthFunctor::ResidualOf(const Eigen::Vector2d& xs, const Eigen::Matrix3d& q, double* r) const {
  if (xs.norm() == 0.0) return false;
  const Eigen::Vector3d rot = internal::RotationTrickResidual(ctx->target, internal::ChordTurn(ctx->goal_angle, xs), q);
  r[0] = xs.norm() - ctx->radius;
  for (int i = 0; i < 3; ++i) r[i + 1] = rot[i];
  return rot.allFinite();
}

// The residual of the path from 0 to `length` of the rolling's elastica (x(0) = 0), Q(0, L) in
// closed form; its chord and rolling are kept in `last`.
bool FreeLengthFunctor::ResidualFrom(const Elastica& e,
                                     const internal::ElasticaClosedRolling& rolling,
                                     double length,
                                     double* r) const {
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
bool FreeLengthFunctor::ShiftedResiduals(
    const Elastica& e, double length, double s0, double h, double* rp, double* rl) const {
  Eigen::Vector2d t0, t1;
  double k0 = 0, k1 = 0;
  e.TangentAndCurvature(0.0, &t0, &k0);
  e.TangentAndCurvature(length, &t1, &k1);
  const Eigen::Vector2d n0 = k0 * Eigen::Vector2d(-t0.y(), t0.x()), n1 = k1 * Eigen::Vector2d(-t1.y(), t1.x());
  const auto spin = [](const Eigen::Vector2d& t, double step) {
    return ExpSO3(step * Eigen::Vector3d(-t.y(), t.x(), 0.0));
  };
  const Eigen::Vector2d chord_p = last.end.chord + s0 * (t1 - t0) + 0.5 * s0 * s0 * (n1 - n0);
  const Eigen::Matrix3d q_p = spin(t1 + 0.5 * s0 * n1, s0) * last.end.q * spin(t0 + 0.5 * s0 * n0, -s0);
  const Eigen::Vector2d chord_l = last.end.chord + h * t1 + 0.5 * h * h * n1;
  return ResidualOf(chord_p, q_p, rp) && ResidualOf(chord_l, spin(t1 + 0.5 * h * n1, h) * last.end.q, rl);
}

// `base`: an elastica of x's modulus and phase (another rate), whose rate-free parts the path shares.
bool FreeLengthFunctor::Residual(const double* x, double* r, bool, const Elastica* base) const {
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

// The residual at x, the last one when it was evaluated there (a run that ended on an accepted point).
bool FreeLengthFunctor::ResidualAt(const double* x, double* r) const {
  if (!LastAt(x)) return Residual(x, r);
  std::copy(last.r, last.r + 4, r);
  return true;
}

// Forward differences, but one closed-form rolling (one per (rate, k)) serves the residual and
// the phase and length columns: only the rate and modulus columns build new ones.
bool FreeLengthFunctor::operator()(const double* x, double* r, double* jacobian) const {
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

// Whether the run stalls at an accepted point of residual norm `norm` (TinySolver evaluates the
// Jacobian exactly at the accepted points): see kStallRatio.
bool FreeLengthFunctor::Stalls(double norm) const {
  const bool stall =
      stall_stop && norm >= kStallFloor && norm > kStallRatio * accepted[1] && accepted[1] > kStallRatio * accepted[0];
  accepted[0] = accepted[1];
  accepted[1] = norm;
  return stall;
}

// A run that reached a known solution (or stalled): a zero residual and Jacobian end TinySolver's loop at
// once (cost below its threshold); the caller drops the run by `duplicate` (or `stalled`).
bool FreeLengthFunctor::StopRun(double* r, double* jacobian) {
  std::fill(r, r + 4, 0.0);
  if (jacobian != nullptr) std::fill(jacobian, jacobian + 16, 0.0);
  return true;
}

// Whether the Gauss-Newton step from x lands on a known solution (only near a root).
bool FreeLengthFunctor::ReachesKnown(const double* x, const double* r, const double* jacobian) const {
  if (known == nullptr || known->empty()) return false;
  const Eigen::Map<const Eigen::Vector4d> res(r);
  if (!(res.norm() <= kDuplicateResidual)) return false;
  const Eigen::Map<const Eigen::Matrix4d> jac(jacobian);
  // At a converged point (no Jacobian computed: Converged) the point itself, within kSearchStop
  // of a root, stands for the Gauss-Newton step.
  const Eigen::Vector4d y = Converged(r)
                                ? Eigen::Vector4d(Eigen::Map<const Eigen::Vector4d>(x))
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
bool FreeLengthFunctor::SecantColumns(const double* x, const double* r, double* jacobian) const {
  if (!secant || ctx->identity || !kept.valid || !(Eigen::Map<const Eigen::Vector4d>(r).norm() > kSecantResidual))
    return false;
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
bool FreeLengthFunctor::AnalyticColumns(const double* x, const double* r, double* jacobian) const {
  internal::ElasticaClosedRolling::PathSensitivity sens;
  if (!last.rolling->Sensitivity(last.end, &sens)) return false;
  const double modulus = last.path->parameters().modulus;
  const double dmodulus = (1.0 - modulus) * (1.0 + modulus);  // d tanh(atanh k) / d atanh k
  for (int j = 0; j < 2; ++j) {
    const double h = kDifferenceStep * (1.0 + std::abs(x[j])), step = j == 0 ? h : h * dmodulus;
    const Eigen::Vector2d chord = last.end.chord + step * (j == 0 ? sens.chord_rate : sens.chord_modulus);
    const Eigen::Matrix3d q = last.end.q * ExpSO3(step * (j == 0 ? sens.spin_rate : sens.spin_modulus));
    double rj[4];
    if (!ResidualOf(chord, q, rj)) return false;
    for (int i = 0; i < 4; ++i) jacobian[j * 4 + i] = (rj[i] - r[i]) / h;
  }
  return true;
}

bool FreeLengthFunctor::Evaluate(const double* x, double* r, double* jacobian) const {
  const ElasticaParameters p = ToParameters(regime, x);
  const double h_phase = kDifferenceStep * (1.0 + std::abs(x[2])), h_length = kDifferenceStep * (1.0 + std::abs(x[3]));
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
    const double h = kDifferenceStep * (1.0 + std::abs(x[j]));
    double xp[4] = {x[0], x[1], x[2], x[3]}, rj[4];
    xp[j] += h;
    if (!Residual(xp, rj, false, j == 0 ? &path : nullptr)) return false;  // the rate: path's k, K, phase terms
    for (int i = 0; i < 4; ++i) jacobian[j * 4 + i] = (rj[i] - r[i]) / h;
  }
  return true;
}

}  // namespace plateball::internal::isoparallel
