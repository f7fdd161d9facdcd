#include "plateball/reach.h"

#include <ceres/tiny_solver.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <nlopt.hpp>
#include <sstream>
#include <stdexcept>

#include "check.h"
#include "field_check.h"
#include "golden_section.h"
#include "reach_internal.h"

namespace plateball {
namespace {

using internal::CircularDistance;
using internal::kTwoPi;
using internal::WrapTwoPi;
// Two refined solutions are the same when s (mod 2 pi) and t agree to this (the refinement
// converges to ~1e-13; distinct transversal solutions are separated by far more).
constexpr double kSameSolution = 1e-7;
// Cells of the scan grid in each time block tested against the target together.
constexpr int kBlockSteps = 16;
// Work budgets of one Reach call (README, "Limits"), checked up front by ReachOptions::Validate.
constexpr double kMaxReachScanNodes = 1e8;        // horizon_periods x scan_directions x scan_steps_per_period
constexpr double kMaxReachRefinePeriods = 25600;  // horizon_periods x max_candidates

double Cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

struct Box {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = Eigen::Vector2d::Constant(-std::numeric_limits<double>::infinity());
  void Add(const Eigen::Vector2d& p) {
    lo = lo.cwiseMin(p);
    hi = hi.cwiseMax(p);
  }
};

// A starting point for the refinement.
struct Candidate {
  double s = 0.0;
  double t = 0.0;
  int sign = 0;  // orientation of the scan cell: the sheet of the map (s, t) -> x
  bool fold = false;
  double distance = 0.0;  // fold seeds: distance of the target to the cell's linear image
};

// The scan: one RK4-tabulated period for each of ns directions s_i = 2 pi i / ns; the node
// (i, j) is t_j = j h, x = x0 + x_i(t_j mod T) + floor(t_j / T) drift_i.
class Scan {
 public:
  Scan(const ReachProblem& p, const ReachOptions& o, double period, double horizon)
      : ns_(o.scan_directions), n_(o.scan_steps_per_period) {
    h_ = period / n_;
    ds_ = kTwoPi / ns_;
    m_ = static_cast<int>(std::ceil(horizon / h_ - 1e-9));
    m_ = std::max(m_, 1);
    tab_.resize(static_cast<std::size_t>(ns_));
    std::vector<internal::ReachDirection> dirs(static_cast<std::size_t>(ns_));
    for (int i = 0; i < ns_; ++i)
      dirs[static_cast<std::size_t>(i)] = internal::DirectionFor(p.start, p.mu, p.model.lambda(), i * ds_);
    internal::TabulatePeriods(dirs.data(), ns_, p.model.lambda(), period, n_, tab_.data());
    blocks_ = (n_ + kBlockSteps - 1) / kBlockSteps;
    boxes_.assign(static_cast<std::size_t>(ns_ * blocks_), Box());
    for (int i = 0; i < ns_; ++i)
      for (int b = 0; b < blocks_; ++b) {
        Box& box = boxes_[static_cast<std::size_t>(i * blocks_ + b)];
        for (int r = b * kBlockSteps; r <= std::min((b + 1) * kBlockSteps, n_); ++r)
          box.Add(Tab(i).x[static_cast<std::size_t>(r)]);
      }
  }

  int ns() const { return ns_; }
  int n() const { return n_; }
  int m() const { return m_; }
  double h() const { return h_; }
  double ds() const { return ds_; }
  const internal::ScanPeriod& Tab(int i) const { return tab_[static_cast<std::size_t>(((i % ns_) + ns_) % ns_)]; }
  // Position relative to x0 of node (i, j).
  Eigen::Vector2d Node(int i, int j) const {
    const internal::ScanPeriod& tp = Tab(i);
    const int k = j / n_, r = j % n_;
    return tp.x[static_cast<std::size_t>(r)] + static_cast<double>(k) * tp.drift;
  }
  Eigen::Vector2d NodeVelocity(int i, int j) const { return Tab(i).v[static_cast<std::size_t>(j % n_)]; }
  // Bounding box (relative to x0) of the nodes of direction i in block b of period k.
  Box BlockBox(int i, int b, int k) const {
    Box box = boxes_[static_cast<std::size_t>((((i % ns_) + ns_) % ns_) * blocks_ + b)];
    const Eigen::Vector2d shift = static_cast<double>(k) * Tab(i).drift;
    box.lo += shift;
    box.hi += shift;
    return box;
  }
  int blocks() const { return blocks_; }

 private:
  int ns_, n_, m_ = 0, blocks_ = 0;
  double h_ = 0.0, ds_ = 0.0;
  std::vector<internal::ScanPeriod> tab_;
  std::vector<Box> boxes_;
};

// Barycentric coordinates of q in triangle (a, b, c); false for a degenerate triangle.
bool Barycentric(const Eigen::Vector2d& a,
                 const Eigen::Vector2d& b,
                 const Eigen::Vector2d& c,
                 const Eigen::Vector2d& q,
                 double* l1,
                 double* l2,
                 double* l3) {
  const double area = Cross(b - a, c - a);
  if (!(std::abs(area) > 1e-300)) return false;
  *l1 = Cross(b - q, c - q) / area;
  *l2 = Cross(c - q, a - q) / area;
  *l3 = Cross(a - q, b - q) / area;
  return true;
}

// Orientation of the quad (a, b, c, d): sign of its signed area (diagonals' cross product).
int QuadSign(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c, const Eigen::Vector2d& d) {
  const double v = Cross(c - a, d - b);
  return v > 0 ? 1 : (v < 0 ? -1 : 0);
}

// Distance from q to the convex hull-ish neighbourhood of a quad: distance to its bounding box.
double BoxDistance(const Eigen::Vector2d& a,
                   const Eigen::Vector2d& b,
                   const Eigen::Vector2d& c,
                   const Eigen::Vector2d& d,
                   const Eigen::Vector2d& q,
                   double* diameter) {
  Box box;
  box.Add(a);
  box.Add(b);
  box.Add(c);
  box.Add(d);
  *diameter = (box.hi - box.lo).norm();
  const Eigen::Vector2d e = (box.lo - q).cwiseMax(q - box.hi).cwiseMax(0.0);
  return e.norm();
}

double SegmentDistance(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& q) {
  const Eigen::Vector2d ab = b - a;
  const double l2 = ab.squaredNorm();
  const double u = l2 > 0 ? std::clamp((q - a).dot(ab) / l2, 0.0, 1.0) : 0.0;
  return (a + u * ab - q).norm();
}

// Distance from q to the piecewise-linear image of a cell (0 inside either triangle).
double CellDistance(const Eigen::Vector2d* c, const Eigen::Vector2d& q) {
  double l1, l2, l3;
  if (Barycentric(c[0], c[1], c[2], q, &l1, &l2, &l3) && l1 >= 0 && l2 >= 0 && l3 >= 0) return 0.0;
  if (Barycentric(c[0], c[2], c[3], q, &l1, &l2, &l3) && l1 >= 0 && l2 >= 0 && l3 >= 0) return 0.0;
  return std::min({SegmentDistance(c[0], c[1], q),
                   SegmentDistance(c[1], c[2], q),
                   SegmentDistance(c[2], c[3], q),
                   SegmentDistance(c[3], c[0], q)});
}

// Corners of the scan cell (i, j): nodes (i, j), (i+1, j), (i+1, j+1), (i, j+1).
void CellCorners(const Scan& scan, int i, int j, Eigen::Vector2d* c) {
  c[0] = scan.Node(i, j);
  c[1] = scan.Node(i + 1, j);
  c[2] = scan.Node(i + 1, j + 1);
  c[3] = scan.Node(i, j + 1);
}

// A hit: the cell's piecewise-linear image contains the target; (s, t) from its barycentric
// coordinates. Triangle (a, b, c): (u, v) = l2 (1, 0) + l3 (1, 1); triangle (a, c, d): l2 (1, 1) + l3 (0, 1).
bool CellHit(
    const Scan& scan, int i, int j, const Eigen::Vector2d* c, const Eigen::Vector2d& q, int sign, Candidate* hit) {
  constexpr double kBarySlack = 1e-9;
  double l1, l2, l3;
  auto inside = [&] { return l1 >= -kBarySlack && l2 >= -kBarySlack && l3 >= -kBarySlack; };
  if (Barycentric(c[0], c[1], c[2], q, &l1, &l2, &l3) && inside()) {
    *hit = {(i + l2 + l3) * scan.ds(), (j + l3) * scan.h(), sign};
    return true;
  }
  if (Barycentric(c[0], c[2], c[3], q, &l1, &l2, &l3) && inside()) {
    *hit = {(i + l2) * scan.ds(), (j + l2 + l3) * scan.h(), sign};
    return true;
  }
  return false;
}

// Fold seeds of the cell (i, j) of orientation `sign`: the orientation changes to the next cell
// in s or in t (the first row is degenerate: every direction starts at x0). Near a fold the true
// map and its piecewise-linear image may cover the target a different number of times (a close
// pair of solutions): when the target is within the linearisation error of either image and
// neither cell caught it, both sides are seeded.
void FoldSeeds(const Scan& scan,
               int i,
               int j,
               const Eigen::Vector2d* c,
               int sign,
               const Eigen::Vector2d& q,
               std::vector<Candidate>* folds) {
  if (j == 0 || sign == 0) return;
  const double d_here = CellDistance(c, q);
  // How far the true cell image may be from the piecewise-linear one: the midpoint deviation of
  // a parabola, |second difference| / 8, in s and in t (safety factor 4).
  const double pl_error = 0.5 * ((scan.Node(i + 2, j) - 2.0 * scan.Node(i + 1, j) + scan.Node(i, j)).norm() +
                                 (scan.Node(i, j + 2) - 2.0 * scan.Node(i, j + 1) + scan.Node(i, j)).norm()) +
                          1e-12;
  for (const auto& [i2, j2] : {std::pair<int, int>{i + 1, j}, std::pair<int, int>{i, j + 1}}) {
    if (j2 >= scan.m()) continue;
    Eigen::Vector2d c2[4];
    CellCorners(scan, i2, j2, c2);
    const int sign2 = QuadSign(c2[0], c2[1], c2[2], c2[3]);
    if (sign2 == 0 || sign2 == sign) continue;
    const double d_there = CellDistance(c2, q);
    if (d_here == 0.0 || d_there == 0.0 || std::min(d_here, d_there) > pl_error) continue;
    const double dist_pair = std::min(d_here, d_there);
    folds->push_back({(i + 0.5) * scan.ds(), (j + 0.5) * scan.h(), sign, true, dist_pair});
    folds->push_back({(i2 + 0.5) * scan.ds(), (j2 + 0.5) * scan.h(), sign2, true, dist_pair});
  }
}

// False when the block b of period k between directions i and i+1 cannot hold a seed: a fold
// seed needs the target within one cell diameter of a cell, and a cell diameter is at most the
// block's box diagonal.
bool BlockMayHold(const Scan& scan, int i, int b, int k, const Eigen::Vector2d& q) {
  Box box = scan.BlockBox(i, b, k);
  const Box other = scan.BlockBox(i + 1, b, k);
  box.Add(other.lo);
  box.Add(other.hi);
  const double margin = (box.hi - box.lo).norm() + 1e-12;
  return !((q.array() < box.lo.array() - margin).any() || (q.array() > box.hi.array() + margin).any());
}

// Hits and fold seeds of the cells j0 .. j1-1 between directions i and i+1.
void ScanCells(const Scan& scan,
               int i,
               int j0,
               int j1,
               const Eigen::Vector2d& q,
               std::vector<Candidate>* hits,
               std::vector<Candidate>* folds) {
  for (int j = j0; j < j1; ++j) {
    Eigen::Vector2d c[4];
    CellCorners(scan, i, j, c);
    double diameter = 0.0;
    const double dist = BoxDistance(c[0], c[1], c[2], c[3], q, &diameter);
    if (dist > diameter) continue;
    const int sign = QuadSign(c[0], c[1], c[2], c[3]);
    Candidate hit;
    if (dist == 0.0 && CellHit(scan, i, j, c, q, sign, &hit)) hits->push_back(hit);
    FoldSeeds(scan, i, j, c, sign, q, folds);
  }
}

// Keeps the candidates not within `cells` scan cells (in s and t, same sheet) of one kept before.
std::vector<Candidate> Thin(const Scan& scan, const std::vector<Candidate>& in, double cells) {
  std::vector<Candidate> kept;
  for (const Candidate& c : in) {
    bool dup = false;
    for (const Candidate& o : kept)
      dup = dup || (c.sign == o.sign && CircularDistance(c.s, o.s) <= cells * scan.ds() &&
                    std::abs(c.t - o.t) <= cells * scan.h());
    if (!dup) kept.push_back(c);
  }
  return kept;
}

// Collects refinement seeds: cells whose piecewise-linear image contains the target, and cells
// next to a fold (orientation change) whose image is close to the target.
std::vector<Candidate> FindCandidates(const Scan& scan, const Eigen::Vector2d& rel_target) {
  std::vector<Candidate> hits, folds;
  const int n = scan.n(), m = scan.m();
  const int periods = (m + n - 1) / n;
  for (int i = 0; i < scan.ns(); ++i)
    for (int k = 0; k < periods; ++k)
      for (int b = 0; b < scan.blocks() && k * n + b * kBlockSteps < m; ++b) {
        const int j0 = k * n + b * kBlockSteps;
        const int j1 = std::min({j0 + kBlockSteps, k * n + n, m});  // cells j0 .. j1-1
        if (BlockMayHold(scan, i, b, k, rel_target)) ScanCells(scan, i, j0, j1, rel_target, &hits, &folds);
      }
  // Hits in neighbouring cells of the same sheet are the same solution (target on a shared edge).
  std::vector<Candidate> out = Thin(scan, hits, 1.0);
  // Along one fold many cell pairs may qualify; the pair nearest the target stands for the
  // others within a few cells (a close pair of solutions lies next to the nearest one).
  std::stable_sort(
      folds.begin(), folds.end(), [](const Candidate& a, const Candidate& b) { return a.distance < b.distance; });
  const std::vector<Candidate> kept = Thin(scan, folds, 3.0);
  out.insert(out.end(), kept.begin(), kept.end());
  return out;
}

// F(s, t) = x_s(t) - target for Ceres' TinySolver; exact Jacobian [dx/ds, dx/dt]. Every call
// integrates with the variational equations and keeps the result: TinySolver evaluates an
// accepted point twice (without, then with the Jacobian), and the caller reuses the last point.
class ReachResidual {
 public:
  using Scalar = double;
  enum { NUM_RESIDUALS = 2, NUM_PARAMETERS = 2 };
  ReachResidual(const ReachProblem& problem, double period, const IntegrationOptions& integration, int* evaluations)
      : problem_(problem), period_(period), integration_(integration), evaluations_(evaluations) {}

  bool operator()(const double* p, double* r, double* jacobian) const {
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || std::abs(p[1]) > 1e12) {
      r[0] = r[1] = 1e30;
      return false;
    }
    const internal::TightPoint& tp = Evaluate(p[0], p[1]);
    const Eigen::Vector2d f = problem_.x0 + tp.x - problem_.target;
    r[0] = f.x();
    r[1] = f.y();
    if (jacobian != nullptr) {  // column-major 2 x 2
      jacobian[0] = tp.dx_ds.x();
      jacobian[1] = tp.dx_ds.y();
      jacobian[2] = tp.velocity.x();
      jacobian[3] = tp.velocity.y();
    }
    return true;
  }

  const internal::TightPoint& Evaluate(double s, double t) const {
    if (has_cache_ && s == cache_s_ && t == cache_t_) return cache_;
    const double lambda = problem_.model.lambda();
    const internal::ReachDirection d = internal::DirectionFor(problem_.start, problem_.mu, lambda, s);
    cache_ = internal::EvaluateTight(d, lambda, period_, t, true, integration_);
    ++*evaluations_;
    cache_s_ = s;
    cache_t_ = t;
    has_cache_ = true;
    return cache_;
  }

 private:
  const ReachProblem& problem_;
  double period_;
  const IntegrationOptions& integration_;
  int* evaluations_;
  mutable bool has_cache_ = false;
  mutable double cache_s_ = 0.0, cache_t_ = 0.0;
  mutable internal::TightPoint cache_;
};

// Cheap closest approach along the direction s: min over t in [0, horizon] of |x_s(t) - target|
// from the RK4 table, refined on the cubic Hermite interpolant around the best node.
struct CheapDistance {
  const ReachProblem* problem;
  double period, horizon;
  int steps;
  int* periods_integrated;
  double operator()(double s, double* t_best) const {
    internal::ScanPeriod tab;
    const double lambda = problem->model.lambda();
    internal::TabulatePeriod(
        internal::DirectionFor(problem->start, problem->mu, lambda, s), lambda, period, steps, &tab);
    ++*periods_integrated;
    const Eigen::Vector2d rel = problem->target - problem->x0;
    const double h = period / steps;
    const int m = static_cast<int>(std::floor(horizon / h + 1e-9));
    auto node = [&](int j) {
      return tab.x[static_cast<std::size_t>(j % steps)] + static_cast<double>(j / steps) * tab.drift;
    };
    auto vel = [&](int j) { return tab.v[static_cast<std::size_t>(j % steps)]; };
    auto at = [&](double t) {  // cubic Hermite between the two nodes around t
      int j = std::min(static_cast<int>(std::floor(t / h)), std::max(m - 1, 0));
      j = std::max(j, 0);
      const double u = (t - j * h) / h;
      const double h00 = (1 + 2 * u) * (1 - u) * (1 - u), h10 = u * (1 - u) * (1 - u);
      const double h01 = u * u * (3 - 2 * u), h11 = u * u * (u - 1);
      return Eigen::Vector2d(h00 * node(j) + h10 * h * vel(j) + h01 * node(j + 1) + h11 * h * vel(j + 1));
    };
    double best = std::numeric_limits<double>::infinity();
    int jb = 0;
    for (int j = 0; j <= m; ++j) {
      const double dist = (node(j) - rel).norm();
      if (dist < best) {
        best = dist;
        jb = j;
      }
    }
    double tb = jb * h;
    if (m * h < horizon) {  // the horizon itself
      const double dist = (at(horizon) - rel).norm();
      if (dist < best) {
        best = dist;
        tb = horizon;
      }
    }
    // Golden-section search on the interpolant over the two neighbouring steps.
    double t_min = 0.0;
    const double f_min = internal::GoldenSection(
        [&](double t) { return (at(t) - rel).norm(); }, std::max(0.0, tb - h), std::min(horizon, tb + h), &t_min);
    if (f_min < best) {
      best = f_min;
      tb = t_min;
    }
    *t_best = tb;
    return best;
  }
};

// The paper's first guess: the s whose drift per period points from x0 to the target.
double DriftGuess(const Scan& scan, const Eigen::Vector2d& dir) {
  if (dir.norm() == 0.0) return std::numeric_limits<double>::quiet_NaN();
  double best_s = std::numeric_limits<double>::quiet_NaN(), best_dot = -std::numeric_limits<double>::infinity();
  for (int i = 0; i < scan.ns(); ++i) {
    const Eigen::Vector2d d0 = scan.Tab(i).drift, d1 = scan.Tab(i + 1).drift;
    const double c0 = Cross(d0, dir), c1 = Cross(d1, dir);
    if ((c0 <= 0 && c1 > 0) || (c0 >= 0 && c1 < 0)) {
      const double u = c0 / (c0 - c1);
      const double dot = ((1 - u) * d0 + u * d1).dot(dir);
      if (dot > best_dot) {
        best_dot = dot;
        best_s = WrapTwoPi((i + u) * scan.ds());
      }
    }
  }
  return best_dot > 0 ? best_s : std::numeric_limits<double>::quiet_NaN();
}

double Objective1d(unsigned /*n*/, const double* x, double* /*grad*/, void* data) {
  auto* f = static_cast<std::function<double(double)>*>(data);
  return (*f)(x[0]);
}

double Objective2d(unsigned /*n*/, const double* x, double* /*grad*/, void* data) {
  auto* f = static_cast<std::function<double(double, double)>*>(data);
  return (*f)(x[0], x[1]);
}

}  // namespace

std::string ReachOptions::Validate() const {
  using internal::InvalidValueMessage;
  if (!(horizon_periods > 0 && horizon_periods <= 1e4))
    return InvalidValueMessage("horizon_periods", horizon_periods, "must be in (0, 1e4]");
  const std::string range = internal::CheckRanges(*this);  // scan grid, tolerance, budgets (the field list)
  if (!range.empty()) return range;
  // Work budget (README, "Limits"): the scan visits directions x steps x periods nodes and each
  // candidate is refined by integrations over up to the whole horizon.
  const double scan_nodes = horizon_periods * scan_directions * scan_steps_per_period;
  if (scan_nodes > kMaxReachScanNodes)
    return InvalidValueMessage(
        "horizon_periods",
        horizon_periods,
        "horizon_periods x scan_directions x scan_steps_per_period = " + internal::FormatNumber(scan_nodes) +
            " exceeds the scan budget " + internal::FormatNumber(kMaxReachScanNodes));
  const double refine_periods = horizon_periods * max_candidates;
  if (refine_periods > kMaxReachRefinePeriods)
    return InvalidValueMessage("horizon_periods",
                               horizon_periods,
                               "horizon_periods x max_candidates = " + internal::FormatNumber(refine_periods) +
                                   " exceeds the refinement budget " + internal::FormatNumber(kMaxReachRefinePeriods));
  return integration.Validate();
}

std::string ToString(ReachStatus status) {
  switch (status) {
    case ReachStatus::kNotRun:
      return "not_run";
    case ReachStatus::kSolved:
      return "solved";
    case ReachStatus::kUnreachableWithinHorizon:
      return "unreachable_within_horizon";
    case ReachStatus::kNumericalFailure:
      return "numerical_failure";
    case ReachStatus::kTargetEqualsStart:
      return "target_equals_start";
  }
  return "unknown";
}

const ReachSolution& ReachSummary::Earliest() const {
  if (solutions.empty())
    throw std::logic_error("ReachSummary::Earliest: no solution (status " + ToString(status) + ")");
  return solutions.front();
}

std::string ReachSummary::BriefReport() const {
  std::ostringstream os;
  os.precision(10);
  os << "Reach: " << ToString(status) << ", " << solutions.size() << " solution(s) with t <= " << horizon << " ("
     << horizon / period << " periods)";
  if (!solutions.empty()) {
    const ReachSolution& e = solutions.front();
    os << "; earliest delta_psi = " << e.delta_psi << ", t = " << e.t << " (" << e.periods << " periods), residual "
       << e.residual;
  } else if (status == ReachStatus::kUnreachableWithinHorizon) {
    os << "; closest approach " << closest_approach.distance << " at delta_psi = " << closest_approach.delta_psi
       << ", t = " << closest_approach.t;
  }
  if (!message.empty()) os << "; " << message;
  os << "; " << candidates << " candidates, " << tight_evaluations << " tight evaluations";
  return os.str();
}

namespace {

// The public boundary: options and finite input, checked once; the angles come back reduced
// (kinematics.h, ReduceAngles) so that a psi of 1e6 is answered like psi mod 2 pi.
ReachProblem ValidateReach(const ReachProblem& problem, const ReachOptions& options) {
  internal::ThrowIfInvalid(options.Validate());
  ReachProblem p = problem;
  p.start = internal::ReduceAngles("start", problem.start);
  internal::RequireEnergy("mu", problem.mu);
  internal::RequireCoordinates("x0", problem.x0);
  internal::RequireCoordinates("target", problem.target);
  internal::RequireFinite("A0", problem.A0);
  return p;
}

struct GlobalMinimum {
  double s = 0.0, t = 0.0, d = std::numeric_limits<double>::infinity();
};

// NLopt's global search (DIRECT-L, deterministic) over s in [0, 2 pi) of the closest approach
// d(s) = min_t |x_s(t) - target|, t in [0, horizon], on the cheap one-period tables. Its minimiser
// is refined by Ceres like every scan candidate (a solution when d reaches 0; the scan enumerates
// the others, since a global optimiser returns one minimum), and when nothing reaches the target
// it gives the closest approach.
GlobalMinimum GlobalSearch(const CheapDistance& cheap, const ReachOptions& options, ReachSummary* summary) {
  std::function<double(double)> d_of_s = [&](double s) {
    ++summary->global_evaluations;
    double t;
    return cheap(s, &t);
  };
  nlopt::opt global(nlopt::GN_DIRECT_L, 1);
  global.set_lower_bounds(std::vector<double>{0.0});
  global.set_upper_bounds(std::vector<double>{kTwoPi});
  global.set_min_objective(Objective1d, &d_of_s);
  global.set_maxeval(options.global_max_evaluations);
  global.set_xtol_abs(1e-10);
  std::vector<double> sx{M_PI};
  GlobalMinimum g;
  try {
    global.optimize(sx, g.d);
  } catch (const nlopt::roundoff_limited&) {
  } catch (const nlopt::forced_stop&) {
  }
  g.s = sx[0];
  cheap(g.s, &g.t);
  return g;
}

// The refinement seeds in order: the global minimiser, the scan's hits and folds, and (when there
// are none) the paper's uniform drift towards the target; at most options.max_candidates.
std::vector<Candidate> CollectCandidates(const Scan& scan,
                                         const ReachProblem& problem,
                                         const ReachOptions& options,
                                         const GlobalMinimum& global,
                                         double period,
                                         double horizon,
                                         ReachSummary* summary) {
  const Eigen::Vector2d rel = problem.target - problem.x0;
  const double lambda = problem.model.lambda();
  std::vector<Candidate> candidates = FindCandidates(scan, rel);
  if (std::isfinite(global.d) && global.t > 0.0) candidates.insert(candidates.begin(), {global.s, global.t, 0});
  if (candidates.empty() && std::isfinite(summary->drift_guess_delta_psi)) {
    const double s = summary->drift_guess_delta_psi;
    internal::ScanPeriod tab;
    internal::TabulatePeriod(internal::DirectionFor(problem.start, problem.mu, lambda, s),
                             lambda,
                             period,
                             options.scan_steps_per_period,
                             &tab);
    ++summary->scan_periods_integrated;
    const double t = rel.norm() / std::max(tab.drift.norm(), 1e-300) * period;
    if (t <= horizon) candidates.push_back({s, t, 0});
  }
  if (static_cast<int>(candidates.size()) > options.max_candidates)
    candidates.resize(static_cast<std::size_t>(options.max_candidates));
  return candidates;
}

// True when a solution in `found` is the same as (s, t) to within (ds, dt) on the circle x line.
bool NearSolution(const std::vector<ReachSolution>& found, double s, double t, double ds, double dt) {
  for (const ReachSolution& o : found)
    if (CircularDistance(o.delta_psi, s) <= ds && std::abs(o.t - t) <= dt) return true;
  return false;
}

// Levenberg-Marquardt (Ceres TinySolver) from every candidate on the tight integration; the
// distinct solutions with 0 < t <= horizon and residual <= tolerance, earliest first.
void RefineCandidates(const Scan& scan,
                      const ReachProblem& problem,
                      const ReachOptions& options,
                      const std::vector<Candidate>& candidates,
                      double period,
                      double horizon,
                      ReachSummary* summary) {
  ReachResidual residual(problem, period, options.integration, &summary->tight_evaluations);
  ceres::TinySolver<ReachResidual> solver;
  solver.options.max_num_iterations = options.max_refine_iterations;
  solver.options.gradient_tolerance = 0.0;
  solver.options.parameter_tolerance = 1e-15;
  solver.options.function_tolerance = 0.0;
  solver.options.cost_threshold = 0.5 * std::pow(0.1 * options.tolerance, 2);
  for (const Candidate& c : candidates) {
    // A fold seed next to a solution already found adds nothing.
    if (c.fold && NearSolution(summary->solutions, WrapTwoPi(c.s), c.t, 2.0 * scan.ds(), 2.0 * scan.h())) continue;
    Eigen::Vector2d x(c.s, c.t);
    solver.Solve(residual, &x);
    summary->refine_iterations += solver.summary.iterations;
    const double t = x[1];
    // t > 0: the target is not x0 (checked before), so t = 0 cannot have a residual this small.
    if (!(t > 0.0 && t <= horizon)) continue;
    const internal::TightPoint tp = residual.Evaluate(x[0], x[1]);
    const double s = WrapTwoPi(x[0]);
    const double res = (problem.x0 + tp.x - problem.target).norm();
    if (!(res <= options.tolerance)) continue;
    if (NearSolution(summary->solutions, s, t, kSameSolution, kSameSolution * std::max(1.0, t))) continue;
    ReachSolution sol;
    sol.delta_psi = s;
    sol.t = t;
    sol.periods = t / period;
    sol.residual = res;
    sol.jacobian_determinant = Cross(tp.dx_ds, tp.velocity);
    summary->solutions.push_back(sol);
  }
  std::sort(summary->solutions.begin(), summary->solutions.end(), [](const ReachSolution& a, const ReachSolution& b) {
    return a.t < b.t;
  });
}

// The impulse and the end state (tight free motion with the orientation) of every solution.
void FinishSolutions(const ReachProblem& problem, const ReachOptions& options, ReachSummary* summary) {
  for (ReachSolution& sol : summary->solutions) {
    sol.impulse = EnergyPreservingImpulse(problem.start, problem.mu, sol.delta_psi, problem.model);
    AngleState after = problem.start;
    after.psi += sol.delta_psi;
    const FreeMotion motion =
        FreeMotion::FromAngles(problem.model, after, problem.mu, problem.x0, problem.A0, options.integration);
    sol.end = motion.At(sol.t);
  }
  const ReachSolution& e = summary->solutions.front();
  summary->closest_approach = {e.residual, e.delta_psi, e.t};
}

// Unreachable within the horizon: the closest approach. The global minimum competes with the scan
// grid's best node (DIRECT may stop on its budget first), then a bounded polish of (s, t) on the
// tight integration (NLopt BOBYQA, deterministic).
ClosestApproach PolishClosestApproach(const Scan& scan,
                                      const CheapDistance& cheap,
                                      const ReachProblem& problem,
                                      const ReachOptions& options,
                                      const GlobalMinimum& global,
                                      double period,
                                      double horizon,
                                      ReachSummary* summary) {
  const Eigen::Vector2d rel = problem.target - problem.x0;
  const double lambda = problem.model.lambda();
  double best_d = global.d;
  double best_s = global.s;
  for (int i = 0; i < scan.ns(); ++i)
    for (int j = 0; j <= scan.m() && j * scan.h() <= horizon; ++j) {
      const double dij = (scan.Node(i, j) - rel).norm();
      if (dij < best_d) {
        best_d = dij;
        best_s = i * scan.ds();
      }
    }
  double best_t = 0.0;
  cheap(best_s, &best_t);
  std::function<double(double, double)> dist2 = [&](double s, double t) {
    const internal::TightPoint tp = internal::EvaluateTight(
        internal::DirectionFor(problem.start, problem.mu, lambda, s), lambda, period, t, false, options.integration);
    ++summary->tight_evaluations;
    return (problem.x0 + tp.x - problem.target).squaredNorm();
  };
  const double t_lo = std::max(0.0, best_t - scan.h()), t_hi = std::min(horizon, best_t + scan.h());
  nlopt::opt local(nlopt::LN_BOBYQA, 2);
  local.set_lower_bounds(std::vector<double>{best_s - scan.ds(), t_lo});
  local.set_upper_bounds(std::vector<double>{best_s + scan.ds(), t_hi});
  local.set_min_objective(Objective2d, &dist2);
  local.set_maxeval(60);
  local.set_xtol_abs(std::vector<double>{1e-10, 1e-10});
  std::vector<double> st{best_s, std::clamp(best_t, t_lo, t_hi)};
  double f2 = dist2(st[0], st[1]);
  try {
    local.optimize(st, f2);
  } catch (const nlopt::roundoff_limited&) {
  } catch (const nlopt::forced_stop&) {
  }
  return {std::sqrt(dist2(st[0], st[1])), WrapTwoPi(st[0]), st[1]};
}

}  // namespace

ReachSummary Reach(const ReachProblem& problem_in, const ReachOptions& options) {
  const ReachProblem problem = ValidateReach(problem_in, options);
  ReachSummary summary;
  summary.message.clear();  // filled only for kNumericalFailure
  summary.problem = problem;
  summary.period = kTwoPi / std::sqrt(problem.mu);
  summary.horizon = options.horizon_periods * summary.period;
  const double period = summary.period, horizon = summary.horizon;
  const Eigen::Vector2d rel = problem.target - problem.x0;
  if (rel.norm() <= options.tolerance) {
    summary.status = ReachStatus::kTargetEqualsStart;
    summary.drift_guess_delta_psi = std::numeric_limits<double>::quiet_NaN();
    summary.closest_approach = {rel.norm(), 0.0, 0.0};
    return summary;
  }
  try {
    const Scan scan(problem, options, period, horizon);
    summary.scan_periods_integrated = scan.ns();
    summary.drift_guess_delta_psi = DriftGuess(scan, rel);
    const CheapDistance cheap{
        &problem, period, horizon, options.scan_steps_per_period, &summary.scan_periods_integrated};
    const GlobalMinimum global = GlobalSearch(cheap, options, &summary);
    const std::vector<Candidate> candidates =
        CollectCandidates(scan, problem, options, global, period, horizon, &summary);
    summary.candidates = static_cast<int>(candidates.size());
    RefineCandidates(scan, problem, options, candidates, period, horizon, &summary);
    if (!summary.solutions.empty()) {
      summary.status = ReachStatus::kSolved;
      FinishSolutions(problem, options, &summary);
      return summary;
    }
    summary.status = ReachStatus::kUnreachableWithinHorizon;
    summary.closest_approach = PolishClosestApproach(scan, cheap, problem, options, global, period, horizon, &summary);
  } catch (const std::runtime_error& e) {
    summary.status = ReachStatus::kNumericalFailure;
    summary.message = e.what();
    summary.solutions.clear();
  }
  return summary;
}

}  // namespace plateball
