// Validate and dispatch: SolveIsoparallel checks the problem and options, builds the Context and
// runs the identity target's family enumeration (isoparallel_families.h) or the shooting passes
// (shape_scan.cc for a general target, search.cc for the identity target's comparison shooting),
// then the verification (verify.cc).
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "check.h"
#include "isoparallel/stages.h"
#include "plateball/isoparallel_families.h"
#include "plateball/so3.h"
#include "rotation_trick.h"

namespace plateball {
namespace internal::isoparallel {
namespace {

// The multi-start work starts x |goal - start| within its budget (README, "Limits").
void CheckStartBudget(const IsoparallelProblem& problem, const IsoparallelOptions& options) {
  const double start_work = options.starts * (problem.goal - problem.start).norm();
  if (start_work > internal::kMaxStartsTimesChord)
    internal::ThrowInvalid("starts",
                           options.starts,
                           "starts x |goal - start| = " + internal::FormatNumber(start_work) +
                               " exceeds the multi-start budget " +
                               internal::FormatNumber(internal::kMaxStartsTimesChord));
}

// A reported solution from an enumerated family (sense = +-1: the mirror image of a rotating
// family), rotated so that its end lands on the goal.
Candidate FamilyCandidate(const Context& ctx,
                          const IsoparallelProblem& problem,
                          const ElasticaFamily& f,
                          double sense) {
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
std::vector<Candidate> SolveByFamilies(Context* ctx,
                                       const IsoparallelProblem& problem,
                                       const IsoparallelOptions& options,
                                       IsoparallelSummary* summary) {
  FamilySearchOptions fo;
  fo.length_cap_factor = options.length_cap_factor;
  fo.tolerance = options.tolerance;
  fo.threads = options.threads;
  if (options.progress) fo.progress = [&options](int m) { options.progress(m, 0); };
  FamilySearch search;
  for (int pass = 0; pass < kFamilyPasses; ++pass) {
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

// Shooting passes: search, merge, then lengthen the search until the cap is covered.
void SolveByShooting(Context* ctx,
                     const IsoparallelProblem& problem,
                     const IsoparallelOptions& options,
                     std::vector<Candidate>* found,
                     IsoparallelSummary* summary) {
  double covered = 0.0;  // crossings up to this length were already searched
  for (int pass = 0; pass < kShootingPasses; ++pass) {
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

// The solution list of a valid problem into `summary`: the identity target's families (or its
// comparison shooting), a general target's shooting, then the verification by rolling.
void Solve(const IsoparallelProblem& problem, const IsoparallelOptions& options, IsoparallelSummary* summary) {
  Context ctx = MakeContext(problem, options);
  std::vector<Candidate> found;
  const bool identity = LogSO3(ctx.target).norm() <= options.tolerance;
  ctx.identity = identity;
  summary->seeded = identity;
  if (identity && options.enumerate_families) found = SolveByFamilies(&ctx, problem, options, summary);
  if (summary->method == IsoparallelMethod::kShooting) SolveByShooting(&ctx, problem, options, &found, summary);
  summary->searched_length = ctx.s_limit;
  try {
    ReportVerified(ctx, problem, options, std::move(found), summary);
    summary->status = summary->solutions.empty() ? IsoparallelStatus::kNoSolution : IsoparallelStatus::kSolved;
    summary->message = summary->solutions.empty() ? "no start converged to a verified solution" : "";
  } catch (const std::runtime_error& e) {
    summary->status = IsoparallelStatus::kIntegrationFailure;
    summary->message = std::string("verification by rolling: ") + e.what();
    summary->solutions.clear();
  }
}

}  // namespace

void ValidateProblem(const IsoparallelProblem& problem) {
  internal::RequireCoordinates("start", problem.start);
  internal::RequireCoordinates("goal", problem.goal);
  internal::RequireFinite("start_orientation", problem.start_orientation);
  internal::RequireFinite("goal_orientation", problem.goal_orientation);
  const double chord = (problem.goal - problem.start).norm();
  if (chord == 0.0)
    internal::ThrowInvalid("goal", "(equal to start)", "the isoparallel rotation trick needs |x1 - x0| > 0");
  if (chord > internal::kMaxIsoparallelChord)  // the family search grows like chord^3 (README, "Limits")
    internal::ThrowInvalid(
        "goal", chord, "|goal - start| must be <= " + internal::FormatNumber(internal::kMaxIsoparallelChord));
  if (!IsRotation(problem.start_orientation, 1e-9))
    internal::ThrowInvalid("start_orientation", "(matrix)", "not a rotation matrix (R^T R = I, det R = 1 to 1e-9)");
  if (!IsRotation(problem.goal_orientation, 1e-9))
    internal::ThrowInvalid("goal_orientation", "(matrix)", "not a rotation matrix (R^T R = I, det R = 1 to 1e-9)");
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

}  // namespace internal::isoparallel

std::string IsoparallelOptions::Validate() const {
  using internal::InvalidValueMessage;
  if (starts < 1 || starts > kMaxStarts)
    return InvalidValueMessage("starts", starts, "must be in [1, " + std::to_string(kMaxStarts) + "]");
  if (!(length_cap_factor >= 1.0 && length_cap_factor <= kMaxLengthCapFactor))
    return InvalidValueMessage(
        "length_cap_factor", length_cap_factor, "must be in [1, " + internal::FormatNumber(kMaxLengthCapFactor) + "]");
  if (max_iterations < 1 || max_iterations > kMaxIterations)
    return InvalidValueMessage(
        "max_iterations", max_iterations, "must be in [1, " + std::to_string(kMaxIterations) + "]");
  if (!(tolerance >= internal::kMinTolerance && tolerance < 1))
    return InvalidValueMessage("tolerance", tolerance, "must be in [1e-15, 1)");
  if (threads < 1 || threads > kMaxThreads)
    return InvalidValueMessage("threads", threads, "must be in [1, " + std::to_string(kMaxThreads) + "]");
  if (!(std::isfinite(max_length) && max_length >= 0))
    return InvalidValueMessage("max_length", max_length, "must be finite and >= 0 (0 = automatic)");
  return integration.Validate();
}

IsoparallelSummary SolveIsoparallel(const IsoparallelProblem& problem, const IsoparallelOptions& options) {
  const auto t0 = std::chrono::steady_clock::now();
  internal::isoparallel::ValidateProblem(problem);
  internal::ThrowIfInvalid(options.Validate());
  internal::isoparallel::CheckStartBudget(problem, options);
  IsoparallelSummary summary;
  summary.problem = problem;
  summary.options = options;
  internal::isoparallel::Solve(problem, options, &summary);
  summary.time_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return summary;
}

}  // namespace plateball
