// The twin search: solutions of a general target often come in close pairs born at a fold of the
// free-length map, and a start near the pair converges to one of them. From each new solution the
// curve on which all residuals but one vanish is followed both ways (a predictor-corrector
// continuation), and a sign change of the last residual starts a search for the twin.
#include "isoparallel/twins.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/SVD>
#include <cmath>

#include "check.h"
#include "dense_solve.h"
#include "isoparallel/stages.h"

namespace plateball::internal::isoparallel {
namespace {

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
  const Eigen::Vector4d t = internal::OrientedNullVector(a);
  return TangentOrientation(w, jac, t) * orientation < 0 ? -t : t;
}

// Corrector: minimum-norm Newton steps on H from y (false: |H| still above kTwinCurveTol after
// kTwinCorrections steps), the first with the Jacobian `previous` of the last curve point (one
// residual), the others with the Jacobian where they start: next to a tangency of the chord with
// the circle (where fold pairs sit) it changes quickly along L. `out` gets the Jacobian at the end.
bool CorrectOntoCurve(const FreeLengthFunctor& f,
                      const CurveFrame& w,
                      const Eigen::Matrix4d& previous,
                      Eigen::Vector4d y,
                      CurvePoint* out) {
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
bool FollowCurve(const FreeLengthFunctor& f,
                 const CurveFrame& w,
                 const Eigen::Vector4d& u,
                 const CurvePoint& start,
                 const Eigen::Vector4d& direction,
                 Eigen::Vector4d* twin_start) {
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

}  // namespace

// Solutions of a general target often come in close pairs born at a fold (T4 of
// docs/paper_notes.md: 22.73757780 and 22.75708870), and a start near the pair converges to one of
// them. From each new solution x* the curve of FollowCurve is followed both ways; a sign change of
// g starts a search (at most two: `twins`).
std::vector<LocalResult> TwinSearches(const Context& ctx,
                                      const LocalResult& r,
                                      const IsoparallelOptions& options,
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

}  // namespace plateball::internal::isoparallel

namespace plateball::internal {

std::vector<IsoparallelSolution> IsoparallelTwins(const IsoparallelProblem& problem,
                                                  const IsoparallelSolution& solution,
                                                  const IsoparallelOptions& options) {
  isoparallel::ValidateProblem(problem);
  ThrowIfInvalid(options.Validate());
  isoparallel::Context ctx = isoparallel::MakeContext(problem, options);
  ctx.s_limit = std::max(ctx.s_limit, 2.0 * solution.length);
  const ElasticaParameters& p = solution.parameters;
  isoparallel::LocalResult r;
  r.regime = p.regime;
  r.x[0] = p.rate;
  r.x[1] = std::atanh(p.modulus);
  r.x[2] = p.phase;
  r.ev.s = solution.length;
  isoparallel::Candidate given;
  given.solution = solution;
  given.signature = {solution.PositionAt(solution.length / 3), solution.PositionAt(2 * solution.length / 3)};
  std::vector<isoparallel::Candidate> found{given};
  IsoparallelSummary summary;
  for (isoparallel::LocalResult& twin : isoparallel::TwinSearches(ctx, r, options, &summary.evaluations))
    isoparallel::MergeResult(ctx, problem, options, &twin, &found, &summary);
  std::vector<IsoparallelSolution> twins;
  for (std::size_t i = 1; i < found.size(); ++i) twins.push_back(found[i].solution);
  return twins;
}

}  // namespace plateball::internal
