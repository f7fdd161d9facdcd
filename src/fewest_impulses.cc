// SolveFewestImpulses (fewest_impulses.h): the driver over counts n = 1, 2, ... and the free
// search of one count: quasi-random starts refined by Levenberg-Marquardt in (s_k, log t_k),
// Newton polish to the tolerances, shortening along the arrival manifold, and the continuation
// of an arrival to fewer impulses by merging its shortest flight. The rig-limits side and the
// description of a count's row are in fewest_limits.cc (shared declarations: fewest_search.h).
#include "plateball/fewest_impulses.h"

#include <ceres/tiny_solver.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "check.h"
#include "constrained_arrival.h"
#include "dense_solve.h"
#include "exact_chain.h"
#include "fewest_search.h"
#include "field_check.h"
#include "plateball/limits.h"
#include "plateball/plate_impulse.h"
#include "plateball/so3.h"

namespace plateball {

std::string ToString(FewestImpulsesStatus status) {
  switch (status) {
    case FewestImpulsesStatus::kNotRun:
      return "not_run";
    case FewestImpulsesStatus::kFound:
      return "found";
    case FewestImpulsesStatus::kNotFound:
      return "not_found";
    case FewestImpulsesStatus::kLimitsNotMet:
      return "limits_not_met";
  }
  return "unknown";
}

std::string ToString(FewestCountVerdict verdict) {
  switch (verdict) {
    case FewestCountVerdict::kReached:
      return "reached";
    case FewestCountVerdict::kGenericallyImpossible:
      return "generically_impossible";
    case FewestCountVerdict::kNotFound:
      return "not_found";
  }
  return "unknown";
}

std::string FewestImpulsesOptions::Validate() const {
  std::string e = internal::CheckRanges(*this);  // counts, window, tolerances (the field list)
  if (!e.empty()) return e;
  e = integration.Validate();
  if (!e.empty()) return "integration." + e;
  e = search_integration.Validate();
  if (!e.empty()) return "search_integration." + e;
  return "";
}

const FewestImpulsesCount* FewestImpulsesSummary::Fewest() const {
  if (status != FewestImpulsesStatus::kFound) return nullptr;
  for (const FewestImpulsesCount& c : counts)
    if (c.reached && c.impulses == fewest) return &c;
  return nullptr;
}

std::string FewestImpulsesSummary::BriefReport() const {
  std::ostringstream os;
  os.precision(3);
  os << "FewestImpulses: " << ToString(status);
  if (const FewestImpulsesCount* f = Fewest()) {
    os << ", fewest n = " << fewest
       << (minimal_for_generic_goal ? " (fewer: 2n below the conditions, impossible for a generic goal)"
                                    : " (a smaller count was not found, not proved impossible)")
       << ", shortest T found = " << f->total_time << ", length = " << f->path_length
       << ", position error = " << f->position_error << ", orientation error = " << f->orientation_error << " rad";
  }
  os << ", counts searched = " << counts.size() << ", window T <= " << max_total_time;
  if (!message.empty()) os << " (" << message << ")";
  return os.str();
}

namespace {

using internal::ChainNode;

using internal::fewest::Admit;
using internal::fewest::CheckArrival;
using internal::fewest::Consider;
using internal::fewest::ConstrainedFor;
using internal::fewest::CountBest;
using internal::fewest::Describe;
using internal::fewest::Evaluate;
using internal::fewest::Search;
using internal::fewest::TotalImpulse;

// The arrival conditions (the orientation's three first with orientation_only) at the chain's end.
Eigen::VectorXd Conditions(const Search& s, const ChainNode& end) {
  const Eigen::Matrix<double, 5, 1> r = internal::ArrivalResidual(end, s.problem->x1, s.problem->A1);
  return s.conditions == 5 ? Eigen::VectorXd(r) : Eigen::VectorXd(r.tail<3>());
}

}  // namespace

namespace internal::fewest {

// Rolls u at `integration`; with `jac` also the Jacobian of the conditions (m x 2n).
Eigen::VectorXd Evaluate(const Search& s,
                         const Eigen::VectorXd& u,
                         const IntegrationOptions& integration,
                         std::vector<ChainNode>* nodes,
                         Eigen::MatrixXd* jac) {
  nodes->assign(static_cast<std::size_t>(u.size() / 2) + 1, s.start);
  internal::ChainJacobian cj;
  internal::RollChain(s.problem->model.lambda(), u, integration, nodes, jac ? &cj : nullptr);
  ++*s.rollouts;
  if (jac) {
    const Eigen::MatrixXd full = internal::ArrivalJacobian(cj, nodes->back(), s.problem->A1);
    *jac = s.conditions == 5 ? full : Eigen::MatrixXd(full.bottomRows<3>());
  }
  return Conditions(s, nodes->back());
}

// Keeps the arrival u (on the grid `ticks` with a rig tick) if it is the shortest of the count so
// far; an equal time keeps the earlier one.
void Consider(const Eigen::VectorXd& u,
              const std::vector<ChainNode>& nodes,
              const std::vector<long long>& ticks,
              CountBest* best) {
  const double t = u.tail(u.size() / 2).sum();
  if (t >= best->time) return;
  best->time = t;
  best->u = u;
  best->nodes = nodes;
  best->ticks = ticks;
  best->blocking.clear();
}

}  // namespace internal::fewest

namespace {  // the unnamed namespace above, reopened: its using-declarations hold here

// The arrival conditions in v = (s_k, log t_k) for ceres::TinySolver, exact Jacobian. A point
// outside the window (a flight longer than the window, a failed integration) gives NaN, which
// TinySolver rejects as a step.
class ArrivalFunctor {
 public:
  using Scalar = double;
  enum { NUM_RESIDUALS = Eigen::Dynamic, NUM_PARAMETERS = Eigen::Dynamic };
  ArrivalFunctor(const Search& s, int n) : s_(s), n_(n) {}
  int NumResiduals() const { return s_.conditions; }
  int NumParameters() const { return 2 * n_; }

  bool operator()(const double* v, double* r, double* jacobian) const {
    Eigen::VectorXd u = Eigen::Map<const Eigen::VectorXd>(v, 2 * n_);
    u.tail(n_) = u.tail(n_).array().exp();
    Eigen::Map<Eigen::VectorXd> res(r, s_.conditions);
    if (!u.allFinite() || u.tail(n_).sum() > s_.max_total_time) {
      res.setConstant(std::numeric_limits<double>::quiet_NaN());
      return false;
    }
    std::vector<ChainNode> nodes;
    Eigen::MatrixXd jac;
    try {
      res = Evaluate(s_, u, s_.options->search_integration, &nodes, jacobian ? &jac : nullptr);
    } catch (const std::runtime_error&) {
      res.setConstant(std::numeric_limits<double>::quiet_NaN());
      return false;
    }
    if (jacobian) {
      jac.rightCols(n_) = jac.rightCols(n_) * u.tail(n_).asDiagonal();  // d/d log t = t d/dt
      Eigen::Map<Eigen::MatrixXd>(jacobian, s_.conditions, 2 * n_) = jac;
    }
    return true;
  }

 private:
  const Search& s_;
  int n_;
};

// Radical inverse of i in `base` (the Halton sequence's coordinate).
double RadicalInverse(int i, int base) {
  double f = 1.0, r = 0.0;
  for (; i > 0; i /= base) {
    f /= base;
    r += f * (i % base);
  }
  return r;
}

// Start i for n impulses: directions s_k in [-pi, pi), total time in the window's (0.1, 1]
// scaled by the i-th point, split by weights in [0.25, 1.25).
Eigen::VectorXd StartPoint(const Search& s, int n, int i) {
  static constexpr int kPrimes[] = {2,   3,   5,   7,   11,  13,  17,  19,  23,  29,  31,  37,  41,  43,
                                    47,  53,  59,  61,  67,  71,  73,  79,  83,  89,  97,  101, 103, 107,
                                    109, 113, 127, 131, 137, 139, 149, 151, 157, 163, 167, 173, 179};
  Eigen::VectorXd v(2 * n);
  Eigen::VectorXd w(n);
  for (int k = 0; k < n; ++k) {
    v[k] = 2.0 * M_PI * RadicalInverse(i + 1, kPrimes[k]) - M_PI;
    w[k] = 0.25 + RadicalInverse(i + 1, kPrimes[n + k]);
  }
  const double total = s.max_total_time * (0.1 + 0.8 * RadicalInverse(i + 1, kPrimes[2 * n]));
  v.tail(n) = (total * w / w.sum()).array().log();
  return v;
}

bool MeetsTolerances(const Search& s, const Eigen::VectorXd& r, double position_tol, double orientation_tol) {
  return s.conditions == 3 ? r.norm() <= orientation_tol
                           : r.head<2>().norm() <= position_tol && r.tail<3>().norm() <= orientation_tol;
}

// Newton steps (minimum-norm, fresh exact Jacobians at the search tolerance, halved while they do
// not reduce |r|) on the values rolled at `values` until |r| meets (position_tol, orientation_tol).
bool Restore(const Search& s,
             const IntegrationOptions& values,
             double position_tol,
             double orientation_tol,
             Eigen::VectorXd* u,
             std::vector<ChainNode>* nodes,
             Eigen::VectorXd* r) {
  const int n = static_cast<int>(u->size() / 2);
  *r = Evaluate(s, *u, values, nodes, nullptr);
  for (int i = 0; i < 8 && !MeetsTolerances(s, *r, position_tol, orientation_tol); ++i) {
    Eigen::MatrixXd jac;
    std::vector<ChainNode> trial;
    Evaluate(s, *u, s.options->search_integration, &trial, &jac);
    const Eigen::VectorXd du = -internal::MinimumNormSolve(jac, *r);
    bool reduced = false;
    for (double alpha = 1.0; alpha > 0.05 && !reduced; alpha *= 0.5) {
      const Eigen::VectorXd u_new = *u + alpha * du;
      if ((u_new.tail(n).array() <= 0).any()) continue;
      const Eigen::VectorXd r_new = Evaluate(s, u_new, values, &trial, nullptr);
      if (!(r_new.norm() < r->norm())) continue;
      *u = u_new;
      *nodes = trial;
      *r = r_new;
      reduced = true;
    }
    if (!reduced) return false;
  }
  return MeetsTolerances(s, *r, position_tol, orientation_tol) && u->tail(n).sum() <= s.max_total_time;
}

// To the final tolerances with the 1e-14 rollouts.
bool Polish(const Search& s, Eigen::VectorXd* u, std::vector<ChainNode>* nodes, Eigen::VectorXd* r) {
  return Restore(
      s, s.options->integration, s.options->position_tolerance, s.options->orientation_tolerance, u, nodes, r);
}

// Shortens the total time of an arrival along the arrival manifold (2n > conditions): steps
// along the projection of -grad T onto the null space of the conditions' Jacobian in
// (s_k, log t_k), each followed by Restore at the search tolerance; a step is kept when T falls.
void Shorten(const Search& s, Eigen::VectorXd* u) {
  const int n = static_cast<int>(u->size() / 2);
  if (2 * n <= s.conditions) return;
  double step = 0.5;
  for (int it = 0; it < 12 && step > 1e-3; ++it) {
    Eigen::MatrixXd jac;
    std::vector<ChainNode> nodes;
    Evaluate(s, *u, s.options->search_integration, &nodes, &jac);
    const Eigen::VectorXd t = u->tail(n);
    jac.rightCols(n) = jac.rightCols(n) * t.asDiagonal();
    Eigen::VectorXd g = Eigen::VectorXd::Zero(2 * n);
    g.tail(n) = t;  // dT/d log t_k
    Eigen::VectorXd d = -(g - internal::MinimumNormSolve(jac, jac * g));
    if (d.norm() < 1e-9) return;
    d *= step / d.norm();
    Eigen::VectorXd trial = *u;
    trial.head(n) += d.head(n);
    trial.tail(n) = (t.array().log() + d.tail(n).array()).exp();
    Eigen::VectorXd r;
    if (Restore(s, s.options->search_integration, 1e-9, 1e-9, &trial, &nodes, &r) &&
        trial.tail(n).sum() < t.sum() - 1e-9) {
      *u = trial;
      step = std::min(1.0, 2.0 * step);
    } else {
      step *= 0.25;
    }
  }
}

// The arrival of count n - 1 with its longest flight split in two by a zero impulse: an arrival
// of count n with the same total time (so that the Pareto table's times do not increase).
Eigen::VectorXd Split(const Eigen::VectorXd& u) {
  const int n = static_cast<int>(u.size() / 2);
  int longest = 0;
  u.tail(n).maxCoeff(&longest);
  Eigen::VectorXd v(2 * n + 2);
  for (int k = 0, j = 0; k < n; ++k, ++j) {
    v[j] = u[k];
    v[n + 1 + j] = u[n + k];
    if (k == longest) {
      v[n + 1 + j] *= 0.5;
      ++j;
      v[j] = 0.0;
      v[n + 1 + j] = 0.5 * u[n + k];
    }
  }
  return v;
}

// The solver of count n's starts.
ceres::TinySolver<ArrivalFunctor> CountSolver(const Search& s) {
  ceres::TinySolver<ArrivalFunctor> solver;
  solver.options.max_num_iterations = s.options->max_iterations;
  solver.options.cost_threshold = 0.5 * 1e-14;  // |r| < 1e-7: Newton's Restore takes over
  solver.options.function_tolerance = 1e-14;
  solver.options.gradient_tolerance = 1e-16;
  solver.options.parameter_tolerance = 1e-12;
  return solver;
}

// The arrivals that count for the row: those within the limits with limits, else all.
int Met(const Search& s, const FewestImpulsesCount& row) { return s.limited ? row.within_limits : row.arrived; }

// Rolls the refined point u (flight times, not logs) of count row->impulses; counts it as an
// arrival when it polishes to the tolerances within the window, else keeps it as the closest.
void Try(const Search& s, Eigen::VectorXd u, FewestImpulsesCount* row, CountBest* best) {
  ++row->starts;
  std::vector<ChainNode> nodes;
  Eigen::VectorXd r;
  try {
    r = Evaluate(s, u, s.options->search_integration, &nodes, nullptr);
    if (r.norm() < 1e-2 && Polish(s, &u, &nodes, &r)) {
      ++row->arrived;
      if (s.limited)
        Admit(s, u, nodes, row, best);
      else
        Consider(u, nodes, {}, best);
    } else if (!std::isfinite(best->time) && !best->feasible_closest && r.allFinite() && r.norm() < best->closest) {
      best->closest = r.norm();
      best->u = u;
      best->nodes = nodes;
    }
  } catch (const std::runtime_error&) {
    // a start whose flights cannot be integrated is not a candidate
  }
}

// Levenberg-Marquardt from v = (s_k, log t_k), then Try.
void Refine(const Search& s, Eigen::VectorXd v, FewestImpulsesCount* row, CountBest* best) {
  const int n = row->impulses;
  ArrivalFunctor f(s, n);
  ceres::TinySolver<ArrivalFunctor> solver = CountSolver(s);
  solver.Solve(f, &v);
  Eigen::VectorXd u = v;
  u.tail(n) = v.tail(n).array().exp();
  Try(s, u, row, best);
}

// The unknowns a rig tick leaves free for count n: every flight time ends at a grid time except the
// last without a stop, so n turns (+ 1). The grid times are countably many choices, each leaving
// fewer unknowns than conditions a null set of goals: such a count reaches no generic goal.
int FreeOnGrid(const Search& s, int n) {
  if (!(s.limited && s.problem->limits.tick > 0)) return 2 * n;
  return n + (s.problem->stop_at_goal ? 0 : 1);
}

// The row from the count's best: an arrival is shortened along the arrival manifold first (with
// limits only when the shortened arrival still meets them, and never with a tick).
void Conclude(const Search& s, CountBest* best, FewestImpulsesCount* row) {
  row->reached = Met(s, *row) > 0;
  const bool generic = 2 * row->impulses < s.conditions || FreeOnGrid(s, row->impulses) < s.conditions;
  row->verdict = row->reached ? FewestCountVerdict::kReached
                 : generic    ? FewestCountVerdict::kGenericallyImpossible
                              : FewestCountVerdict::kNotFound;
  if (row->reached && !(s.limited && s.problem->limits.tick > 0)) {
    Eigen::VectorXd u = best->u;
    std::vector<ChainNode> nodes;
    Eigen::VectorXd r;
    try {
      Shorten(s, &u);
      if (Polish(s, &u, &nodes, &r) && (!s.limited || (internal::MeetsLimits(ConstrainedFor(s, row->impulses), u) &&
                                                       CheckArrival(s, u, nodes, {}).passed)))
        Consider(u, nodes, {}, best);
    } catch (const std::runtime_error&) {
      // keep the arrival found before shortening
    }
  }
  if (best->u.size() > 0) Describe(s, *best, row);
  row->parameters = best->u;
}

// All starts of count n (the first the previous count's arrival split, when there is one). A
// count with 2n >= conditions that no start reached continues up to adaptive_starts starts.
FewestImpulsesCount SearchCount(const Search& s, int n, const Eigen::VectorXd& previous) {
  FewestImpulsesCount row;
  row.impulses = n;
  CountBest best;
  const int seeded = previous.size() > 0 ? 1 : 0;
  if (seeded) Try(s, Split(previous), &row, &best);
  const int budget =
      2 * n >= s.conditions ? std::max(s.options->starts, s.options->adaptive_starts) : s.options->starts;
  for (int i = 0; row.starts < budget && row.arrived < s.options->arrivals_per_count; ++i) {
    if (row.starts >= s.options->starts && Met(s, row) > 0) break;  // settled: the count is reached
    if (s.options->progress) s.options->progress(n, (*s.starts)++);
    Refine(s, StartPoint(s, n, i), &row, &best);
  }
  Conclude(s, &best, &row);
  return row;
}

// Projected descent of log t_k along the arrival manifold of u's count (2n > conditions), each
// step restored onto the manifold at the search tolerance, until t_k is below kMergeFraction of
// the total time. Returns false when the descent stalls first.
constexpr double kMergeFraction = 1e-4;
bool ShrinkFlight(const Search& s, int k, Eigen::VectorXd* u) {
  const int n = static_cast<int>(u->size() / 2);
  double step = 0.5;
  for (int it = 0; it < 60 && step > 1e-3; ++it) {
    const Eigen::VectorXd t = u->tail(n);
    if (t[k] < kMergeFraction * t.sum()) return true;
    Eigen::MatrixXd jac;
    std::vector<ChainNode> nodes;
    Evaluate(s, *u, s.options->search_integration, &nodes, &jac);
    jac.rightCols(n) = jac.rightCols(n) * t.asDiagonal();
    Eigen::VectorXd g = Eigen::VectorXd::Zero(2 * n);
    g[n + k] = 1.0;  // d log t_k
    Eigen::VectorXd d = -(g - internal::MinimumNormSolve(jac, jac * g));
    if (d.norm() < 1e-9) return false;
    d *= step / d.norm();
    Eigen::VectorXd trial = *u;
    trial.head(n) += d.head(n);
    trial.tail(n) = (t.array().log() + d.tail(n).array()).exp();
    Eigen::VectorXd r;
    if (Restore(s, s.options->search_integration, 1e-9, 1e-9, &trial, &nodes, &r) && trial[n + k] < t[k]) {
      *u = trial;
      step = std::min(2.0, 2.0 * step);
    } else {
      step *= 0.25;
    }
  }
  return (*u)[n + k] < kMergeFraction * u->tail(n).sum();
}

// u of count n + 1 with flight k (of length ~0) removed: impulses k and k + 1 merge (their turns
// of psi add); a vanishing last flight removes the last impulse. Returns (s_j, log t_j) of count n.
Eigen::VectorXd Merge(const Eigen::VectorXd& u, int k) {
  const int m = static_cast<int>(u.size() / 2), n = m - 1;
  Eigen::VectorXd v(2 * n);
  for (int j = 0, src = 0; j < n; ++j, ++src) {
    if (src == k) {
      if (k + 1 < m) {
        v[j] = u[k] + u[k + 1];
        v[n + j] = std::log(u[m + k + 1]);
        ++src;
        continue;
      }
    }
    v[j] = u[src];
    v[n + j] = std::log(u[m + src]);
  }
  return v;
}

// Continuation into count n from count n + 1's arrival u: each flight in turn (shortest first)
// is shrunk to zero and the merged point refined. Returns the row when one arrives.
std::optional<FewestImpulsesCount> Continue(const Search& s, int n, const Eigen::VectorXd& u) {
  const int m = n + 1;
  std::vector<int> order(static_cast<std::size_t>(m));
  for (int k = 0; k < m; ++k) order[static_cast<std::size_t>(k)] = k;
  std::sort(order.begin(), order.end(), [&](int a, int b) { return u[m + a] < u[m + b]; });
  FewestImpulsesCount row;
  row.impulses = n;
  CountBest best;
  Search merged = s;  // the row is dropped unless it arrives: no closest feasible arrival is reported
  merged.closest_wanted = false;
  for (int k : order) {
    Eigen::VectorXd w = u;
    try {
      if (!ShrinkFlight(s, k, &w)) continue;
    } catch (const std::runtime_error&) {
      continue;
    }
    Refine(merged, Merge(w, k), &row, &best);
    if (Met(s, row) > 0) break;
  }
  if (Met(s, row) == 0) return std::nullopt;
  Conclude(s, &best, &row);
  row.by_continuation = true;
  return row;
}

void ValidateProblem(const FewestImpulsesProblem& p) {
  internal::RequireFinite("initial.theta", p.initial.theta);
  internal::RequireFinite("initial.phi", p.initial.phi);
  internal::RequireFinite("initial.psi", p.initial.psi);
  internal::ValidateStartAndGoal(p.mu, p.x0, p.x1, p.A0, p.A1);
  if (p.limits.Empty()) return;
  if (p.orientation_only)
    internal::ThrowInvalid("orientation_only",
                           "true",
                           "the rig's limits need the goal position (the plate, obstacle and stroke limits hold "
                           "along a path to x1)");
  internal::ValidateRigProblem(p.limits, p.physical, p.x0, p.x1);
}

// The search window's rolling length sqrt(mu) T must stay within limits::kMaxFewestWindowLength: named by
// max_total_time when the caller set the window, else by the goal whose distance sets it.
void RequireBoundedWindow(const FewestImpulsesProblem& p, const FewestImpulsesOptions& o, double window) {
  const double length = std::sqrt(p.mu) * window;
  if (length <= limits::kMaxFewestWindowLength) return;
  const std::string why = "the search window rolls sqrt(mu) T = " + internal::FormatNumber(length) +
                          " radii, more than the limit " + internal::FormatNumber(limits::kMaxFewestWindowLength) +
                          ": plan along a path and steer piece by piece";
  if (o.max_total_time > 0) internal::ThrowInvalid("max_total_time", internal::FormatNumber(o.max_total_time), why);
  internal::ThrowInvalid("x1",
                         "(" + internal::FormatNumber(p.x1.x()) + ", " + internal::FormatNumber(p.x1.y()) + ")",
                         "the goal is " + internal::FormatNumber((p.x1 - p.x0).norm()) + " radii from x0: " + why);
}

std::string Searched(const Search& s, int last) {
  std::ostringstream os;
  os << "n = 1.." << last << ", " << s.options->starts << " Halton starts per n (up to "
     << std::max(s.options->starts, s.options->adaptive_starts)
     << " while a count with 2n >= conditions has no arrival, then continuation from count n + 1; directions in [-pi, "
        "pi), total time in ["
     << 0.1 * s.max_total_time << ", " << 0.9 * s.max_total_time << "]), Levenberg-Marquardt (ceres::TinySolver, exact"
     << " Jacobian) in (delta psi, log t), window T <= " << s.max_total_time << "; " << s.conditions
     << " conditions on 2n unknowns";
  return os.str();
}

int FirstReached(const std::vector<FewestImpulsesCount>& counts) {
  for (const FewestImpulsesCount& c : counts)
    if (c.reached) return c.impulses;
  return 0;
}

// After count n arrived: counts below it with 2k >= conditions that no start reached are tried by
// continuation, downwards while it succeeds.
void ContinueDown(const Search& s, std::vector<FewestImpulsesCount>* counts) {
  for (std::size_t i = counts->size() - 1; i >= 1; --i) {
    FewestImpulsesCount& below = (*counts)[i - 1];
    if (below.reached || below.verdict != FewestCountVerdict::kNotFound) return;
    std::optional<FewestImpulsesCount> row = Continue(s, below.impulses, (*counts)[i].parameters);
    if (!row) return;
    row->starts += below.starts;
    below = *row;
  }
}

// The counts with exact arrivals (within the limits or not), "2, 3"; empty when none.
std::string ArrivedWithoutLimits(const std::vector<FewestImpulsesCount>& counts) {
  std::string out;
  for (const FewestImpulsesCount& c : counts)
    if (c.arrived > 0) out += (out.empty() ? "" : ", ") + std::to_string(c.impulses);
  return out;
}

// The limits that block the counts with exact arrivals, each once, in the order met.
std::vector<std::string> Blocking(const std::vector<FewestImpulsesCount>& counts) {
  std::vector<std::string> out;
  for (const FewestImpulsesCount& c : counts)
    for (const std::string& name : c.blocking)
      if (std::find(out.begin(), out.end(), name) == out.end()) out.push_back(name);
  return out;
}

std::string Join(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out.empty() ? "none found (the constrained solver found no feasible point)" : out;
}

// The goal is met at the start (within the tolerances): the fewest count is 0, the only row
// the start itself (a rolling start with stop_at_goal stops there).
FewestImpulsesSummary MetAtStart(const Search& s, double turn, FewestImpulsesSummary out) {
  const FewestImpulsesProblem& p = *s.problem;
  FewestImpulsesCount row;
  row.arrived = 1;
  row.reached = true;
  row.position_error = s.conditions == 5 ? (p.x1 - p.x0).norm() : 0.0;
  row.orientation_error = turn;
  row.x_final = p.x0;
  row.A_final = s.start.A;
  if (p.stop_at_goal && !p.start_at_rest) row.stop = internal::StopImpulse(p.model, p.mu, s.start, 0.0);
  row.total_impulse = TotalImpulse(p, {}, row.stop);
  out.counts.push_back(row);
  out.fewest = 0;
  out.minimal_for_generic_goal = true;  // no count is smaller than 0
  out.status = FewestImpulsesStatus::kFound;
  out.message = "the goal is met at the start: 0 impulses";
  out.searched = "nothing: the start meets the goal within the tolerances";
  return out;
}

}  // namespace

constexpr double kWindowFactor = 1.5;

FewestImpulsesSummary SolveFewestImpulses(const FewestImpulsesProblem& problem, const FewestImpulsesOptions& options) {
  internal::ThrowIfInvalid(options.Validate());
  ValidateProblem(problem);
  FewestImpulsesSummary out;
  Search s;
  s.problem = &problem;
  s.options = &options;
  s.start = internal::StartNode(problem.model, problem.initial, problem.mu, problem.x0, problem.A0);
  s.conditions = problem.orientation_only ? 3 : 5;
  s.rollouts = &out.rollouts;
  s.limited = !problem.limits.Empty();
  s.summary = &out;
  out.limited = s.limited;
  const double turn = LogSO3(problem.A1.transpose() * s.start.A).norm();
  const double distance = problem.orientation_only ? 0.0 : (problem.x1 - problem.x0).norm();
  s.max_total_time = options.max_total_time > 0
                         ? options.max_total_time
                         : kWindowFactor * (distance + turn + 2.0 * M_PI) / std::sqrt(problem.mu);
  RequireBoundedWindow(problem, options, s.max_total_time);
  out.max_total_time = s.max_total_time;
  int starts = 0;
  s.starts = &starts;
  if (distance <= options.position_tolerance && turn <= options.orientation_tolerance)
    return MetAtStart(s, turn, std::move(out));
  int last = 0;
  for (int n = 1; n <= options.max_impulses; ++n) {
    if (out.fewest > 0 && n >= out.fewest + options.pareto_counts) break;
    const Eigen::VectorXd previous =
        !out.counts.empty() && out.counts.back().reached ? out.counts.back().parameters : Eigen::VectorXd();
    out.counts.push_back(SearchCount(s, n, previous));
    last = n;
    if (out.counts.back().reached) ContinueDown(s, &out.counts);
    out.fewest = FirstReached(out.counts);
  }
  out.minimal_for_generic_goal = out.fewest > 0;
  for (const FewestImpulsesCount& c : out.counts)
    if (c.impulses < out.fewest && c.verdict != FewestCountVerdict::kGenericallyImpossible)
      out.minimal_for_generic_goal = false;
  out.searched = Searched(s, last);
  if (out.fewest > 0) {
    out.status = FewestImpulsesStatus::kFound;
    out.message.clear();
  } else if (s.limited && !ArrivedWithoutLimits(out.counts).empty()) {
    out.status = FewestImpulsesStatus::kLimitsNotMet;
    out.blocking = Blocking(out.counts);
    out.message =
        "no count up to max_impulses = " + std::to_string(options.max_impulses) +
        " arrived within the rig's limits (counts that arrive without them: " + ArrivedWithoutLimits(out.counts) +
        "); blocked by " + Join(out.blocking) + " (closest feasible arrival per count reported)";
  } else {
    out.status = FewestImpulsesStatus::kNotFound;
    out.message = "no count up to max_impulses = " + std::to_string(options.max_impulses) +
                  " arrived within the search (closest arrival per count reported)";
  }
  return out;
}

ExactArrivalProblem ReplayProblemFor(const FewestImpulsesProblem& problem, int impulses) {
  ExactArrivalProblem p;
  p.model = problem.model;
  p.initial = problem.initial;
  p.mu = problem.mu;
  p.A0 = problem.A0;
  p.x0 = problem.x0;
  const bool apart = (problem.x1 - problem.x0).norm() > 1e-9;
  p.reference = Path({SmoothCurve::Line(problem.x0, apart ? problem.x1 : problem.x0 + Eigen::Vector2d::UnitX())});
  p.impulses = impulses;
  p.x1 = problem.x1;
  p.A1 = problem.A1;
  p.start_at_rest = problem.start_at_rest;
  p.stop_at_goal = problem.stop_at_goal;
  p.limits = problem.limits;
  p.physical = problem.physical;
  return p;
}

}  // namespace plateball
