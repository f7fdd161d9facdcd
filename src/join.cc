#include "plateball/join.h"

#include <ceres/jet.h>
#include <ceres/tiny_solver.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "arc.h"
#include "check.h"
#include "connect.h"
#include "contact_series.h"
#include "dopri5.h"
#include "dynamics.h"
#include "fehlberg78.h"
#include "field_check.h"

namespace plateball {
namespace {

using SensState = internal::SensitivityState;  // z[3], x[2], dz/ds[3], dx/ds[2]
// When the equal steps of the hand-written Fehlberg 7(8) kernel are refused, arcs shorter than
// this (t sqrt(mu), about the distance rolled) use odeint's adaptive Dormand-Prince 5(4), which
// covers them in about one step at tolerance 1e-12; longer ones Fehlberg 7(8), which needs far
// fewer right-hand-side evaluations there (T1, |x - x0| = 0.05: 52 instead of 88 per join; 0.2:
// 113 instead of 369).
constexpr double kShortJoinArc = 0.02;
// Up to this many equal steps a rollout tries the hand-written Fehlberg 7(8) kernel first.
constexpr double kMaxEqualSteps = 16;

using internal::SensitivityRhs;

// The first step of a rollout over a length `span` when the last rollout's largest accepted step
// was `hint`: the whole span when it exceeds the hint by at most 25% (the next t of the iteration
// differs from the last by little, and the step controller rejects a step that is too long), else
// the span split into equal steps of at most the hint. Without it a rollout slightly longer than
// the last one ends with a step over ~1e-6 of the time that costs a full set of stages (T1: a
// quarter of the right-hand-side evaluations).
double EvenStep(double span, double hint) {
  if (!(hint > 0) || span <= 1.25 * hint) return span;
  return span / std::ceil(span / hint);
}
using internal::WrapPi;

// The residual x_s(t) - (target - x0) and its exact Jacobian, for Ceres' TinySolver. TinySolver
// evaluates the residual alone at a trial point and then the Jacobian at the same point once the
// step is accepted; one rollout gives both, so the last one is cached.
class JoinFunction {
 public:
  using Scalar = double;
  enum { NUM_RESIDUALS = 2, NUM_PARAMETERS = 2 };

  JoinFunction(const internal::ImpulseBasis& basis,
               double mu,
               double lambda,
               const Eigen::Vector2d& d,
               const IntegrationOptions& options)
      : basis_(basis), mu_(mu), lambda_(lambda), d_(d), options_(options) {}

  bool operator()(const double* p, double* r, double* jac) const {
    if (!(has_cache_ && p[0] == cache_p_[0] && p[1] == cache_p_[1])) Evaluate(p[0], p[1]);
    r[0] = cache_r_[0];
    r[1] = cache_r_[1];
    if (jac) {
      for (int i = 0; i < 4; ++i) jac[i] = cache_j_[i];
    }
    return !failed_;
  }

  // One rollout over [0, t] (t may be negative during the iteration) with dx/ds.
  void Evaluate(double s, double t) const {
    const internal::ReachDirection dir = BeginEvaluation(s, t);
    SensState y{};
    y[0] = dir.z0.x();
    y[1] = dir.z0.y();
    y[2] = dir.z0.z();
    const SensitivityRhs rhs{lambda_, {k_.x(), k_.y()}, {dir.dk_ds.x(), dir.dk_ds.y()}};
    if (!Rollout(rhs, s, t, &y)) return Fail();
    FinishEvaluation(y.data(), y[8], y[9]);
  }

  // The check of a point whose dx/ds is known to good accuracy (the Taylor model's): a rollout of
  // (z, x) alone, half the work of one with the variational equations. The cache then holds the
  // residual, x'(t) and the given dx/ds; Invalidate() before an iteration that needs exact ones.
  void EvaluateWithSColumn(double s, double t, double cos_w, double sin_w, const Eigen::Vector2d& dx_ds) const {
    const internal::ReachDirection dir = BeginEvaluation(s, t, cos_w, sin_w);
    internal::MotionState y{dir.z0.x(), dir.z0.y(), dir.z0.z(), 0.0, 0.0};
    const internal::MotionRhs rhs{lambda_, {k_.x(), k_.y()}};
    if (!Rollout(rhs, s, t, &y)) return Fail();
    FinishEvaluation(y.data(), dx_ds.x(), dx_ds.y());
  }
  void Invalidate() const { has_cache_ = false; }
  // The cached Jacobian's columns d r / d s and d r / d t (= x'(t)); the s column replaceable by
  // an estimate (the quasi-Newton steps' secant update).
  Eigen::Vector2d s_column() const { return {cache_j_[0], cache_j_[1]}; }
  Eigen::Vector2d t_column() const { return {cache_j_[2], cache_j_[3]}; }
  void set_s_column(const Eigen::Vector2d& c) const {
    cache_j_[0] = c.x();
    cache_j_[1] = c.y();
  }

  // Integrates a state starting with (z, x) over [0, t]; false (failure_ says why) when the point
  // is not finite, leaves the local range or the integration fails.
  template <typename State, typename Rhs>
  bool Rollout(const Rhs& rhs, double s, double t, State* y) const {
    if (!std::isfinite(s) || !std::isfinite(t)) return false;
    if (std::abs(t) > max_abs_t_) {
      // Lemma 2.1 is local: its branch has t well below a period. Rolling out further only costs
      // time in proportion to t (and an absurd target would make LM integrate for hours).
      failure_ = "the iteration left the local range |t| <= one period";
      return false;
    }
    if (t == 0.0) return true;
    double last = 0.0, largest = 0.0;
    auto observe = [&](double tt, const State&) {
      largest = std::max(largest, std::abs(tt - last));
      last = tt;
    };
    namespace odeint = boost::numeric::odeint;
    const double dt0 = EvenStep(std::abs(t), dt_hint());
    // Equal Fehlberg 7(8) steps of the last rollout's length (fehlberg78.h), each within the
    // tolerances, lengthened for the next rollout when their error allows; the adaptive loop only
    // when one is not (or the arc needs many steps).
    const double steps = std::ceil(std::abs(t) / dt0 - 1e-9);
    if (steps == 1 && t * t * mu_ <= kShortJoinArc * kShortJoinArc && OneDopri5Step(rhs, t, y)) return true;
    double err = 0.0;
    if (steps <= kMaxEqualSteps &&
        internal::IntegrateEqualSteps(rhs, *y, 0.0, t, static_cast<int>(steps), options_, &err)) {
      dt_hint_ = std::abs(t) / steps;
      dt_err_ = err;  // lengthened when next used (dt_hint()): a lone rollout does not pay for it
      return true;
    }
    try {
      if (std::abs(t) * std::sqrt(mu_) <= kShortJoinArc)
        internal::IntegrateAdaptive<odeint::runge_kutta_dopri5<State>>(rhs, *y, 0.0, t, dt0, options_, observe);
      else
        internal::IntegrateAdaptive<odeint::runge_kutta_fehlberg78<State>>(rhs, *y, 0.0, t, dt0, options_, observe);
    } catch (const std::runtime_error& e) {
      failure_ = e.what();
      return false;
    }
    if (largest > 0) set_dt_hint(largest);
    return true;
  }

  // A short rollout (T2 n = 1024: t ~ 0.016) in one hand-written Dormand-Prince 5(4) step
  // (dopri5.h, 7 evaluations instead of Fehlberg 7(8)'s 13); false (y unchanged) when refused.
  template <typename State, typename Rhs>
  bool OneDopri5Step(const Rhs& rhs, double t, State* y) const {
    State w = *y;
    const double err =
        internal::DormandPrince5Step(rhs, w, 0.0, t, options_.absolute_tolerance, options_.relative_tolerance);
    if (!(err <= 1.0)) return false;
    for (double v : w)
      if (!std::isfinite(v)) return false;
    *y = w;
    set_dt_hint(std::abs(t));
    return true;
  }

  // |r| without hypot's care for overflow: the residual is below 1e100 (a failed rollout's value).
  double Residual() const { return std::sqrt(cache_r_[0] * cache_r_[0] + cache_r_[1] * cache_r_[1]); }
  Eigen::Vector2d residual_vector() const { return {cache_r_[0], cache_r_[1]}; }
  double Conditioning() const {
    const double det = cache_j_[0] * cache_j_[3] - cache_j_[1] * cache_j_[2];
    const double scale = std::hypot(cache_j_[0], cache_j_[1]) * std::hypot(cache_j_[2], cache_j_[3]);
    return scale > 0 ? std::abs(det) / scale : 0.0;
  }
  bool failed() const { return failed_; }
  const internal::ImpulseBasis& basis() const { return basis_; }
  const Eigen::Vector2d& d() const { return d_; }
  void set_max_abs_t(double t) { max_abs_t_ = t; }
  const std::string& failure() const { return failure_; }
  const Eigen::Vector3d& z_end() const { return z_end_; }
  const Eigen::Vector2d& k() const { return k_; }
  int evaluations() const { return evaluations_; }
  void set_dt_hint(double h) const {
    dt_hint_ = h;
    dt_err_ = -1.0;
  }
  // The step to try next: the last equal steps' length, lengthened as far as their error allows.
  double dt_hint() const {
    if (dt_err_ >= 0) dt_hint_ = internal::LengthenedStep(dt_hint_, dt_err_);
    dt_err_ = -1.0;
    return dt_hint_;
  }

 private:
  // cos_w, sin_w: of w = phi - (psi + s) when at hand (else NaN: computed here).
  internal::ReachDirection BeginEvaluation(double s, double t, double cos_w = NAN, double sin_w = NAN) const {
    ++evaluations_;
    has_cache_ = true;
    cache_p_[0] = s;
    cache_p_[1] = t;
    const internal::ReachDirection dir =
        std::isnan(cos_w) ? internal::DirectionFor(basis_, s) : internal::DirectionFromTrig(basis_, s, cos_w, sin_w);
    k_ = dir.k;
    failed_ = false;
    return dir;
  }
  void Fail() const {
    failed_ = true;
    // A huge residual makes TinySolver reject the step.
    cache_r_[0] = cache_r_[1] = 1e100;
    for (double& v : cache_j_) v = 0.0;
  }
  // y starts with (z, x) at the end of the arc.
  void FinishEvaluation(const double* y, double dx_ds0, double dx_ds1) const {
    z_end_ = Eigen::Vector3d(y[0], y[1], y[2]);
    double wt[2];
    const double kd[2] = {k_.x(), k_.y()};
    internal::OmegaFromZK(y, kd, lambda_, wt);
    cache_r_[0] = y[3] - d_.x();
    cache_r_[1] = y[4] - d_.y();
    cache_j_[0] = dx_ds0;  // column-major: d r / d s
    cache_j_[1] = dx_ds1;
    cache_j_[2] = wt[1];  // d r / d t = x'(t) = (omega_2, -omega_1)
    cache_j_[3] = -wt[0];
  }

  internal::ImpulseBasis basis_;
  double mu_, lambda_;
  Eigen::Vector2d d_;
  IntegrationOptions options_;
  mutable bool has_cache_ = false;
  mutable double cache_p_[2] = {0, 0};
  mutable double cache_r_[2] = {0, 0};
  mutable double cache_j_[4] = {0, 0, 0, 0};
  mutable Eigen::Vector2d k_ = Eigen::Vector2d::Zero();
  mutable Eigen::Vector3d z_end_ = Eigen::Vector3d::UnitZ();
  mutable bool failed_ = false;
  double max_abs_t_ = std::numeric_limits<double>::infinity();
  mutable std::string failure_;
  mutable double dt_hint_ = 0.01;
  mutable double dt_err_ = -1.0;  // the error measure of the steps of dt_hint_ (< 0: none)
  mutable int evaluations_ = 0;
};

// The public boundary: options, finite input, mu and coordinates in range (check.h); the angles come back reduced once
// (kinematics.h, ReduceAngles) so that a psi of 1e6 is answered like psi mod 2 pi.
AngleState ValidateJoinInput(const AngleState& start,
                             double mu,
                             const Eigen::Vector2d& x0,
                             const Eigen::Vector2d& target,
                             const JoinOptions& options) {
  internal::ThrowIfInvalid(options.Validate());
  const AngleState reduced = internal::ReduceAngles("start", start);
  internal::RequireEnergy("mu", mu);
  internal::RequireCoordinates("x0", x0);
  internal::RequireCoordinates("target", target);
  return reduced;
}

// Velocity-ellipse guess (27)-(28): x'_s(0) = -b sin(w) e_r - a cos(w) e_phi with w = phi - psi - s
// pointing at the target; t = distance / speed. g: the start's trig. The guess (s, t) with
// cos w, sin w of its w = phi - (psi + s) (the impulse direction, arc.h).
struct Guess {
  Eigen::Vector2d p;  ///< (s, t)
  double cos_w = 1.0, sin_w = 0.0;
};
Guess EllipseGuess(
    const AngleState& start, const internal::AngleTrig& g, double mu, double lambda, const Eigen::Vector2d& d) {
  const double a = internal::SemiAxisFromTrig(g.sin_theta, g.cos_theta, mu, lambda), b = std::sqrt(mu);
  const Eigen::Vector2d er(g.cos_phi, g.sin_phi), ephi(-er.y(), er.x());
  // w = atan2(y, x) and the speed from (cos w, sin w) = (x, y) / |(x, y)| without their libm calls.
  const double y = -d.dot(er) / b, x = -d.dot(ephi) / a, r = std::sqrt(x * x + y * y);
  const double speed = std::sqrt(b * b * y * y + a * a * x * x) / r;
  return {{WrapPi(start.phi - start.psi - std::atan2(y, x)), d.norm() / speed}, x / r, y / r};
}

// The guess moved by delta: s - delta[0] turns w = phi - (psi + s) by +delta[0] (one sine and
// cosine of a small angle instead of those of w).
Guess Moved(const Guess& g, const Eigen::Vector2d& delta) {
  const double c = std::cos(delta[0]), s = std::sin(delta[0]);
  return {g.p - delta, g.cos_w * c - g.sin_w * s, g.sin_w * c + g.cos_w * s};
}

// MakeImpulseBasis (arc.h) from the start's trig at hand (the same values, no sine computed again).
internal::ImpulseBasis BasisFromTrig(const AngleState& start, const internal::AngleTrig& g, double mu, double lambda) {
  internal::ImpulseBasis e;
  e.z0 = {g.sin_theta * g.cos_phi, g.sin_theta * g.sin_phi, g.cos_theta};
  e.a = internal::SemiAxisFromTrig(g.sin_theta, g.cos_theta, mu, lambda);
  e.b = std::sqrt(mu);
  e.cos_phi = g.cos_phi;
  e.sin_phi = g.sin_phi;
  e.phi = start.phi;
  e.psi = start.psi;
  e.lambda = lambda;
  return e;
}

// One Newton step on the Taylor model of order M of x(s, t) (contact_series.h, dx/ds in forward
// mode): the correction delta with x(p - delta) ~ x0 + d to the model's accuracy; false when the
// model's Jacobian is singular.
template <int M, int D>
bool SeriesNewtonStep(const internal::ImpulseBasis& basis,
                      const Eigen::Vector2d& d,
                      const Guess& g,
                      Eigen::Vector2d* delta,
                      Eigen::Vector2d* dx_ds) {
  using Dual = internal::SeriesDual;
  const double z0[3] = {basis.z0.x(), basis.z0.y(), basis.z0.z()};
  const Eigen::Vector2d& p = g.p;
  const internal::ReachDirection dir = internal::DirectionFromTrig(basis, p[0], g.cos_w, g.sin_w);
  const Dual k[2] = {Dual(dir.k.x(), dir.dk_ds.x()), Dual(dir.k.y(), dir.dk_ds.y())};
  std::array<std::array<Dual, 2>, M + 1> x;
  internal::ContactSeries<M, D>(z0, k, basis.lambda, &x);
  // Horner: X = sum x_m t^m and dX/dt = sum m x_m t^(m-1).
  const double t = p[1];
  Dual xs[2] = {x[M][0], x[M][1]};
  double xt[2] = {M * xs[0].a, M * xs[1].a};
  for (int m = M - 1; m >= 1; --m) {
    for (int i = 0; i < 2; ++i) {
      xs[i] = t * xs[i] + x[m][i];
      xt[i] = xt[i] * t + m * x[m][i].a;
    }
  }
  Eigen::Matrix2d jac;
  jac << xs[0].d * t, xt[0], xs[1].d * t, xt[1];
  *dx_ds = jac.col(0);
  if (!(std::abs(jac.determinant()) > 1e-12 * jac.squaredNorm())) return false;
  *delta = jac.inverse() * Eigen::Vector2d(xs[0].a * t - d.x(), xs[1].a * t - d.y());
  return delta->allFinite();
}

// The guess refined by two Newton steps on Taylor models of x(s, t): a step on the order-4 model,
// then one on the order-7 model (its Jacobian from the order-4 terms; order 13 from order 6 on
// kHighOrderArcs, below). *dx_ds: the model's d x / d s. What the model is worth depends on the
// arc (t sqrt(mu)):
//  - up to kSeriesArc, kChecked: the ellipse guess is the model's first-order solution (T1:
//    residual up to 5e-4), the first step brings it to ~2e-6 and the second (~1e-6: a Jacobian
//    good to ~1e-6 suffices) to the model's truncation error (T1: below the check rollout's own
//    ~3e-13), so that the rollout there (the check) is within 1e-12 and needs no iteration; dx/ds
//    is good to ~1e-6 relative (the reported conditioning's s column).
//  - up to kSeriesGuessArc, kGuess: the truncation error is above the tolerance, but the refined
//    point is still far better than the ellipse's (random joins at t sqrt(mu) 0.2-1: residual
//    1.7e-6 against 1.5e-2; docs/benchmarks.md, "The Taylor model as the long arcs' guess"); a
//    rollout with the variational equations and the quasi-Newton steps follow. Taken when the second step
//    is at most half the first (the model converging), else the ellipse guess stays.
//    On kHighOrderArcs the second step is on the order-13 model (Jacobian from order 6): random
//    joins there need 1.9 quasi-Newton steps instead of 2.4 (0.5-1), 3.2 instead of 3.3 (1-1.5);
//    beyond 1.5 it is no better than order 7.
//  - kNone (the guess unchanged): beyond, or when a step is singular or leaves t > 0.
// Either way a rollout decides convergence: the model only saves rollouts.
constexpr double kSeriesArc = 0.2;
constexpr double kSeriesGuessArc = 3.0;
constexpr double kHighOrderArcs[2] = {0.5, 1.5};
enum class SeriesUse { kNone, kGuess, kChecked };
SeriesUse RefineOnSeries(
    const internal::ImpulseBasis& basis, double mu, const Eigen::Vector2d& d, Guess* guess, Eigen::Vector2d* dx_ds) {
  const double root_mu = std::sqrt(mu);
  const double arc0 = guess->p[1] * root_mu;
  Eigen::Vector2d delta;
  if (!(guess->p[1] > 0 && arc0 <= kSeriesGuessArc) || !SeriesNewtonStep<4, 3>(basis, d, *guess, &delta, dx_ds))
    return SeriesUse::kNone;
  const Guess g = Moved(*guess, delta);
  const double arc = g.p[1] * root_mu, first = delta.squaredNorm();
  if (!(g.p[1] > 0 && arc <= kSeriesGuessArc)) return SeriesUse::kNone;
  const bool high = arc > kHighOrderArcs[0] && arc <= kHighOrderArcs[1];
  const bool stepped =
      high ? SeriesNewtonStep<13, 6>(basis, d, g, &delta, dx_ds) : SeriesNewtonStep<7, 4>(basis, d, g, &delta, dx_ds);
  if (!stepped) return SeriesUse::kNone;
  // On a short arc the second step is the model's quadratic convergence; a large one means the
  // model is no guide there.
  const bool short_arc = arc0 <= kSeriesArc && arc <= kSeriesArc;
  if (short_arc && delta.norm() <= 1e-4 * (1.0 + std::abs(g.p[1]))) {
    *guess = Moved(g, delta);
    return SeriesUse::kChecked;
  }
  if (!(delta.squaredNorm() <= 0.25 * first)) return SeriesUse::kNone;  // the model not converging
  *guess = Moved(g, delta);
  return SeriesUse::kGuess;
}

// Levenberg-Marquardt (Ceres TinySolver) on (s, t) from the guess; leaves fn's cache at the
// final point with t >= 0. The reversed motion: (psi + pi) flips omega, and (z(-t), -omega(-t))
// is again a solution, so a solution with t < 0 is the solution (s + pi, -t).
// Ceres 2.1's TinySolver leaves members unset until Solve; GCC cannot see that once it is inlined here.
#pragma GCC diagnostic push
#if !defined(__clang__)  // clang knows no -Wmaybe-uninitialized and warns about the pragma itself
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#endif
int SolveLocal(JoinFunction& fn, const JoinOptions& options, int max_iterations, Eigen::Vector2d* params) {
  ceres::TinySolver<JoinFunction> solver;
  solver.options.max_num_iterations = max_iterations;
  solver.options.gradient_tolerance = 0.0;  // stop on the residual, not the gradient
  solver.options.function_tolerance = 0.0;  // (an absolute test in Ceres 2.1)
  solver.options.parameter_tolerance = 1e-15;
  solver.options.cost_threshold = 0.5 * options.residual_tolerance * options.residual_tolerance;
  solver.options.initial_trust_region_radius = 1e12;  // Gauss-Newton while the model is good
  const auto& ts = solver.Solve(fn, params);
  if ((*params)[1] < 0) {
    (*params)[0] += M_PI;
    (*params)[1] = -(*params)[1];
  }
  double r[2];
  fn(params->data(), r, nullptr);  // make the cache hold the final point
  return ts.iterations;
}
#pragma GCC diagnostic pop

// Newton steps p -= J^-1 r with the Jacobian at hand, each checked by a rollout of (z, x) alone
// (half the work of one with the variational equations): the t column is each rollout's exact
// x'(t), the s column the Taylor model's or the first full rollout's, corrected after each step by
// the secant condition on that column (Broyden's rule), so that the steps converge superlinearly
// (T2 n = 16, arcs of t ~ 1: the ellipse guess's residual ~1e-2 within 1e-12 in about four
// rollouts, where Levenberg-Marquardt took four to five with the variational equations). True
// when the residual is within the tolerance (guess then holds the point, with the trig of its w);
// false when a step does not halve the residual, leaves t > 0 or a rollout fails, or after
// max_steps (guess then holds the last point that did, fn's cache is not its).
constexpr int kMaxQuasiNewtonSteps = 8;
bool QuasiNewton(JoinFunction& fn, const JoinOptions& options, int max_steps, Guess* guess, int* steps) {
  Eigen::Vector2d col_s = fn.s_column();
  for (*steps = 0; fn.Residual() > options.residual_tolerance;) {
    if (*steps == max_steps) return false;
    const Eigen::Vector2d r = fn.residual_vector(), col_t = fn.t_column();
    Eigen::Matrix2d jac;
    jac << col_s, col_t;
    if (!(std::abs(jac.determinant()) > 1e-12 * jac.squaredNorm())) return false;
    const Eigen::Vector2d delta = jac.inverse() * r;
    const Guess next = Moved(*guess, delta);
    const double before = fn.Residual();
    if (!(next.p[1] > 0)) return false;
    ++*steps;
    fn.EvaluateWithSColumn(next.p[0], next.p[1], next.cos_w, next.sin_w, col_s);
    if (fn.failed() || !(fn.Residual() <= 0.5 * before)) return false;
    *guess = next;
    // Secant on the s column: col_s (-delta_s) + (mean t column) (-delta_t) = r_new - r. Below
    // 1e-8 in s the rollouts' own error (~1e-13) would dominate the difference: kept as it is.
    if (std::abs(delta[0]) > 1e-8) {
      col_s = -(fn.residual_vector() - r + 0.5 * (col_t + fn.t_column()) * delta[1]) / delta[0];
      fn.set_s_column(col_s);
    }
  }
  return true;
}

// From the ellipse guess to the answer: on a short arc the guess refined on the Taylor model and
// checked by one rollout of (z, x), else one rollout with the variational equations at the guess
// (refined on the model up to kSeriesGuessArc);
// from there quasi-Newton steps on rollouts of (z, x) (QuasiNewton), and Levenberg-Marquardt on
// full rollouts only when they fail. Fills delta_psi, t, residual, conditioning, iterations (the
// quasi-Newton steps and LM's) and the residual at the first point rolled out; leaves fn's cache
// at the answer. step: the rollouts' step to try first (0: the guess's t, i.e. one step). True
// when the quasi-Newton steps (or the check alone) gave the answer (guess then holds it, with the
// trig of its w).
bool SolveFromGuess(
    JoinFunction& fn, double mu, const JoinOptions& options, double step, Guess* guess, JoinSummary* out) {
  Eigen::Vector2d dx_ds;
  const bool modelled = RefineOnSeries(fn.basis(), mu, fn.d(), guess, &dx_ds) == SeriesUse::kChecked;
  fn.set_dt_hint(step > 0 ? step : guess->p[1]);
  if (modelled)
    fn.EvaluateWithSColumn(guess->p[0], guess->p[1], guess->cos_w, guess->sin_w, dx_ds);  // the check
  else
    fn.Evaluate(guess->p[0], guess->p[1]);
  out->initial_guess_residual = fn.Residual();
  // The quasi-Newton steps and LM's iterations share options.max_iterations.
  int steps = 0;
  const int budget = std::min(kMaxQuasiNewtonSteps, options.max_iterations);
  const bool converged =
      !fn.failed() && (fn.Residual() <= options.residual_tolerance || QuasiNewton(fn, options, budget, guess, &steps));
  Eigen::Vector2d params = guess->p;
  out->iterations = steps;
  if (!converged) {
    fn.Invalidate();  // the iteration needs the exact dx/ds
    if (steps < options.max_iterations) {
      out->iterations += SolveLocal(fn, options, options.max_iterations - steps, &params);
    } else {
      double r[2];
      fn(params.data(), r, nullptr);  // the cache at the last point (no iteration left)
    }
  }
  out->delta_psi = WrapPi(params[0]);
  out->t = params[1];
  out->residual = fn.Residual();
  out->jacobian_conditioning = fn.Conditioning();
  return converged;
}

// Why a finished iteration is not the local solution of Lemma 2.1 (empty when it is). Messages
// are built only on failure (a string stream costs more than a short rollout).
std::string LocalFailure(const JoinSummary& out, const JoinOptions& options, double dist) {
  if (out.residual <= options.residual_tolerance && out.t <= out.time_limit && out.jacobian_conditioning >= 1e-3)
    return {};
  std::ostringstream os;
  os.precision(6);
  if (!(out.residual <= options.residual_tolerance)) {
    os << "no solution found within " << out.iterations << " iterations: residual " << out.residual << " > tolerance "
       << options.residual_tolerance << " (|target - x0| = " << dist << ")";
  } else if (out.t > out.time_limit) {
    os << "the solution found has t = " << out.t << " > K1 |target - x0| = " << out.time_limit
       << ": not the local branch of Lemma 2.1 (|target - x0| = " << dist << ")";
  } else if (out.jacobian_conditioning < 1e-3) {
    os << "the polar coordinates (s, t) degenerate at the solution (conditioning " << out.jacobian_conditioning << ")";
  }
  return os.str();
}

// The impulse s and the state on arrival (z, K at the end of the arc, the contact point x). g: the
// start's trig.
// cos_w, sin_w: of w = phi - (psi + s) after the impulse when at hand (else NaN: computed here).
// end_angles: false leaves angles_after unset (the planner takes them from its own arc).
void FinishState(const BallModel& model,
                 const internal::AngleTrig& g,
                 double s,
                 const Eigen::Vector3d& z,
                 const Eigen::Vector2d& k,
                 const Eigen::Vector2d& x,
                 JoinSummary* out,
                 double cos_w = NAN,
                 double sin_w = NAN,
                 bool end_angles = true) {
  // EnergyPreservingImpulse (impulse.h) with each sine and cosine once: theta and phi are those of
  // the start, only w = phi - psi changes.
  internal::RequireEnergy("mu", out->mu);  // as EnergyPreservingImpulse would (a ball too slow to join)
  const AngleState& a = out->start;
  AngleState after = a;
  after.psi += s;
  internal::AngleTrig trig = g;
  const PhaseVariables p0 = internal::PhaseFromTrig(trig, out->mu, model.lambda());
  const double w1 = after.phi - after.psi;
  trig.sin_w = std::isnan(sin_w) ? std::sin(w1) : sin_w;
  trig.cos_w = std::isnan(cos_w) ? std::cos(w1) : cos_w;
  out->impulse = internal::ImpulseFromPhases(
      a, out->mu, after, out->mu, p0, internal::PhaseFromTrig(trig, out->mu, model.lambda()));
  out->state_after.z = z.normalized();
  out->state_after.omega = OmegaFromMomentum(out->state_after.z, k, model);
  if (end_angles) out->angles_after = AnglesFromState(out->state_after, model);
  out->x_after = x;
}

// The start itself as the end state (no impulse, no motion): the answer of the early exits.
void FinishAtStart(const BallModel& model, const internal::AngleTrig& g, JoinSummary* out) {
  const PhaseVariables p0 = internal::PhaseFromTrig(g, out->mu, model.lambda());  // StateFromAngles
  FinishState(model, g, 0.0, p0.z, ConservedMomentum({p0.z, p0.omega}, model), out->x0, out, g.cos_w, g.sin_w);
}

}  // namespace

std::string ToString(JoinStatus status) {
  switch (status) {
    case JoinStatus::kNotRun:
      return "not_run";
    case JoinStatus::kConverged:
      return "converged";
    case JoinStatus::kTargetEqualsStart:
      return "target_equals_start";
    case JoinStatus::kTargetBeyondLocalRadius:
      return "target_beyond_local_radius";
    case JoinStatus::kIntegrationFailure:
      return "integration_failure";
  }
  return "unknown";
}

// Below 1e-15 a residual is round-off (a rollout cannot reach it); above 1e-3 the join's
// target-equals-start test and its local branch stop meaning anything.
constexpr double kMinResidualTolerance = 1e-15, kMaxResidualTolerance = 1e-3;

std::string JoinOptions::Validate() const {
  // residual_tolerance in [1e-15, 1e-3]: beyond 1e-3 a join "converges" to the wrong point (0.999
  // called every target the start), below 1e-15 no double residual meets it.
  if (!(residual_tolerance >= kMinResidualTolerance && residual_tolerance <= kMaxResidualTolerance))
    return internal::InvalidValueMessage("residual_tolerance", residual_tolerance, "must be in [1e-15, 1e-3]");
  const std::string e = internal::CheckRanges(*this);  // iterations, local-time factor (the field list)
  if (!e.empty()) return e;
  return integration.Validate();
}

std::string JoinSummary::BriefReport() const {
  std::ostringstream os;
  os.precision(6);
  os << "Join: " << ToString(status) << ", delta_psi = " << delta_psi << ", t = " << t << ", residual = " << residual
     << ", iterations = " << iterations;
  if (!message.empty()) os << " (" << message << ")";
  return os.str();
}

double MinimumContactSpeed(double mu, const BallModel& model) {
  internal::RequirePositive("mu", mu);
  return internal::MinimumContactSpeed(mu, model.lambda());
}

JoinSummary Join(const JoinProblem& problem, const JoinOptions& options) {
  const AngleState start_reduced = ValidateJoinInput(problem.start, problem.mu, problem.x0, problem.target, options);
  return internal::JoinValidated(problem.model, start_reduced, problem.mu, problem.x0, problem.target, options);
}

namespace internal {

JoinSummary JoinValidated(const BallModel& model,
                          const AngleState& start_reduced,
                          double mu,
                          const Eigen::Vector2d& x0,
                          const Eigen::Vector2d& target,
                          const JoinOptions& options,
                          JoinCarry* carry) {
  const double lambda = model.lambda();
  JoinSummary out;
  out.message.clear();  // filled only when the join does not converge
  out.start = start_reduced;
  out.mu = mu;
  out.x0 = x0;
  out.target = target;
  const internal::AngleTrig trig = internal::TrigFromAngles(out.start);  // each sine and cosine of the start once
  const Eigen::Vector2d d = target - x0;
  const double dist = d.norm();
  out.time_limit = options.local_time_factor / internal::MinimumContactSpeed(mu, lambda) * dist;

  if (dist <= options.residual_tolerance) {
    out.status = JoinStatus::kTargetEqualsStart;
    out.message = "target equals the start point x0 (|target - x0| = " + std::to_string(dist) + ")";
    out.residual = dist;
    FinishAtStart(model, trig, &out);
    return out;
  }

  // Lemma 2.1's branch needs much less than a period; a target whose first-guess time is above
  // half a period is beyond the local radius (Reach handles it), and is answered without rolling out.
  Guess guess = EllipseGuess(out.start, trig, mu, lambda, d);
  const double period = 2.0 * M_PI / std::sqrt(mu);
  if (!(guess.p[1] <= 0.5 * period)) {
    out.delta_psi = guess.p[0];
    out.t = guess.p[1];
    out.residual = dist;
    out.status = JoinStatus::kTargetBeyondLocalRadius;
    out.message = "target at distance " + std::to_string(dist) + " needs t ~ " + std::to_string(guess.p[1]) +
                  " > half a period (" + std::to_string(0.5 * period) + "): beyond the local radius of Lemma 2.1";
    FinishAtStart(model, trig, &out);
    return out;
  }

  JoinFunction fn(BasisFromTrig(out.start, trig, mu, lambda), mu, lambda, d, options.integration);
  fn.set_max_abs_t(period);
  const bool checked = SolveFromGuess(fn, mu, options, carry != nullptr ? carry->step : 0.0, &guess, &out);
  if (carry != nullptr) carry->step = fn.dt_hint();
  if (fn.failed()) {
    out.status = JoinStatus::kIntegrationFailure;
    out.message = fn.failure();
    return out;
  }
  // After a check within the tolerance, the trig of the impulse is the check's (guess.p unchanged).
  FinishState(model,
              trig,
              out.delta_psi,
              fn.z_end(),
              fn.k(),
              target + fn.residual_vector(),
              &out,
              checked ? guess.cos_w : NAN,
              checked ? guess.sin_w : NAN,
              carry == nullptr || carry->end_angles);
  out.message = LocalFailure(out, options, dist);
  out.status = out.message.empty() ? JoinStatus::kConverged : JoinStatus::kTargetBeyondLocalRadius;
  return out;
}

}  // namespace internal

}  // namespace plateball
