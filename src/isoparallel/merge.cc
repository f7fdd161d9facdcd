// Merge: each searched result that is not known yet is polished (search.cc) and, when it is a new
// distinct solution, added to the list (a general target's new solution also starts the twin
// search, twins.cc). Candidates carry a signature that tells distinct solutions apart.
#include <cmath>
#include <limits>

#include "isoparallel/stages.h"
#include "jacobi_elliptic.h"
#include "plateball/rolling.h"
#include "plateball/so3.h"

namespace plateball::internal::isoparallel {
namespace {

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

// Family test of a path of a whole number of periods: when the paths from the phase shifted by
// 0.31 and 0.67 curvature periods (the length kept) still solve the target to kFamilyTol, the
// canonical member (phase 0) replaces p and ev (true).
bool CanonicalFamilyMember(const Context& ctx, PendulumRegime regime, ElasticaParameters* p, Evaluation* ev) {
  const double u_period =
      (regime == PendulumRegime::kOscillating ? 2.0 : 1.0) * 2.0 * internal::CompleteEllipticK(std::abs(p->modulus));
  for (double frac : {0.31, 0.67}) {
    ElasticaParameters q = *p;
    q.phase += frac * u_period;
    Evaluation evq;
    if (!Evaluate(ctx, q, ev->s, &evq) || evq.residual.norm() > kFamilyTol) return false;
  }
  ElasticaParameters q = *p;
  q.phase = 0.0;  // canonical member
  Evaluation evq;
  if (!Evaluate(ctx, q, ev->s, &evq)) return false;
  *p = q;
  *ev = evq;
  return true;
}

// Builds the reported solution from a converged local result: world frame, family test. A result
// as long as the chord (to kStraightTol) is the straight segment: only a straight path is as
// short as its chord, and the shooting's parameters degenerate there (modulus -> 0 with any rate
// and phase: every such run would polish to a slightly different near-straight path). When the
// segment itself solves the target to `tolerance`, it is reported instead, the same candidate for
// every such run.
Candidate MakeCandidate(const Context& ctx, const IsoparallelProblem& problem, const LocalResult& r, double tolerance) {
  if (std::abs(r.ev.s - ctx.radius) <= kStraightTol * (1 + ctx.radius)) {
    const double residual = LogSO3(ctx.target.transpose() * RollAlongSegment(problem.start, problem.goal)).norm();
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
  if (!e.IsStraight() && whole >= 1 && std::abs(sol.periods - whole) < kWholePeriodTol * whole)
    sol.family = CanonicalFamilyMember(ctx, r.regime, &p, &ev);
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

bool Known(const std::vector<Candidate>& found, const Candidate& c, double tol) {
  for (const Candidate& f : found)
    if (SameSolution(f, c, tol)) return true;
  return false;
}

}  // namespace

// The straight segment from start to goal (p with rate 0, heading along the chord), as a solution
// of the given length (the chord) and residual.
Candidate StraightCandidate(
    const Context& ctx, const IsoparallelProblem& problem, ElasticaParameters p, double length, double residual) {
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

// Adds a search result to `found` when it polishes to a new solution; true if it did.
bool MergeResult(const Context& ctx,
                 const IsoparallelProblem& problem,
                 const IsoparallelOptions& options,
                 LocalResult* r,
                 std::vector<Candidate>* found,
                 IsoparallelSummary* summary) {
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
// a general target, each new solution's twin across a fold (TwinSearches) is tried at once, unless
// the solution lies beyond the cap by more than kTwinReach.
void MergeResults(const Context& ctx,
                  const IsoparallelProblem& problem,
                  const IsoparallelOptions& options,
                  std::vector<std::vector<LocalResult>> per_start,
                  std::vector<Candidate>* found,
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

}  // namespace plateball::internal::isoparallel
