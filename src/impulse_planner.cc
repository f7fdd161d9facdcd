#include "plateball/impulse_planner.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "arc.h"
#include "check.h"
#include "connect.h"
#include "dynamics.h"
#include "field_check.h"
#include "plan_partitioned.h"
#include "plateball/partition.h"
#include "plateball/rolling.h"
#include "plateball/so3.h"

namespace plateball {
namespace {

// One Newton-Schulz step towards the nearest rotation: removes the O(1e-16) drift of a product of
// rotations at the cost of two 3x3 products (ProjectToSO3, an SVD, is used once at the end).
Eigen::Matrix3d Reorthonormalize(const Eigen::Matrix3d& r) {
  return 0.5 * r * (3.0 * Eigen::Matrix3d::Identity() - r.transpose() * r);
}

}  // namespace

std::string ToString(PlanStatus status) {
  switch (status) {
    case PlanStatus::kNotRun:
      return "not_run";
    case PlanStatus::kSuccess:
      return "success";
    case PlanStatus::kSegmentBeyondLocalRadius:
      return "segment_beyond_local_radius";
    case PlanStatus::kIntegrationFailure:
      return "integration_failure";
  }
  return "unknown";
}

std::string PlanOptions::Validate() const {
  std::string e = internal::CheckRanges(*this);  // bound_samples (the field list)
  if (!e.empty()) return e;
  e = join.Validate();
  if (!e.empty()) return e;
  if (reach_fallback) {
    e = reach.Validate();
    if (!e.empty()) return "plan option 'reach': " + e;
  }
  return integration.Validate();
}

std::string PlanSummary::BriefReport() const {
  std::ostringstream os;
  os.precision(4);
  os << "Plan: " << ToString(status) << ", n = " << segments << " (" << pieces << " piece" << (pieces == 1 ? "" : "s")
     << "), measured error " << measured_error << " <= bound " << bounds.a_posteriori << " (Theorem 2.6 "
     << bounds.theorem_2_6 << "), polyline error " << polyline_error << ", max pass miss " << max_pass_miss << ", time "
     << total_time;
  if (!message.empty()) os << " (" << message << ")";
  return os.str();
}

namespace {

// What the validation of a plan hands on: the reduced initial angles, n, and the
// energy-changing factors of each global segment index.
struct PlanInput {
  AngleState initial;
  int n_total = 0;
  std::vector<std::vector<double>> factors;
};

// The public boundary, checked once: options, mu, angles (reduced mod 2 pi), the step count of
// the partition (MakePartition validated each piece's points), the energy-change indices and factors.
PlanInput ValidatePlan(const AngleState& initial,
                       double mu,
                       const Path& path,
                       const std::vector<std::vector<double>>& partition,
                       const std::vector<EnergyChange>& energy_changes,
                       const PlanOptions& options) {
  internal::ThrowIfInvalid(options.Validate());
  internal::RequireEnergy("mu", mu);
  PlanInput in;
  in.initial = internal::ReduceAngles("initial", initial);
  if (static_cast<int>(partition.size()) != path.PieceCount())
    internal::ThrowInvalid("partition (piece count)",
                           static_cast<double>(partition.size()),
                           "must equal the number of path pieces " + std::to_string(path.PieceCount()));
  for (int i = 0; i < path.PieceCount(); ++i) {  // each piece's partition validated by MakePartition
    in.n_total += static_cast<int>(partition[i].size()) - 1;
    if (in.n_total > internal::kMaxPartitionSteps)  // README, "Limits"
      internal::ThrowInvalid(
          "partition (steps)", in.n_total, "must be <= " + std::to_string(internal::kMaxPartitionSteps));
  }
  in.factors.resize(static_cast<std::size_t>(in.n_total));
  for (std::size_t i = 0; i < energy_changes.size(); ++i) {
    const std::string f = "energy_changes[" + std::to_string(i) + "]";
    const EnergyChange& e = energy_changes[i];
    if (e.index < 0 || e.index >= in.n_total)
      internal::ThrowInvalid(
          f + ".index", e.index, "must be a partition index in [0, " + std::to_string(in.n_total) + ")");
    internal::RequirePositive(f + ".factor", e.factor);
    in.factors[static_cast<std::size_t>(e.index)].push_back(e.factor);
  }
  return in;
}

// The state carried from segment to segment: the ball, its energy, the contact point, the clock,
// the canonical angles of the ball (computed once per arrival) and the three orientations that
// Theorems 2.5 and 2.6 compare.
struct PlanCursor {
  BallState state;
  AngleState angles;
  double mu = 0.0;
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  double time = 0.0;
  Eigen::Matrix3d a_ref, a_poly, a_imp;
  internal::RowMajor3x3 ref{};                  // A(tau) integrated along the current piece
  double ref_dt = 0.0;                          // its step size, carried from segment to segment
  internal::ArcStepHints arc_steps;             // the free arcs' integration steps, carried from arc to arc
  internal::JoinCarry join_carry{false, 0.0};   // the joins' step; no arrival angles (FlyArc's)
  Eigen::Vector2d p = Eigen::Vector2d::Zero();  // p(tau_k): the last segment's end on this piece
  // On a circle piece rolled in closed form: its radius |p'| and Rz(tau_k) (the last segment's
  // Rz(tau_k+1)), each computed once instead of once per segment.
  double circle_radius = 0.0;
  Eigen::Matrix3d rz = Eigen::Matrix3d::Identity();
};

// A grid for the impulse times and where the segment's end may slide (tau_next: the next
// partition point; NaN: the end is a fixed point of the path).
struct SegmentGrid {
  const internal::PlanGrid* grid = nullptr;
  internal::PlanGridReport* report = nullptr;
  double tau_next = std::numeric_limits<double>::quiet_NaN();
};

// "segment g (piece p, k = k): " and the like, for the failure messages.
std::string SegmentName(const PlanStep& s) {
  return "segment " + std::to_string(s.global_index) + " (piece " + std::to_string(s.piece) +
         ", k = " + std::to_string(s.index) + ")";
}

// Energy-changing impulses at p(tau_k) (the paper's remark): scale |omega|, keep its direction
// (the angles do not change). The energy is tracked nominally: it is a constant of the free
// motion, and recomputing it from the integrated state would let round-off drift into it.
void ApplyEnergyChanges(const BallModel& model, const std::vector<double>& factors, PlanCursor* cur, PlanStep* s) {
  for (double f : factors) {
    const Impulse e = EnergyChangingImpulse(s->angles_before, cur->mu, f, model);
    s->energy_changes.push_back(e);
    cur->mu = e.mu_after;
    cur->state = e.state_after;
  }
  s->mu = cur->mu;
}

// The impulse at p(tau_k) and the free arc with its orientation, integrated directly over
// [0, t_k]. Returns the arc; the step records the join and the arrival.
internal::ArcEnd FlyArc(
    const BallModel& model, const JoinSummary& j, const PlanOptions& options, PlanCursor* cur, PlanStep* s) {
  s->delta_psi = j.delta_psi;
  s->duration = j.t;
  s->impulse = j.impulse;
  s->delta_omega = j.impulse.delta_omega;
  s->plate_velocity_change = j.impulse.plate_velocity_change;
  const BallState after_impulse = j.impulse.state_after;
  const Eigen::Vector2d k_mom = ConservedMomentum(after_impulse, model);
  const internal::ArcEnd arc =
      internal::IntegrateArc(model.lambda(), after_impulse.z, k_mom, j.t, options.integration, &cur->arc_steps);
  cur->x += arc.dx;
  cur->a_imp = Reorthonormalize(arc.phi * cur->a_imp);
  cur->state = {arc.z, OmegaFromMomentum(arc.z, k_mom, model)};
  cur->angles = AnglesFromState(cur->state, model);
  s->state_after = cur->state;
  s->angles_after = cur->angles;
  s->x_end = cur->x;
  s->pass_miss = (cur->x - s->p_end).norm();
  s->arc_max_speed = arc.max_speed;
  s->arc_max_acceleration = arc.max_acceleration;
  return arc;
}

// Rolling along a circle or a line piece in closed form (exact up to rounding; the derivation is in
// tests/rolling_test.cc): on p = c + rho (cos tau, sin tau), omega = e3 x p' = Rz(tau) w0 with
// w0 = (-rho, 0, 0), so A = Rz(tau) B with B' = hat(w0 - e3) B and
//   A(tau_b) = Rz(tau_b) exp((tau_b - tau_a) hat(w0 - e3)) Rz(tau_a)^T A(tau_a);
// a line rolls as RollAlongSegment. False for the other curves (and a reversed circle): integrated.
bool RollsInClosedForm(const SmoothCurve& curve) {
  return curve.kind() == CurveKind::kLine || (curve.kind() == CurveKind::kCircle && !curve.reversed());
}

// Rz(tau_k) and the radius for the closed form on a circle piece (RollInClosedForm carries Rz).
void StartClosedFormPiece(const SmoothCurve& curve, double tau_begin, PlanCursor* cur) {
  if (curve.kind() != CurveKind::kCircle) return;
  cur->circle_radius = curve.DerivativeNorms(tau_begin)[0];
  cur->rz = RotationZ(tau_begin);
}

bool RollInClosedForm(const SmoothCurve& curve, const PlanStep& s, PlanCursor* cur) {
  if (!RollsInClosedForm(curve)) return false;
  const Eigen::Matrix3d a = internal::MatrixFromRowMajor(cur->ref.data());
  if (curve.kind() == CurveKind::kLine) {
    internal::RowMajorFromMatrix(RollAlongSegment(s.p_begin, s.p_end) * a, cur->ref.data());
    return true;
  }
  const Eigen::Matrix3d rz_b = RotationZ(s.tau_end);
  const Eigen::Matrix3d b = ExpSO3((s.tau_end - s.tau_begin) * Eigen::Vector3d(-cur->circle_radius, 0.0, -1.0));
  internal::RowMajorFromMatrix(rz_b * b * cur->rz.transpose() * a, cur->ref.data());
  cur->rz = rz_b;
  return true;
}

// Segments longer than this on the plate (chord, in ball radii) roll the reference with Fehlberg
// 7(8), shorter ones with Dormand-Prince 5(4): at tolerance 1e-12 a dopri5 step covers about 0.02,
// so a short segment is one dopri5 step (7 evaluations), while a long one takes several and
// rkf78 needs fewer evaluations (T2 before the circle's closed form: n = 16 6.5M -> 5.1M
// instructions, n = 128 8.6M -> 7.4M; n >= 512 has chords below 0.025 and keeps dopri5).
constexpr double kLongReferenceSegment = 0.035;

// The reference over the segment by integration (one integration carried through the partition
// points, its step size with it, so that each costs about one step).
void IntegrateReference(const SmoothCurve& curve, const PlanOptions& options, const PlanStep& s, PlanCursor* cur) {
  namespace odeint = boost::numeric::odeint;
  const internal::RollingRhs rhs{[&curve](double tau) { return curve.Derivative(tau); }};
  double last = s.tau_begin;
  const auto observe = [&](double tau, const internal::RowMajor3x3&) {
    if (tau < s.tau_end) cur->ref_dt = tau - last;
    last = tau;
  };
  if ((s.p_end - s.p_begin).norm() > kLongReferenceSegment)
    internal::IntegrateAdaptive<odeint::runge_kutta_fehlberg78<internal::RowMajor3x3>>(
        rhs, cur->ref, s.tau_begin, s.tau_end, cur->ref_dt, options.integration, observe);
  else
    internal::IntegrateAdaptive(rhs, cur->ref, s.tau_begin, s.tau_end, cur->ref_dt, options.integration, observe);
}

// The planned A(tau_k+1) (rolling along the curve: in closed form on circles and lines, else
// integrated) and the polyline's Abar_k+1.
void AdvanceReferences(const SmoothCurve& curve, const PlanOptions& options, PlanCursor* cur, PlanStep* s) {
  if (!RollInClosedForm(curve, *s, cur)) IntegrateReference(curve, options, *s, cur);
  cur->a_ref = Reorthonormalize(internal::MatrixFromRowMajor(cur->ref.data()));
  cur->a_poly = Reorthonormalize(RollAlongSegment(s->p_begin, s->p_end) * cur->a_poly);
  s->A_planned = cur->a_ref;
  s->A_polyline = cur->a_poly;
  s->A_impulsive = cur->a_imp;
}

// The measured derivative maxima of the segment and its terms of the bounds.
void AddBounds(const SmoothCurve& curve,
               const internal::ArcEnd& arc,
               const JoinSummary& j,
               const PlanOptions& options,
               PlanStep* s,
               ErrorBounds* b) {
  SegmentMeasures m;
  m.h = s->tau_end - s->tau_begin;
  m.chord = (s->p_end - s->p_begin).norm();
  m.path = EstimateCurveDerivativeBounds(curve, s->tau_begin, s->tau_end, options.bound_samples);
  m.arc_time = j.t;
  m.arc_max_speed = arc.max_speed;
  m.arc_max_acceleration = arc.max_acceleration;
  s->path_max_speed = m.path.max_speed;
  s->path_max_acceleration = m.path.max_acceleration;
  s->path_bound = SegmentBound(m.path.max_speed, m.path.max_acceleration, m.h);
  s->arc_bound = SegmentBound(arc.max_speed, arc.max_acceleration, j.t);
  AccumulateSegment(m, b);
}

// The flight time from the cursor's state (after the energy changes) to p(tau): the join's t, NaN
// when no join connects them. The trial joins start from a copy of the cursor's join carry.
double FlightTimeTo(const BallModel& model,
                    const SmoothCurve& curve,
                    const PlanOptions& options,
                    const PlanCursor& cur,
                    const PlanStep& s,
                    double tau) {
  internal::JoinCarry carry = cur.join_carry;
  const JoinSummary j = internal::ConnectPoints(model,
                                                s.angles_before,
                                                cur.mu,
                                                cur.x,
                                                curve.Value(tau),
                                                options.join,
                                                options.reach_fallback ? &options.reach : nullptr,
                                                nullptr,
                                                &carry);
  return j.IsSolutionUsable() ? j.t : std::numeric_limits<double>::quiet_NaN();
}

// A partition point slid onto the grid: its tau, its tick index and the flight's duration.
struct GridSlide {
  double tau = 0.0;
  long long index = 0;
  double duration = 0.0;
};

// Slides the end of segment s along the curve, strictly between tau_begin and tau_next, so that the
// flight to it lasts D = m tick - t_impulse: m the multiple nearest the unslid arrival, at least
// min_interval after the impulse. The flight time t(tau) is monotone on the local branch; its root
// t(tau) = D is bracketed between tau_begin (t = 0) and the unslid end or tau_next, and found by
// regula falsi with the Illinois modification, to rounding of tau or of t. Empty (with *why) when
// the join fails or D is beyond the next partition point.
std::optional<GridSlide> SlideOntoGrid(const BallModel& model,
                                       const SmoothCurve& curve,
                                       const PlanOptions& options,
                                       const internal::PlanGrid& grid,
                                       double tau_next,
                                       const PlanCursor& cur,
                                       const PlanStep& s,
                                       std::string* why) {
  const auto t_of = [&](double tau) { return FlightTimeTo(model, curve, options, cur, s, tau); };
  const double t_nominal = t_of(s.tau_end);
  if (std::isnan(t_nominal)) return *why = "no join reaches the unslid point", std::nullopt;
  const double start = cur.time;
  long long m =
      std::max(std::llround((start + t_nominal) / grid.tick), static_cast<long long>(std::floor(start / grid.tick)));
  while (!(static_cast<double>(m) * grid.tick - start > 0.0 &&
           static_cast<double>(m) * grid.tick - start >= grid.min_interval))
    ++m;
  const double d = static_cast<double>(m) * grid.tick - start;
  double a = s.tau_begin, fa = -d, b = s.tau_end, fb = t_nominal - d;
  if (fb < 0) {
    a = b, fa = fb, b = tau_next, fb = t_of(tau_next) - d;
    if (!(fb >= 0)) {
      *why = "the tick multiple " + internal::FormatNumber(static_cast<double>(m) * grid.tick) +
             " lies beyond the arrival at the next partition point";
      return std::nullopt;
    }
  }
  // |t(tau) - D| at the rounding of t: the join's t carries noise of its residual, so the bracket
  // collapsing to adjacent doubles ends the search too.
  const double tolerance = 4 * std::numeric_limits<double>::epsilon() * d;
  constexpr int kMaxIterations = 200;  // Illinois converges superlinearly: 4 to 6 joins on the circle at 1 kHz
  int side = 0;
  for (int it = 0; it < kMaxIterations; ++it) {
    double c = (a * fb - b * fa) / (fb - fa);
    if (!(c > a && c < b)) c = 0.5 * (a + b);
    if (!(c > a && c < b)) break;
    const double t = t_of(c);
    if (std::isnan(t)) return *why = "no join reaches p(tau = " + internal::FormatNumber(c) + ")", std::nullopt;
    const double fc = t - d;
    if (std::abs(fc) <= tolerance) return GridSlide{c, m, d};
    if ((fc > 0) == (fb > 0)) {
      b = c, fb = fc;
      if (side == -1) fa /= 2;
      side = -1;
    } else {
      a = c, fa = fc;
      if (side == 1) fb /= 2;
      side = 1;
    }
  }
  const double c = a > s.tau_begin && std::abs(fa) < std::abs(fb) ? a : b;
  if (!(c < tau_next)) return *why = "the root lies at the next partition point", std::nullopt;
  return GridSlide{c, m, d};
}

// One segment k of a piece: energy changes, the join to p(tau_k+1), the arc, the references and
// the bounds. False (with out->status and out->message set) when the plan cannot go on.
bool PlanSegment(const BallModel& model,
                 const SmoothCurve& curve,
                 const std::vector<double>& factors,
                 const PlanOptions& options,
                 const SegmentGrid& grid,
                 PlanCursor* cur,
                 PlanStep* s,
                 PlanSummary* out) {
  s->p_begin = cur->p;
  s->t_impulse = cur->time;
  s->state_before = cur->state;
  s->angles_before = cur->angles;
  ApplyEnergyChanges(model, factors, cur, s);
  std::optional<GridSlide> slide;
  if (grid.grid && grid.grid->tick > 0 && !std::isnan(grid.tau_next)) {
    std::string why;
    slide = SlideOntoGrid(model, curve, options, *grid.grid, grid.tau_next, *cur, *s, &why);
    if (slide) {
      s->tau_end = slide->tau;
      ++grid.report->slid;
    } else {
      grid.report->missed.push_back("partition point " + std::to_string(s->global_index + 1) + " (piece " +
                                    std::to_string(s->piece) + ", tau = " + internal::FormatNumber(s->tau_end) +
                                    "): " + why);
      grid.report->missed_points.emplace_back(s->piece, s->index + 1);
    }
  }
  s->p_end = cur->p = curve.Value(s->tau_end);
  JoinSummary j = internal::ConnectPoints(model,
                                          s->angles_before,
                                          cur->mu,
                                          cur->x,
                                          s->p_end,
                                          options.join,
                                          options.reach_fallback ? &options.reach : nullptr,
                                          &s->reached_globally,
                                          &cur->join_carry);
  s->join_status = j.status;
  s->join_residual = j.residual;
  s->join_iterations = j.iterations;
  if (!j.IsSolutionUsable()) {
    out->status = j.status == JoinStatus::kIntegrationFailure ? PlanStatus::kIntegrationFailure
                                                              : PlanStatus::kSegmentBeyondLocalRadius;
    out->message = SegmentName(*s) + ": " + j.BriefReport();
    return false;
  }
  if (slide) j.t = slide->duration;  // the grid's difference; the join's t is within the root find's tolerance
  internal::ArcEnd arc;
  try {
    arc = FlyArc(model, j, options, cur, s);
  } catch (const std::runtime_error& e) {
    out->status = PlanStatus::kIntegrationFailure;
    out->message = "segment " + std::to_string(s->global_index) + ": " + e.what();
    return false;
  }
  try {
    AdvanceReferences(curve, options, cur, s);
  } catch (const std::runtime_error& e) {
    out->status = PlanStatus::kIntegrationFailure;
    out->message = "segment " + std::to_string(s->global_index) + " (rolling reference): " + e.what();
    return false;
  }
  AddBounds(curve, arc, j, options, s, &out->bounds);
  cur->time = slide ? static_cast<double>(slide->index) * grid.grid->tick : cur->time + j.t;  // on the grid exactly
  out->max_pass_miss = std::max(out->max_pass_miss, s->pass_miss);
  out->max_join_residual = std::max(out->max_join_residual, j.residual);
  return true;
}

// The bounds from the accumulated constants, the final orientations and their errors.
void FinishPlan(const PlanCursor& cur, int n_total, PlanSummary* out) {
  CompleteBounds(n_total, &out->bounds);
  out->total_time = cur.time;
  out->A_planned = ProjectToSO3(cur.a_ref);
  out->A_polyline = ProjectToSO3(cur.a_poly);
  out->A_impulsive = ProjectToSO3(cur.a_imp);
  out->measured_error = OperatorNormDistance(out->A_planned, out->A_impulsive);
  out->polyline_error = OperatorNormDistance(out->A_planned, out->A_polyline);
  out->final_state = cur.state;
  out->mu_final = cur.mu;
}

}  // namespace

namespace internal {

PlanSummary PlanPartitioned(const BallModel& model,
                            const AngleState& initial,
                            double mu,
                            const Eigen::Matrix3d& A0,
                            const Path& path,
                            const std::vector<std::vector<double>>& partition,
                            const std::vector<EnergyChange>& energy_changes,
                            const PlanOptions& options,
                            const PlanGrid& grid,
                            PlanGridReport* report) {
  PlanGridReport unused;
  if (!report) report = &unused;
  *report = {};
  const PlanInput in = ValidatePlan(initial, mu, path, partition, energy_changes, options);
  PlanSummary out;
  out.status = PlanStatus::kSuccess;  // until a segment fails
  out.message.clear();
  out.pieces = path.PieceCount();
  out.segments = in.n_total;
  out.mu_initial = mu;
  PlanCursor cur;
  cur.state = StateFromAngles(in.initial, mu, model);
  cur.angles = AnglesFromState(cur.state, model);
  cur.mu = mu;
  cur.x = path.StartPoint();
  out.A0 = AlignOrientationToAxis(A0, cur.state.z);
  cur.a_ref = cur.a_poly = cur.a_imp = out.A0;
  out.steps.reserve(static_cast<std::size_t>(in.n_total));
  int g = 0;
  for (int piece = 0; piece < path.PieceCount() && out.status == PlanStatus::kSuccess; ++piece) {
    const SmoothCurve& curve = path.pieces()[piece];
    std::vector<double> taus = partition[piece];  // the interior points slide onto a grid
    internal::RowMajorFromMatrix(cur.a_ref, cur.ref.data());
    cur.ref_dt = taus[1] - taus[0];
    cur.p = curve.Value(taus[0]);
    StartClosedFormPiece(curve, taus[0], &cur);
    for (std::size_t k = 0; k + 1 < taus.size(); ++k, ++g) {
      PlanStep s;
      s.piece = piece;
      s.index = static_cast<int>(k);
      s.global_index = g;
      s.tau_begin = taus[k];
      s.tau_end = taus[k + 1];
      SegmentGrid sg{&grid, report};
      if (k + 2 < taus.size()) sg.tau_next = taus[k + 2];
      const bool ok = PlanSegment(model, curve, in.factors[static_cast<std::size_t>(g)], options, sg, &cur, &s, &out);
      taus[k + 1] = s.tau_end;
      out.steps.push_back(std::move(s));
      if (!ok) break;
    }
  }
  FinishPlan(cur, in.n_total, &out);
  return out;
}

}  // namespace internal

PlanSummary PlanImpulses(const PlanProblem& problem, const PlanOptions& options) {
  const std::vector<std::vector<double>> partition = MakePartition(problem.path, problem.partition, "partition");
  return internal::PlanPartitioned(
      problem.model, problem.initial, problem.mu, problem.A0, problem.path, partition, problem.energy_changes, options);
}

}  // namespace plateball
