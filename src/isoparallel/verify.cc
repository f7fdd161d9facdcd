// Verify: the solutions up to the length cap, sorted, each verified independently of the solver by
// rolling (VerifyRolling: Runge-Kutta-Fehlberg 7(8) along the path), with its crossing number,
// first conjugate point and the Maxwell pairs of the list.
#include <algorithm>
#include <cmath>
#include <limits>

#include "check.h"
#include "dynamics.h"
#include "isoparallel/stages.h"
#include "isoparallel_conjugate.h"
#include "plateball/so3.h"

namespace plateball {
namespace internal::isoparallel {
namespace {

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
  const internal::ConjugateTime c = internal::FirstConjugateTime(internal::ConjugateProblem::kPlateBall,
                                                                 internal::ExtremalDataOf(sol->parameters),
                                                                 kConjugateSearchFactor * sol->length);
  sol->conjugate_time = c.found ? c.time : std::numeric_limits<double>::infinity();
  sol->locally_optimal = sol->conjugate_time >= sol->length * (1 - kConjugateEndTolerance);
}

// The pairs of solutions of equal length (sorted by length: neighbours in runs).
std::vector<MaxwellPair> MaxwellPairs(const std::vector<IsoparallelSolution>& sols) {
  std::vector<MaxwellPair> pairs;
  for (std::size_t i = 0; i < sols.size(); ++i)
    for (std::size_t j = i + 1; j < sols.size() && sols[j].length <= sols[i].length * (1 + kMaxwellLengthTolerance);
         ++j)
      pairs.push_back({static_cast<int>(i), static_cast<int>(j)});
  return pairs;
}

}  // namespace

// The solutions up to the length cap, sorted, each verified independently by rolling
// (VerifyRolling along the path, spread over the threads; a failed integration is rethrown here).
void ReportVerified(const Context& ctx,
                    const IsoparallelProblem& problem,
                    const IsoparallelOptions& options,
                    std::vector<Candidate> found,
                    IsoparallelSummary* summary) {
  std::stable_sort(found.begin(), found.end(), [](const Candidate& a, const Candidate& b) {
    return a.solution.length < b.solution.length;
  });
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

}  // namespace internal::isoparallel

namespace {

// The verification runs at a tenth of the integration tolerances (clamped to 1e-15): the
// Runge-Kutta-Fehlberg 7(8) pair, controlled by its local error estimate, accumulates ~10x the
// tolerance over these lengths (Figure 7's shortest: 1.2e-12 rad at 1e-12, 1.4e-13 at 1e-13).
IntegrationOptions VerifyTolerances(const IntegrationOptions& integration) {
  IntegrationOptions o = integration;
  o.absolute_tolerance = std::max(internal::kMinTolerance, 0.1 * o.absolute_tolerance);
  o.relative_tolerance = std::max(internal::kMinTolerance, 0.1 * o.relative_tolerance);
  return o;
}

}  // namespace

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
                    ? static_cast<int>(whole)
                    : 1;
  const double span = solution.length / m;
  internal::RowMajor3x3 y{1, 0, 0, 0, 1, 0, 0, 0, 1};
  using Stepper = boost::numeric::odeint::runge_kutta_fehlberg78<internal::RowMajor3x3>;
  if (span > 0)
    internal::IntegrateAdaptive<Stepper>(
        rhs, y, 0.0, span, span / 16.0, VerifyTolerances(integration), [](double, const internal::RowMajor3x3&) {});
  const Eigen::Matrix3d p = ProjectToSO3(internal::MatrixFromRowMajor(y.data()));
  Eigen::Matrix3d q = p;
  for (int i = 1; i < std::max(m, 1); ++i) q = p * q;
  return ProjectToSO3(q);
}

}  // namespace plateball
