// The free-length search from a start (the search stage) and the polish of its result (the polish
// stage), both ceres::TinySolver runs on the free-length residual (FreeLengthFunctor); the starts
// of the identity target's comparison shooting.
#include <ceres/tiny_solver.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "isoparallel/stages.h"
#include "jacobi_elliptic.h"

namespace plateball::internal::isoparallel {
namespace {

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

// TinySolver on the free-length residual from v to kSearchStop, at most kSearchIterations
// iterations (fewer when options.max_iterations is smaller). A run still far from a root after
// kTriageIterations (above kHopelessResidual) is abandoned: such runs rarely converge, and their
// solutions are reached from other starts. The final cost; negative (TinySolver's "not run") when
// the start has no residual.
double TriagedSearch(const FreeLengthFunctor& f, const IsoparallelOptions& options, Eigen::Vector4d* v) {
  ceres::TinySolver<FreeLengthFunctor> solver;
  solver.options.max_num_iterations = std::min(options.max_iterations, kSearchIterations);
  solver.options.gradient_tolerance = 0.0;
  solver.options.parameter_tolerance = 1e-15;
  solver.options.function_tolerance = 0.0;
  solver.options.cost_threshold = f.cost_threshold;
  double r0[4];
  if (f.Residual(v->data(), r0)) {
    const int total = solver.options.max_num_iterations;
    solver.options.max_num_iterations = std::min(total, kTriageIterations);
    solver.Solve(f, v);
    if (v->allFinite() && solver.summary.final_cost > 0.5 * kSearchStop * kSearchStop &&
        solver.summary.final_cost <= 0.5 * kHopelessResidual * kHopelessResidual && total > kTriageIterations) {
      solver.options.max_num_iterations = total - kTriageIterations;
      solver.Solve(f, v);
    }
  }
  return solver.summary.final_cost;
}

// Whether a search run that ended at v with the given cost goes to the polish, and from where
// (out->ev). Runs that stopped far from a root (above kHandOffResidual) do not: the hand-off's
// tables over the whole search length would be spent mostly on them. The crossing formulation's
// n: the crossing nearest to L on the search table, else on the polish table (a near-tangency, the
// chord just reaching the radius between two coarse nodes), else (kTangentHandOff) the run's own
// length.
bool GoesToPolish(const Context& ctx, const Eigen::Vector4d& v, double cost, LocalResult* out) {
  if (!(cost >= 0 && cost <= 0.5 * kHandOffResidual * kHandOffResidual)) return false;
  if (HandOff(ctx, v[3], kSearch, out) || HandOff(ctx, v[3], kPolish, out)) return true;
  return !ctx.identity && std::sqrt(2 * cost) <= kTangentHandOff &&  // cf. PolishLocal
         Evaluate(ctx, ToParameters(out->regime, v.data()), v[3], &out->ev);
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
  double a = (*v)[0], ga = u.dot(r), b = a * (1 + kValleyFirstStep);
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

// Radical-inverse (Halton): deterministic, portable.
double Halton(long index, int base) {
  double f = 1.0, r = 0.0;
  for (long i = index; i > 0; i /= base) {
    f /= base;
    r += f * static_cast<double>(i % base);
  }
  return r;
}

}  // namespace

// Search stage on the free-length formulation from a start and one of its crossings; the result
// is handed off (at the crossing nearest its length, the residual checked there) to the
// polish. A run that reaches one of the `known` solutions stops there (LocalResult::duplicate), a
// run that stalls (kStallRatio) too.
LocalResult SearchLocalFreeLength(const Context& ctx,
                                  PendulumRegime regime,
                                  const double* x0,
                                  double length0,
                                  const IsoparallelOptions& options,
                                  const std::vector<SearchRoot>* known) {
  LocalResult out;
  out.regime = regime;
  FreeLengthFunctor f{&ctx, regime};
  f.known = known;
  f.stall_stop = true;
  f.cost_threshold = 0.5 * kSearchStop * kSearchStop;
  Eigen::Vector4d v(x0[0], x0[1], x0[2], length0);
  const double cost = TriagedSearch(f, options, &v);
  out.evaluations = f.evaluations;
  out.duplicate = f.duplicate;
  std::copy(v.data(), v.data() + 3, out.x);
  if (out.duplicate || f.stalled) return out;
  if (!v.allFinite() || !(v[3] > 0) || std::abs(std::tanh(v[1])) >= 1.0) return out;
  out.searched = GoesToPolish(ctx, v, cost, &out);
  return out;
}

// Polish stage: LM (in effect Newton) on the free-length formulation with exact Jacobians (no
// Broyden columns), from the handed-off point (the search's parameters, L at its crossing), to
// options.tolerance on all four residuals: the chord miss and the rotation residual there (the
// crossing number is counted on the reported path: CrossingCount). The free length needs no
// table of crossings, which makes each evaluation cheap (docs/paper_notes.md, "General targets",
// point 12).
void PolishLocal(const Context& ctx, const IsoparallelOptions& options, LocalResult* r) {
  FreeLengthFunctor f{&ctx, r->regime};
  f.secant = false;
  Eigen::Vector4d v(r->x[0], r->x[1], r->x[2], r->ev.s);
  ceres::TinySolver<FreeLengthFunctor> solver;
  // options.max_iterations, no smaller cap: near the straight rolling the search ends where the
  // Jacobian is nearly singular and Newton needs up to 100 steps (docs/paper_notes.md, "General
  // targets: the whole certificate in one call").
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

// The first options.starts points of the Halton sequence (bases 2, 3, 5, 7). General targets:
// unshifted shapes (phase 0: SearchShape scans the phase), so the solution list does not depend
// on the seed; identity target (shooting only as a comparison with the enumeration): starts with
// a Cranley-Patterson shift drawn from the seed.
std::vector<Start> MakeStarts(
    const IsoparallelOptions& options, double s_limit, double radius, bool seeded, bool shapes) {
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
    // Shapes: denser towards the separatrix (k = kStartMaxModulus sin(pi u / 2)), where long
    // solutions have narrow basins in atanh k; starts: uniform in k.
    const double k = shapes ? kStartMaxModulus * std::sin(0.5 * M_PI * u[2]) : kStartMaxModulus * u[2];
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

// Local searches from every start, over the crossings beyond `covered` (the identity target's
// comparison shooting).
std::vector<std::vector<LocalResult>> SearchStarts(const Context& ctx,
                                                   const IsoparallelOptions& options,
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

}  // namespace plateball::internal::isoparallel
