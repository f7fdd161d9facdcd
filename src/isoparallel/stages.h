// Internal: the stages of the isoparallel solver (SolveIsoparallel, isoparallel.h) and what they
// share. One input passes through them in this order:
//   solve.cc       validate the problem, build the Context, dispatch: the identity target's family
//                  enumeration, or the shooting passes (general targets; the identity target's
//                  comparison shooting);
//   shape_scan.cc  general targets: scan each shape's (start phase, length) plane for points near a
//                  solution and start a free-length search from each;
//   search.cc      the free-length search from a start, its hand-off to the polish, and the polish;
//                  the identity target's comparison shooting from random starts;
//   merge.cc       after each batch: polish the searched results that are new, keep the distinct
//                  solutions, and search from each new one of a general target for its twin;
//   twins.cc       the twin search: the continuation from a solution to its twin across a fold;
//   verify.cc      the solutions up to the cap, verified by rolling (VerifyRolling), conjugate
//                  points, Maxwell pairs.
// free_length.cc holds the rotation trick's evaluation (section 2.2) and the free-length residual
// (FreeLengthFunctor) that the search, the polish and the twin search solve; report.cc the
// summary's text. The tuning constants are in tuning.h; twins.h exposes the twin search to tests.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <limits>
#include <mutex>
#include <optional>
#include <vector>

#include "elastica_closed_rolling.h"
#include "elastica_rolling.h"
#include "isoparallel/tuning.h"
#include "parallel_for.h"
#include "plateball/elastica.h"
#include "plateball/isoparallel.h"

namespace plateball::internal::isoparallel {

// ---------------------------------------------------------------- the problem as the stages see it
struct Context {
  Eigen::Matrix3d target;  // A1 A0^-1
  double radius;           // |x1 - x0|
  double goal_angle;       // direction of x1 - x0
  double s_limit;
  // Identity target (the shooting there is only a comparison with the enumeration): the starts
  // are shifted by the seed. Any other target: unshifted, the same for every seed.
  bool identity = false;
};

// The rotation trick at one arc length: the crossing, the rotation B and the residual there.
struct Evaluation {
  double s = 0.0;     // arc length at the crossing
  double beta = 0.0;  // rotation B = RotationZ(beta)
  Eigen::Vector3d residual = Eigen::Vector3d::Zero();
};

// A search run's result, then (PolishLocal) the polished one.
struct LocalResult {
  bool converged = false;
  PendulumRegime regime = PendulumRegime::kOscillating;
  double x[3] = {0, 0, 0};
  bool searched = false;   // handed to the polish: within kSearchAccept, or kTangentHandOff at a near-tangency
  bool duplicate = false;  // the search stopped at a solution known before its batch
  Evaluation ev;
  long evaluations = 0;
};

// A known solution in the free-length search's unknowns (rate, atanh k, phase, L).
struct SearchRoot {
  PendulumRegime regime;
  Eigen::Vector4d x;
};

// A start of the search (rate, atanh k, phase), or a shape (phase 0) of the shape scan.
struct Start {
  PendulumRegime regime;
  double x[3];
};

// A solution as reported, and what tells it from the others.
struct Candidate {
  IsoparallelSolution solution;
  std::vector<Eigen::Vector2d> signature;  // world positions at s = L/3, 2L/3
};

// ---------------------------------------------------------------- the rotation trick (free_length.cc)
// The elastica of the search unknowns x = (rate, atanh k, phase) in the pendulum frame.
ElasticaParameters ToParameters(PendulumRegime regime, const double* x);
// Whether the closed-form rolling takes e's parameters and arc lengths up to s_max.
bool ClosedFormApplies(const Elastica& e, double s_max);
// The rotation trick of section 2.2 at arc length s of e (the rolling in closed form).
bool EvaluateAt(const Context& ctx, const Elastica& e, double s, Evaluation* out);
// The same for the elastica with parameters p (false where p is not admissible).
bool Evaluate(const Context& ctx, const ElasticaParameters& p, double length, Evaluation* out);
// Finite parameters and |k| < 1.
bool Admissible(const ElasticaParameters& p);
// A table of positions only over [0, s_limit] with acc's nodes: the crossings of the circle.
internal::ElasticaRollingTable CrossingTable(const Elastica& e, double s_limit, const Accuracy& acc);
// Which crossing of the circle |x - x0| = |x1 - x0| ends a path of the given length.
int CrossingCount(const Context& ctx, const Elastica& e, double length);
// Whether y (free-length unknowns) is the root `root` to kDuplicateTol.
bool SameRoot(PendulumRegime regime, const Eigen::Vector4d& y, const SearchRoot& root);

// The rotation trick without the crossing: the length L is a fourth unknown and |x(L)| - |x1 - x0|
// a fourth residual. Smooth where the crossing formulation jumps (a tangency adding or removing a
// pair of crossings, near which solutions often lie). A ceres::TinySolver functor; its members are
// defined in free_length.cc.
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
  bool Converged(const double* r) const {
    return Eigen::Map<const Eigen::Vector4d>(r).squaredNorm() / 2 < cost_threshold;
  }

  bool Admissible(const ElasticaParameters& p, double length) const;
  // The residual of a path with chord xs and rolling q.
  bool ResidualOf(const Eigen::Vector2d& xs, const Eigen::Matrix3d& q, double* r) const;
  // The residual of the path from 0 to `length` of the rolling's elastica, kept in `last`.
  bool ResidualFrom(const Elastica& e, const internal::ElasticaClosedRolling& rolling, double length, double* r) const;
  // The residuals of the last path shifted by s0 along its elastica and lengthened by h.
  bool ShiftedResiduals(const Elastica& e, double length, double s0, double h, double* rp, double* rl) const;

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
  bool Residual(const double* x, double* r, bool = false, const Elastica* base = nullptr) const;

  // Whether the last residual was evaluated at x.
  bool LastAt(const double* x) const { return last.rolling.has_value() && last.ok && std::equal(x, x + 4, last.x); }

  // The residual at x, the last one when it was evaluated there (a run that ended on an accepted point).
  bool ResidualAt(const double* x, double* r) const;

  // TinySolver's call: the residual, and the Jacobian when asked for.
  bool operator()(const double* x, double* r, double* jacobian) const;

  // The last Jacobian evaluated (a run resumed after the triage starts at its point).
  struct KeptJacobian {
    bool valid = false;
    double x[4] = {0, 0, 0, 0};
    double r[4] = {0, 0, 0, 0};
    double jacobian[16] = {};
  };
  mutable KeptJacobian kept;

  // Whether the run stalls at an accepted point of residual norm `norm` (kStallRatio).
  bool Stalls(double norm) const;
  // A zero residual and Jacobian: ends TinySolver's loop at once.
  static bool StopRun(double* r, double* jacobian);
  // Whether the Gauss-Newton step from x lands on a known solution (only near a root).
  bool ReachesKnown(const double* x, const double* r, const double* jacobian) const;
  // Far from a root, the rate and modulus columns by a Broyden update.
  bool SecantColumns(const double* x, const double* r, double* jacobian) const;
  // The rate and modulus columns from the closed-form derivatives of the last path.
  bool AnalyticColumns(const double* x, const double* r, double* jacobian) const;
  // The residual and (jacobian != nullptr) its Jacobian, column-major.
  bool Evaluate(const double* x, double* r, double* jacobian) const;
};

// ---------------------------------------------------------------- validate and dispatch (solve.cc)
// Throws std::invalid_argument naming the field of an invalid problem.
void ValidateProblem(const IsoparallelProblem& problem);
// The search context: the target reorientation, the circle of the rotation trick and the first search length.
Context MakeContext(const IsoparallelProblem& problem, const IsoparallelOptions& options);

// Runs search(i) for the starts or shapes i in [first, first + count) of `total` on the option's
// threads (results per index do not depend on the thread count) and reports progress.
template <class Search>
std::vector<std::vector<LocalResult>> SearchAll(
    int first, int count, int total, const IsoparallelOptions& options, Search&& search) {
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

// ---------------------------------------------------------------- search and polish (search.cc)
// The free-length search from a start (x0, length0); a run that reaches a `known` solution stops.
LocalResult SearchLocalFreeLength(const Context& ctx,
                                  PendulumRegime regime,
                                  const double* x0,
                                  double length0,
                                  const IsoparallelOptions& options,
                                  const std::vector<SearchRoot>* known = nullptr);
// The polish of a handed-off result to options.tolerance (r->converged).
void PolishLocal(const Context& ctx, const IsoparallelOptions& options, LocalResult* r);
// The first options.starts Halton points as starts (shapes: phase 0, denser near the separatrix).
std::vector<Start> MakeStarts(
    const IsoparallelOptions& options, double s_limit, double radius, bool seeded, bool shapes);
// Local searches from every start over the crossings beyond `covered` (the identity target's comparison shooting).
std::vector<std::vector<LocalResult>> SearchStarts(const Context& ctx,
                                                   const IsoparallelOptions& options,
                                                   double covered);

// ---------------------------------------------------------------- shape scan (shape_scan.cc)
// General targets: the shapes' scans and searches in batches, merged into `found`; the search length
// shrinks to the cap after each batch.
void SearchShapes(Context* ctx,
                  const IsoparallelProblem& problem,
                  const IsoparallelOptions& options,
                  double covered,
                  std::vector<Candidate>* found,
                  IsoparallelSummary* summary);

// ---------------------------------------------------------------- twin search (twins.cc)
// The searches started from the twins of solution r across a fold (at most two).
std::vector<LocalResult> TwinSearches(const Context& ctx,
                                      const LocalResult& r,
                                      const IsoparallelOptions& options,
                                      long* evaluations);

// ---------------------------------------------------------------- merge (merge.cc)
// The straight segment from start to goal as a solution of the given length and residual.
Candidate StraightCandidate(
    const Context& ctx, const IsoparallelProblem& problem, ElasticaParameters p, double length, double residual);
// Adds a search result to `found` when it polishes to a new solution; true if it did.
bool MergeResult(const Context& ctx,
                 const IsoparallelProblem& problem,
                 const IsoparallelOptions& options,
                 LocalResult* r,
                 std::vector<Candidate>* found,
                 IsoparallelSummary* summary);
// MergeResult for every result, and (general targets) the twin searches from each new solution.
void MergeResults(const Context& ctx,
                  const IsoparallelProblem& problem,
                  const IsoparallelOptions& options,
                  std::vector<std::vector<LocalResult>> per_start,
                  std::vector<Candidate>* found,
                  IsoparallelSummary* summary);
// The longest length reported: length_cap_factor times the shortest solution found.
double CapLength(const IsoparallelOptions& options, const std::vector<Candidate>& found);
// The found solutions as roots of the free-length search.
std::vector<SearchRoot> SearchRoots(const std::vector<Candidate>& found);

// ---------------------------------------------------------------- verify (verify.cc)
// The solutions up to the length cap, sorted and verified by rolling, into summary->solutions.
void ReportVerified(const Context& ctx,
                    const IsoparallelProblem& problem,
                    const IsoparallelOptions& options,
                    std::vector<Candidate> found,
                    IsoparallelSummary* summary);

}  // namespace plateball::internal::isoparallel
