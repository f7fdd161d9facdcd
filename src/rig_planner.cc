#include "plateball/rig_planner.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "check.h"
#include "field_check.h"
#include "golden_section.h"
#include "plan_partitioned.h"
#include "plateball/free_motion.h"
#include "plateball/partition.h"
#include "plateball/plan_rig_check.h"
#include "rig_geometry.h"

namespace plateball {

std::string ToString(RigPlanStatus status) {
  switch (status) {
    case RigPlanStatus::kNotRun:
      return "not_run";
    case RigPlanStatus::kSuccess:
      return "success";
    case RigPlanStatus::kPlanFailed:
      return "plan_failed";
    case RigPlanStatus::kLimitsNotMet:
      return "limits_not_met";
  }
  return "unknown";
}

std::string RigPlanOptions::Validate() const {
  const std::string e = internal::CheckRanges(*this);  // rounds and samples (the field list)
  if (!e.empty()) return e;
  return internal::CheckRanges(tolerances, "tolerances.");
}

std::string RigPlanSummary::BriefReport() const {
  std::ostringstream os;
  os << "Rig plan: " << ToString(status) << ", " << plan.segments << " segments (" << segments_initial << " asked, "
     << points_added << " added in " << rounds << " round" << (rounds == 1 ? "" : "s") << ", " << points_removed
     << " removed, " << points_slid << " slid onto the tick grid)";
  if (!message.empty()) os << " (" << message << ")";
  os << "; " << plan.BriefReport();
  return os.str();
}

namespace {

// The smallest geometric margin (plate, obstacles, stroke) at a contact point and its limit.
struct Margin {
  double value = std::numeric_limits<double>::infinity();
  std::string limit;
};

Margin SmallestMargin(const RigLimits& limits, const Eigen::Vector2d& x0, const Eigen::Vector2d& x) {
  Margin m;
  internal::VisitGeometricMargins(limits, x0, x, [&](const std::string& name, double margin) {
    if (margin < m.value) m = {margin, name};
  });
  return m;
}

bool HasGeometricLimits(const RigLimits& l) { return l.plate || !l.obstacles.empty() || l.stroke; }

// "leaves the plate", "enters obstacles[1]", "leaves the stroke box (x)".
std::string Crossing(const std::string& limit) {
  if (limit == "plate") return "leaves the plate";
  if (limit.rfind("stroke", 0) == 0) return "leaves the stroke box (" + limit.substr(7) + ")";
  return "enters " + limit;
}

std::string Point(const Eigen::Vector2d& x) {
  return "(" + internal::FormatNumber(x.x()) + ", " + internal::FormatNumber(x.y()) + ")";
}

void AddOnce(const std::string& name, std::vector<std::string>* names) {
  if (std::find(names->begin(), names->end(), name) == names->end()) names->push_back(name);
}

// The path itself against the geometric limits, sampled at `samples` points per segment of the
// given partition and at least kPathSamplesPerPiece per piece (as PathLimitBreaks samples a
// reference): one line per limit it exceeds beyond the tolerance, at its worst point. No partition
// can keep the flights inside where the pass points themselves lie outside.
constexpr int kPathSamplesPerPiece = 2000;

std::vector<std::pair<std::string, std::string>> PathCrossings(const RigLimits& limits,
                                                               const Path& path,
                                                               const std::vector<std::vector<double>>& partition,
                                                               int samples,
                                                               double tolerance) {
  struct Worst {
    double margin;
    std::string where;
  };
  std::map<std::string, Worst> worst;
  const Eigen::Vector2d x0 = path.StartPoint();
  for (int piece = 0; piece < path.PieceCount(); ++piece) {
    const SmoothCurve& curve = path.pieces()[piece];
    const std::vector<double>& taus = partition[piece];
    const int segments = static_cast<int>(taus.size()) - 1;
    const int per_segment = std::max(samples, (kPathSamplesPerPiece + segments - 1) / segments);
    for (std::size_t k = 0; k + 1 < taus.size(); ++k)
      for (int j = 0; j <= per_segment; ++j) {
        const double tau = taus[k] + (taus[k + 1] - taus[k]) * j / per_segment;
        const Eigen::Vector2d p = curve.Value(tau);
        internal::VisitGeometricMargins(limits, x0, p, [&](const std::string& name, double margin) {
          if (margin >= -tolerance) return;
          auto it = worst.find(name);
          if (it != worst.end() && !(margin < it->second.margin)) return;
          worst[name] = {margin,
                         "by " + internal::FormatNumber(-margin) + " at p(tau = " + internal::FormatNumber(tau) +
                             ") = " + Point(p) + " (piece " + std::to_string(piece) + ")"};
        });
      }
  }
  std::vector<std::pair<std::string, std::string>> out;
  for (const auto& [name, w] : worst)
    out.emplace_back(name,
                     "the path itself " + Crossing(name) + " " + w.where + ": no partition keeps the flights out");
  return out;
}

// Each flight's smallest geometric margin and its limit: the flight integrated (IntegrateFreeMotion)
// from its impulse at the planner's arrival at its pass point, sampled at `samples` points, and
// the smallest sample refined by golden-section search between its neighbours (each evaluation
// integrated from the sample before).
std::vector<Margin> FlightMargins(const PlanProblem& problem,
                                  const PlanSummary& plan,
                                  const RigLimits& limits,
                                  const IntegrationOptions& integration,
                                  int samples) {
  const Eigen::Vector2d x0 = problem.path.StartPoint();
  std::vector<Margin> out;
  out.reserve(plan.steps.size());
  Eigen::Vector2d x = x0;
  Eigen::Matrix3d a = plan.A0;
  std::vector<double> times(static_cast<std::size_t>(samples) + 1);
  for (const PlanStep& s : plan.steps) {
    for (int j = 0; j <= samples; ++j) times[static_cast<std::size_t>(j)] = s.duration * j / samples;
    const std::vector<MotionSample> q =
        IntegrateFreeMotion(problem.model, FreeMotionStart{s.impulse.state_after, x, a}, times, integration);
    Margin least;
    std::size_t at = 1;
    for (std::size_t j = 1; j < q.size(); ++j) {
      const Margin m = SmallestMargin(limits, x0, q[j].x);
      if (m.value < least.value) least = m, at = j;
    }
    const MotionSample& before = q[at - 1];
    const FreeMotionStart from{before.state, before.x, before.A};
    const auto margin_at = [&](double dt) {
      return SmallestMargin(limits, x0, IntegrateFreeMotion(problem.model, from, {0.0, dt}, integration)[1].x).value;
    };
    const double span = q[std::min(at + 1, q.size() - 1)].t - before.t;
    const double refined = internal::GoldenSection(margin_at, 0.0, span);
    if (refined < least.value) least.value = refined;  // the limit of the smallest sample (the bow's)
    out.push_back(least);
    x = s.x_end;
    a = s.A_impulsive;
  }
  return out;
}

// The partition points as the plan used them (slid onto a grid or not), per piece.
std::vector<std::vector<double>> PlannedPartition(const PlanSummary& plan, int pieces) {
  std::vector<std::vector<double>> out(static_cast<std::size_t>(pieces));
  for (const PlanStep& s : plan.steps) {
    std::vector<double>& taus = out[static_cast<std::size_t>(s.piece)];
    if (taus.empty()) taus.push_back(s.tau_begin);
    taus.push_back(s.tau_end);
  }
  return out;
}

// The energy changes at their partition points: `owners[piece][k]` lists the problem's energy
// changes at point k of the piece (in the problem's order); their global indices follow the
// partition as it is refined.
std::vector<EnergyChange> PlacedEnergyChanges(const PlanProblem& problem,
                                              const std::vector<std::vector<std::vector<int>>>& owners) {
  std::vector<std::pair<int, EnergyChange>> placed;  // (position in the problem's list, change)
  int offset = 0;
  for (const auto& piece : owners) {
    for (std::size_t k = 0; k < piece.size(); ++k)
      for (int i : piece[k])
        placed.push_back(
            {i,
             EnergyChange{offset + static_cast<int>(k), problem.energy_changes[static_cast<std::size_t>(i)].factor}});
    offset += static_cast<int>(piece.size()) - 1;
  }
  std::sort(placed.begin(), placed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<EnergyChange> out;
  for (const auto& p : placed) out.push_back(p.second);
  return out;
}

// Per piece and partition point, the problem's energy changes there.
std::vector<std::vector<std::vector<int>>> EnergyChangeOwners(const PlanProblem& problem,
                                                              const std::vector<std::vector<double>>& partition) {
  std::vector<std::vector<std::vector<int>>> owners;
  std::vector<std::pair<int, int>> at;  // global index -> (piece, k)
  for (std::size_t piece = 0; piece < partition.size(); ++piece) {
    owners.emplace_back(partition[piece].size());
    for (std::size_t k = 0; k + 1 < partition[piece].size(); ++k)
      at.push_back({static_cast<int>(piece), static_cast<int>(k)});
  }
  for (std::size_t i = 0; i < problem.energy_changes.size(); ++i) {
    const int g = problem.energy_changes[i].index;
    if (g < 0 || g >= static_cast<int>(at.size()))  // as the planner says it
      internal::ThrowInvalid("energy_changes[" + std::to_string(i) + "].index",
                             g,
                             "must be a partition index in [0, " + std::to_string(at.size()) + ")");
    owners[static_cast<std::size_t>(at[static_cast<std::size_t>(g)].first)]
          [static_cast<std::size_t>(at[static_cast<std::size_t>(g)].second)]
              .push_back(static_cast<int>(i));
  }
  return owners;
}

// The refinement's state and its decisions.
struct Refinement {
  std::vector<std::vector<double>> partition;
  std::vector<std::vector<std::vector<int>>> owners;
  std::vector<std::string> reasons;  // why a limit blocks
};

// When flights exceed the `exceeded` limits and the path itself exceeds one of them, refinement
// cannot help (the pass points converge to the path): true, with the limit blocking and the path's
// worst point as the reason.
bool PathBlocks(const RigLimits& limits,
                const Path& path,
                const std::vector<std::vector<double>>& partition,
                const RigPlanOptions& options,
                const std::vector<std::string>& exceeded,
                Refinement* r,
                RigPlanSummary* out) {
  bool blocked = false;
  for (const auto& [name, reason] :
       PathCrossings(limits, path, partition, options.samples_per_flight, options.tolerances.position))
    if (std::find(exceeded.begin(), exceeded.end(), name) != exceeded.end())
      AddOnce(name, &out->blocking), r->reasons.push_back(reason), blocked = true;
  return blocked;
}

// Bisects the segments of the flights below -tolerances.position. False (with the blocking limits and reasons)
// when a bisection would break min_interval, reach the resolution of tau or exceed the budget.
bool Bisect(const PlanSummary& plan,
            const std::vector<Margin>& margins,
            const RigLimits& limits,
            const RigPlanOptions& options,
            Refinement* r,
            RigPlanSummary* out) {
  std::vector<std::size_t> bad;
  for (std::size_t k = 0; k < margins.size(); ++k)
    if (margins[k].value < -options.tolerances.position) bad.push_back(k);
  const int added = static_cast<int>(bad.size());
  if (out->points_added + added > options.max_added_points || plan.segments + added > internal::kMaxPartitionSteps) {
    for (std::size_t k : bad) AddOnce(margins[k].limit, &out->blocking);
    r->reasons.push_back("refining " + std::to_string(added) + " more segments would exceed the refinement's budget (" +
                         std::to_string(out->points_added) + " of max_added_points " +
                         std::to_string(options.max_added_points) + " added, " + std::to_string(plan.segments) +
                         " segments)");
    return false;
  }
  r->partition = PlannedPartition(plan, plan.pieces);
  for (auto it = bad.rbegin(); it != bad.rend(); ++it) {  // from the back: the indices of the earlier stay valid
    const PlanStep& s = plan.steps[*it];
    const Margin& m = margins[*it];
    if (limits.min_interval > 0 && s.duration / 2 < limits.min_interval) {
      AddOnce("min_interval", &out->blocking);
      r->reasons.push_back(
          "flight " + std::to_string(*it) + " " + Crossing(m.limit) + " by " + internal::FormatNumber(-m.value) +
          ", and bisecting it (t_k = " + internal::FormatNumber(s.duration) +
          ") would make flights shorter than min_interval " + internal::FormatNumber(limits.min_interval));
      return false;
    }
    const double mid = 0.5 * (s.tau_begin + s.tau_end);
    if (!(mid > s.tau_begin && mid < s.tau_end)) {
      AddOnce(m.limit, &out->blocking);
      r->reasons.push_back("flight " + std::to_string(*it) + " " + Crossing(m.limit) +
                           " with its segment at the resolution of tau");
      return false;
    }
    std::vector<double>& taus = r->partition[static_cast<std::size_t>(s.piece)];
    taus.insert(taus.begin() + s.index + 1, mid);
    auto& owners = r->owners[static_cast<std::size_t>(s.piece)];
    owners.insert(owners.begin() + s.index + 1, std::vector<int>{});
  }
  out->points_added += added;
  return true;
}

// Coarsening. A point whose removal merges a flight shorter than min_interval (not the last: the
// check's rule) or a flight the tick grid could not place with its neighbour: the flight's end when
// it is an interior point of its piece without energy changes and not frozen, else its begin. No two
// neighbours are removed in one round (each merge joins two segments).
using PointSet = std::vector<std::pair<int, int>>;         // (piece, index of the point in the piece)
using FrozenPoints = std::vector<std::pair<int, double>>;  // (piece, tau): kept whatever the indices become

bool Removable(const Refinement& r, const FrozenPoints& frozen, int piece, int k) {
  const std::size_t p = static_cast<std::size_t>(piece);
  if (!(k > 0 && k + 1 < static_cast<int>(r.partition[p].size()) && r.owners[p][static_cast<std::size_t>(k)].empty()))
    return false;
  const double tau = r.partition[p][static_cast<std::size_t>(k)];
  return std::find(frozen.begin(), frozen.end(), std::make_pair(piece, tau)) == frozen.end();
}

void ChooseMerge(const Refinement& r, const FrozenPoints& frozen, int piece, int end, PointSet* chosen) {
  const auto has = [&](int k) {
    return std::find(chosen->begin(), chosen->end(), std::make_pair(piece, k)) != chosen->end();
  };
  if (has(end) || has(end - 1)) return;  // the flight already merges
  for (int k : {end, end - 1})
    if (Removable(r, frozen, piece, k) && !has(k - 1) && !has(k + 1)) {
      chosen->emplace_back(piece, k);
      return;
    }
}

PointSet PointsToMerge(const PlanSummary& plan,
                       const RigLimits& limits,
                       const internal::PlanGridReport& grid,
                       const RigPlanOptions& options,
                       const Refinement& r,
                       const FrozenPoints& frozen) {
  PointSet chosen;
  for (std::size_t k = 0; k + 1 < plan.steps.size(); ++k) {
    const PlanStep& s = plan.steps[k];
    if (limits.min_interval > 0 && s.duration < limits.min_interval * (1 - options.tolerances.time))
      ChooseMerge(r, frozen, s.piece, s.index + 1, &chosen);
  }
  for (const auto& [piece, k] : grid.missed_points) ChooseMerge(r, frozen, piece, k, &chosen);
  std::sort(chosen.begin(), chosen.end());
  return chosen;
}

// The partition without the chosen points (sorted); `merged` gets, per point, its merged flight's
// (piece, index) in the new partition.
Refinement WithoutPoints(const Refinement& r, const PointSet& points, PointSet* merged) {
  Refinement out = r;
  for (auto it = points.rbegin(); it != points.rend(); ++it) {
    const std::size_t p = static_cast<std::size_t>(it->first);
    out.partition[p].erase(out.partition[p].begin() + it->second);
    out.owners[p].erase(out.owners[p].begin() + it->second);
  }
  for (const auto& [piece, k] : points) {
    int before = 0;  // removed points of the piece before this one
    for (const auto& [q, j] : points) before += q == piece && j < k;
    merged->emplace_back(piece, k - 1 - before);
  }
  return out;
}

// The flights of `plan` shorter than min_interval, but the last (the check's rule).
int ShortFlights(const PlanSummary& plan, const RigLimits& limits, const RigPlanOptions& options) {
  int n = 0;
  for (std::size_t k = 0; k + 1 < plan.steps.size(); ++k)
    n += limits.min_interval > 0 && plan.steps[k].duration < limits.min_interval * (1 - options.tolerances.time);
  return n;
}

// Merges the flights that are too short (PointsToMerge) round by round and plans again, keeping a
// round's merges only when every flight of the new plan stays within the geometric limits: a
// merge whose flight would leave them is frozen (its point stays, named in the reasons) and the
// round is retried without it. Stops when no flight is too short, nothing can be merged, or after
// max_rounds accepted rounds.
void Coarsen(const PlanProblem& problem,
             const RigLimits& limits,
             const PlanOptions& options,
             const RigPlanOptions& rig_options,
             const internal::PlanGrid& grid,
             Refinement* r,
             internal::PlanGridReport* grid_report,
             RigPlanSummary* out) {
  FrozenPoints frozen;
  for (int accepted = 0; accepted < rig_options.max_rounds;) {
    const PointSet points = PointsToMerge(out->plan, limits, *grid_report, rig_options, *r, frozen);
    if (points.empty()) return;
    PointSet merged;
    Refinement candidate = WithoutPoints(*r, points, &merged);
    internal::PlanGridReport report;
    PlanSummary plan = internal::PlanPartitioned(problem.model,
                                                 problem.initial,
                                                 problem.mu,
                                                 problem.A0,
                                                 problem.path,
                                                 candidate.partition,
                                                 PlacedEnergyChanges(problem, candidate.owners),
                                                 options,
                                                 grid,
                                                 &report);
    PointSet refused;
    if (!plan.IsSolutionUsable()) {
      refused = points;
      r->reasons.push_back("merging flights shorter than min_interval or the tick fails: " + plan.message);
    } else if (HasGeometricLimits(limits)) {
      const std::vector<Margin> margins =
          FlightMargins(problem, plan, limits, options.integration, rig_options.samples_per_flight);
      bool other = false;  // a flight that was not merged now exceeds a limit: refuse the round
      std::string first;   // the first refused merge, for the reasons
      for (std::size_t k = 0; k < margins.size(); ++k) {
        if (!(margins[k].value < -rig_options.tolerances.position)) continue;
        const PlanStep& s = plan.steps[k];
        const auto at = std::find(merged.begin(), merged.end(), std::make_pair(s.piece, s.index));
        if (at == merged.end()) {
          other = true;
          continue;
        }
        const std::pair<int, int> point = points[static_cast<std::size_t>(at - merged.begin())];
        refused.push_back(point);
        if (first.empty())
          first = "at partition point " + std::to_string(point.second) + " (piece " + std::to_string(point.first) +
                  ") the merged flight " + Crossing(margins[k].limit) + " by " +
                  internal::FormatNumber(-margins[k].value);
      }
      if (!refused.empty())
        r->reasons.push_back(std::to_string(refused.size()) +
                             " merges of flights shorter than min_interval or the tick keep their points, their "
                             "flights would exceed a geometric limit (the first " +
                             first + ")");
      if (other && refused.empty()) {
        refused = points;
        r->reasons.push_back("merging " + std::to_string(points.size()) +
                             " flights shorter than min_interval or the tick pushes other flights out of the limits");
      }
    }
    if (!refused.empty()) {
      for (const auto& [piece, k] : refused)
        frozen.emplace_back(piece, r->partition[static_cast<std::size_t>(piece)][static_cast<std::size_t>(k)]);
      continue;
    }
    if (!grid_report->missed_points.empty()) AddOnce("tick", &out->active);
    if (ShortFlights(out->plan, limits, rig_options) > 0) AddOnce("min_interval", &out->active);
    out->points_removed += static_cast<int>(points.size());
    out->plan = std::move(plan);
    *grid_report = std::move(report);
    *r = std::move(candidate);
    ++accepted;
  }
}

// The final verdict: the independent check, the grid's misses and the refinement's reasons.
void Conclude(const PlanProblem& problem,
              const RigLimits& limits,
              const std::optional<PhysicalParameters>& physical,
              const RigPlanOptions& options,
              const internal::PlanGridReport& grid,
              Refinement* r,
              RigPlanSummary* out) {
  if (!out->plan.IsSolutionUsable()) {
    out->status = RigPlanStatus::kPlanFailed;
    out->message = ToString(out->plan.status) + ": " + out->plan.message;
    return;
  }
  out->points_slid = grid.slid;
  if (grid.slid > 0) AddOnce("tick", &out->active);
  if (!grid.missed.empty()) AddOnce("tick", &out->blocking);
  for (const std::string& m : grid.missed) r->reasons.push_back("tick: " + m);
  // An impulse at a junction of pieces is at a fixed point: the grid cannot absorb its time.
  if (limits.tick > 0)
    for (const PlanStep& s : out->plan.steps)
      if (s.piece > 0 && s.index == 0 && s.t_impulse != std::round(s.t_impulse / limits.tick) * limits.tick) {
        AddOnce("tick", &out->blocking);
        r->reasons.push_back("tick: the impulse at the junction of pieces " + std::to_string(s.piece - 1) + " and " +
                             std::to_string(s.piece) + " (a fixed point of the path) falls at t = " +
                             internal::FormatNumber(s.t_impulse) + ", off the grid");
      }
  out->check =
      CheckPlanRigLimits(problem, out->plan, limits, physical, options.tolerances, options.check_samples_per_flight);
  for (const std::string& v : out->check.violations) AddOnce(v.substr(0, v.find(" exceeded")), &out->blocking);
  if (out->check.passed && out->blocking.empty()) {
    out->status = RigPlanStatus::kSuccess;
    out->message.clear();
    return;
  }
  out->status = RigPlanStatus::kLimitsNotMet;
  std::vector<std::string> lines = r->reasons;
  lines.insert(lines.end(), out->check.violations.begin(), out->check.violations.end());
  out->message.clear();
  for (std::size_t i = 0; i < lines.size(); ++i) out->message += (i ? "; " : "") + lines[i];
}

}  // namespace

RigPlanSummary PlanImpulsesOnRig(const PlanProblem& problem,
                                 const RigLimits& limits,
                                 const std::optional<PhysicalParameters>& physical,
                                 const PlanOptions& options,
                                 const RigPlanOptions& rig_options) {
  internal::ThrowIfInvalid(rig_options.Validate());
  internal::ThrowIfInvalid(limits.Validate());
  RigPlanSummary out;
  Refinement r;
  r.partition = MakePartition(problem.path, problem.partition, "partition");
  r.owners = EnergyChangeOwners(problem, r.partition);
  for (const auto& taus : r.partition) out.segments_initial += static_cast<int>(taus.size()) - 1;
  const internal::PlanGrid grid{limits.tick, limits.min_interval};
  internal::PlanGridReport grid_report;
  for (int round = 0;; ++round) {
    out.plan = internal::PlanPartitioned(problem.model,
                                         problem.initial,
                                         problem.mu,
                                         problem.A0,
                                         problem.path,
                                         r.partition,
                                         PlacedEnergyChanges(problem, r.owners),
                                         options,
                                         grid,
                                         &grid_report);
    if (!out.plan.IsSolutionUsable() || !HasGeometricLimits(limits)) break;
    const std::vector<Margin> margins =
        FlightMargins(problem, out.plan, limits, options.integration, rig_options.samples_per_flight);
    std::vector<std::string> exceeded;
    for (const Margin& m : margins)
      if (m.value < -rig_options.tolerances.position) AddOnce(m.limit, &exceeded), AddOnce(m.limit, &out.active);
    if (exceeded.empty()) break;
    if (PathBlocks(limits, problem.path, r.partition, rig_options, exceeded, &r, &out)) break;
    if (round == rig_options.max_rounds) {
      for (const std::string& name : exceeded) AddOnce(name, &out.blocking);
      r.reasons.push_back("after " + std::to_string(round) +
                          " rounds of refinement (max_rounds) flights still exceed the limits");
      break;
    }
    if (!Bisect(out.plan, margins, limits, rig_options, &r, &out)) break;
    out.rounds = round + 1;
  }
  if (out.plan.IsSolutionUsable() && out.blocking.empty())
    Coarsen(problem, limits, options, rig_options, grid, &r, &grid_report, &out);
  Conclude(problem, limits, physical, rig_options, grid_report, &r, &out);
  return out;
}

}  // namespace plateball
