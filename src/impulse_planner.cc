#include "plateball/impulse_planner.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "arc.h"
#include "check.h"
#include "connect.h"
#include "dynamics.h"
#include "plateball/partition.h"
#include "plateball/rolling.h"
#include "plateball/so3.h"

namespace plateball {
namespace {

using Mat9 = std::array<double, 9>;

// A' = hat(e3 x p'(tau)) A along one smooth piece (rolling.h, RollingReorientation), integrated
// segment by segment with the step size carried over, so that each A(tau_k) costs about one step.
struct CurveRollingRhs {
  const SmoothCurve* curve;
  void operator()(const Mat9& y, Mat9& dy, double tau) const {
    const Eigen::Vector2d v = curve->Derivative(tau);
    const double w0 = -v.y(), w1 = v.x();
    for (int c = 0; c < 3; ++c) {
      dy[0 + c] = w1 * y[6 + c];
      dy[3 + c] = -w0 * y[6 + c];
      dy[6 + c] = -w1 * y[0 + c] + w0 * y[3 + c];
    }
  }
};

Eigen::Matrix3d ToMatrix(const Mat9& y) {
  Eigen::Matrix3d m;
  m << y[0], y[1], y[2], y[3], y[4], y[5], y[6], y[7], y[8];
  return m;
}

// One Newton-Schulz step towards the nearest rotation: removes the O(1e-16) drift of a product of
// rotations at the cost of two 3x3 products (ProjectToSO3, an SVD, is used once at the end).
Eigen::Matrix3d Reorthonormalize(const Eigen::Matrix3d& r) {
  return 0.5 * r * (3.0 * Eigen::Matrix3d::Identity() - r.transpose() * r);
}

}  // namespace

std::string ToString(PlanStatus status) {
  switch (status) {
    case PlanStatus::kSuccess: return "success";
    case PlanStatus::kSegmentBeyondLocalRadius: return "segment_beyond_local_radius";
    case PlanStatus::kIntegrationFailure: return "integration_failure";
  }
  return "unknown";
}

std::string PlanOptions::Validate() const {
  if (bound_samples < 2) return "plan option 'bound_samples' = " + std::to_string(bound_samples) + " must be >= 2";
  std::string e = join.Validate();
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
     << bounds.theorem_2_6 << "), polyline error " << polyline_error << ", max pass miss " << max_pass_miss
     << ", time " << total_time;
  if (!message.empty()) os << " (" << message << ")";
  return os.str();
}

PlanSummary PlanImpulses(const BallModel& model, const AngleState& initial, double mu, const Eigen::Matrix3d& A0,
                         const Path& path, const std::vector<std::vector<double>>& partition,
                         const std::vector<EnergyChangeSpec>& energy_changes, const PlanOptions& options) {
  const std::string err = options.Validate();
  if (!err.empty()) throw std::invalid_argument(err);
  internal::RequirePositive("mu", mu);
  BallState state = StateFromAngles(initial, mu, model);  // validates the angles
  if (static_cast<int>(partition.size()) != path.PieceCount())
    internal::ThrowInvalid("partition (piece count)", static_cast<double>(partition.size()),
                           "must equal the number of path pieces " + std::to_string(path.PieceCount()));
  int n_total = 0;
  for (int i = 0; i < path.PieceCount(); ++i) {
    ValidatePartition(path.pieces()[i], partition[i], "partition[" + std::to_string(i) + "]");
    n_total += static_cast<int>(partition[i].size()) - 1;
  }
  std::vector<std::vector<double>> factors(static_cast<std::size_t>(n_total));
  for (std::size_t i = 0; i < energy_changes.size(); ++i) {
    const std::string f = "energy_changes[" + std::to_string(i) + "]";
    const EnergyChangeSpec& e = energy_changes[i];
    if (e.index < 0 || e.index >= n_total)
      internal::ThrowInvalid(f + ".index", e.index, "must be a partition index in [0, " + std::to_string(n_total) + ")");
    internal::RequirePositive(f + ".factor", e.factor);
    factors[static_cast<std::size_t>(e.index)].push_back(e.factor);
  }

  PlanSummary out;
  out.pieces = path.PieceCount();
  out.segments = n_total;
  out.mu_initial = mu;
  out.A0 = AlignOrientationToAxis(A0, state.z);
  out.steps.reserve(static_cast<std::size_t>(n_total));

  Eigen::Matrix3d a_ref = out.A0, a_poly = out.A0, a_imp = out.A0;
  Eigen::Vector2d x = path.StartPoint();
  double time = 0.0;
  double mu_now = mu;
  ErrorBoundConstants& c = out.bounds.constants;
  ErrorBounds& b = out.bounds;
  int g = 0;
  const double lambda = model.lambda();

  for (int piece = 0; piece < path.PieceCount() && out.status == PlanStatus::kSuccess; ++piece) {
    const SmoothCurve& curve = path.pieces()[piece];
    const std::vector<double>& taus = partition[piece];
    // Reference A(tau) along this piece: one integration carried through the partition points.
    Mat9 ref{};
    {
      const Eigen::Matrix3d a = a_ref;
      for (int r = 0; r < 3; ++r)
        for (int q = 0; q < 3; ++q) ref[3 * r + q] = a(r, q);
    }
    const CurveRollingRhs ref_rhs{&curve};
    double ref_dt = taus[1] - taus[0];
    for (std::size_t k = 0; k + 1 < taus.size(); ++k, ++g) {
      PlanStep s;
      s.piece = piece;
      s.index = static_cast<int>(k);
      s.global_index = g;
      s.tau_begin = taus[k];
      s.tau_end = taus[k + 1];
      s.p_begin = curve.Value(s.tau_begin);
      s.p_end = curve.Value(s.tau_end);
      s.t_impulse = time;
      s.state_before = state;
      s.angles_before = AnglesFromState(state, model);
      // Energy-changing impulses (the paper's remark): scale |omega|, keep its direction (the
      // angles do not change).
      for (double f : factors[static_cast<std::size_t>(g)]) {
        const Impulse e = EnergyChangingImpulse(s.angles_before, mu_now, f, model);
        s.energy_changes.push_back(e);
        mu_now = e.mu_after;
        state = e.state_after;
      }
      s.mu = mu_now;

      // The energy is tracked nominally (it is a constant of the free motion; recomputing it from
      // the integrated state would let round-off drift into it).
      const JoinSummary j = internal::ConnectPoints(model, s.angles_before, mu_now, x, s.p_end, options.join,
                                                    options.reach_fallback ? &options.reach : nullptr,
                                                    &s.reached_globally);
      s.join_status = j.status;
      s.join_residual = j.residual;
      s.join_iterations = j.iterations;
      if (!j.IsSolutionUsable()) {
        out.status = j.status == JoinStatus::kIntegrationFailure ? PlanStatus::kIntegrationFailure
                                                                 : PlanStatus::kSegmentBeyondLocalRadius;
        out.message = "segment " + std::to_string(g) + " (piece " + std::to_string(piece) + ", k = " +
                      std::to_string(k) + "): " + j.BriefReport();
        out.steps.push_back(s);
        break;
      }
      s.delta_psi = j.delta_psi;
      s.duration = j.t;
      s.impulse = j.impulse;
      s.delta_omega = j.impulse.delta_omega;
      s.plate_velocity_change = j.impulse.plate_velocity_change;

      // The free arc with its orientation, integrated directly over [0, t_k].
      const BallState after_impulse = j.impulse.state_after;
      const Eigen::Vector2d k_mom = ConservedMomentum(after_impulse, model);
      internal::ArcEnd arc;
      try {
        arc = internal::IntegrateArc(lambda, after_impulse.z, k_mom, j.t, options.integration);
      } catch (const std::runtime_error& e) {
        out.status = PlanStatus::kIntegrationFailure;
        out.message = "segment " + std::to_string(g) + ": " + e.what();
        out.steps.push_back(s);
        break;
      }
      x = x + arc.dx;
      a_imp = Reorthonormalize(arc.phi * a_imp);
      state = {arc.z, OmegaFromMomentum(arc.z, k_mom, model)};
      s.state_after = state;
      s.angles_after = AnglesFromState(state, model);
      s.x_end = x;
      s.pass_miss = (x - s.p_end).norm();
      s.arc_max_speed = arc.max_speed;
      s.arc_max_acceleration = arc.max_acceleration;

      // The orientations compared by Theorems 2.5 and 2.6.
      try {
        double last = s.tau_begin;
        internal::IntegrateAdaptive(ref_rhs, ref, s.tau_begin, s.tau_end, ref_dt, options.integration,
                                    [&](double tau, const Mat9&) {
                                      if (tau < s.tau_end) ref_dt = tau - last;
                                      last = tau;
                                    });
      } catch (const std::runtime_error& e) {
        out.status = PlanStatus::kIntegrationFailure;
        out.message = "segment " + std::to_string(g) + " (rolling reference): " + e.what();
        out.steps.push_back(s);
        break;
      }
      a_ref = Reorthonormalize(ToMatrix(ref));
      a_poly = Reorthonormalize(RollAlongSegment(s.p_begin, s.p_end) * a_poly);
      s.A_planned = a_ref;
      s.A_polyline = a_poly;
      s.A_impulsive = a_imp;

      // Bounds and constants.
      const double h = s.tau_end - s.tau_begin;
      const double chord = (s.p_end - s.p_begin).norm();
      const CurveDerivativeBounds pb = EstimateCurveDerivativeBounds(curve, s.tau_begin, s.tau_end, options.bound_samples);
      s.path_max_speed = pb.max_speed;
      s.path_max_acceleration = pb.max_acceleration;
      s.path_bound = SegmentBound(pb.max_speed, pb.max_acceleration, h);
      s.arc_bound = SegmentBound(arc.max_speed, arc.max_acceleration, j.t);
      b.a_posteriori_path += s.path_bound;
      b.a_posteriori_arcs += s.arc_bound;
      b.sum_dtau_cubed += h * h * h;
      b.parameter_norm = std::max(b.parameter_norm, h);
      c.K_p = std::max(c.K_p, pb.max_acceleration);
      c.M_prime_p = std::max(c.M_prime_p, pb.max_speed);
      c.C_p = std::max(c.C_p, h / chord);
      c.M_prime = std::max(c.M_prime, arc.max_speed);
      c.K_10 = std::max(c.K_10, 0.5 * arc.max_acceleration);
      c.K1 = std::max(c.K1, j.t / chord);

      out.max_pass_miss = std::max(out.max_pass_miss, s.pass_miss);
      out.max_join_residual = std::max(out.max_join_residual, j.residual);
      time += j.t;
      out.steps.push_back(std::move(s));
    }
  }

  c.K_bar_p = c.K_p * c.M_prime_p;
  c.D_p = c.M_prime_p;
  c.K_tilde = 2.0 * c.K_10 * c.M_prime;
  c.K_tilde_p = c.K_tilde * std::pow(c.K1 * c.D_p, 3);
  b.segments = n_total;
  b.theorem_2_5 = c.K_bar_p * b.sum_dtau_cubed;
  b.corollary_2 = c.K_bar_p * n_total * std::pow(b.parameter_norm, 3);
  b.theorem_2_6 = (c.K_bar_p + c.K_tilde_p) * b.sum_dtau_cubed;
  b.corollary_3 = (c.K_bar_p + c.K_tilde_p) * n_total * std::pow(b.parameter_norm, 3);
  b.a_posteriori = b.a_posteriori_path + b.a_posteriori_arcs;

  out.total_time = time;
  a_ref = ProjectToSO3(a_ref);
  a_poly = ProjectToSO3(a_poly);
  a_imp = ProjectToSO3(a_imp);
  out.A_planned = a_ref;
  out.A_polyline = a_poly;
  out.A_impulsive = a_imp;
  out.measured_error = OperatorNormDistance(a_ref, a_imp);
  out.polyline_error = OperatorNormDistance(a_ref, a_poly);
  out.final_state = state;
  out.mu_final = mu_now;
  return out;
}

PlanSummary PlanImpulses(const Problem& problem, const PlanOptions& options, int n) {
  if (!problem.plan) throw std::invalid_argument("'plan' is missing: the problem has no plan task");
  const PlanTask& task = *problem.plan;
  const Path path = Path::FromSpec(task.path, "plan.path");
  PartitionSpec spec = task.partition;
  if (n > 0) spec.n = n;
  const auto partition = MakePartition(path, spec, "plan.partition");
  const double size = std::max(1.0, path.Length());
  if ((problem.x0 - path.StartPoint()).norm() > 1e-9 * size) {
    std::ostringstream os;
    os.precision(17);
    os << "'x0' = (" << problem.x0.x() << ", " << problem.x0.y() << ") is invalid: must equal the path start p(tau_0) = ("
       << path.StartPoint().x() << ", " << path.StartPoint().y() << ")";
    throw std::invalid_argument(os.str());
  }
  PlanOptions o = options;
  o.integration = problem.integration;
  o.join.integration = problem.integration;
  return PlanImpulses(problem.model, problem.initial_angles, problem.mu, problem.A0, path, partition,
                      task.energy_changes, o);
}

}  // namespace plateball
