#include "constrained_arrival.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <nlopt.hpp>
#include <stdexcept>

#include "check.h"
#include "dense_qp.h"
#include "dense_solve.h"
#include "plateball/plate_impulse.h"

namespace plateball::internal {

namespace {

// Smallest flight time the solver allows (the arcs must stay positive).
constexpr double kMinFlight = 1e-6;
// A constraint within this of its bound counts as active in the report.
constexpr double kActiveTolerance = 1e-6;
// The solver's constraints count as met to this (the sampling margin keeps the check's room).
constexpr double kFeasibilityTolerance = 1e-7;
// The impulse bounds are imposed this much tighter (relative): SLSQP holds an inequality to 1e-10
// absolute, which for a small bound (0.05) can exceed the independent check's relative tolerance.
constexpr double kImpulseMargin = 1e-8;
// Points per flight of the dense look between sample nodes, and the rounds of adding missed points.
constexpr int kDenseSamples = 32;
constexpr int kExchangeRounds = 3;
// An SLSQP round that ends farther outside than this fraction of the sampling margin is not run again.
constexpr double kRestartViolation = 0.5;
// The Gauss-Newton SQP before SLSQP: its steps (a few bring the start near the solution and near
// feasibility, from where SLSQP finishes in a handful of evaluations; further steps converge only
// linearly, the Gauss-Newton model lacking the constraints' curvature), the Levenberg damping
// (relative to the largest curvature), the step below which it has converged (relative to u), the
// shortest line-search step.
constexpr int kSqpIterations = 4;
constexpr double kSqpDamping = 1e-8;
constexpr double kSqpStep = 1e-10;
constexpr double kSqpSmallestStep = 1.0 / 16;
// The sufficient decrease of the merit along a step (Armijo).
constexpr double kArmijo = 1e-4;
// Halvings of the turns tried for the start of the closest feasible arrival search.
constexpr int kTurnHalvings = 6;
// RestoreFeasibility also acts on a point whose arrival residual (at the Jacobian's tolerance) is above this.
constexpr double kRestoreResidual = 1e-9;

enum class ImpulseRole { kTurn, kStart, kStop };

// The magnitude the limits bound of one impulse at (z, K) turning psi by s: |J| with physical
// parameters, else the plate's velocity change 2 |delta omega_h|.
double ImpulseMagnitude(const ConstrainedSetup& s,
                        Eigen::Vector3d z,
                        const Eigen::Vector2d& k,
                        double turn,
                        ImpulseRole role,
                        bool as_impulse) {
  z.normalize();
  Eigen::Vector2d w_before, k_after, w_after;
  OmegaFromZK(z.data(), k.data(), s.lambda, w_before.data());
  ImpulseMomentum(z.data(), k.data(), turn, s.lambda, k_after.data());
  OmegaFromZK(z.data(), k_after.data(), s.lambda, w_after.data());
  Eigen::Vector2d dw = w_after - w_before;
  if (role == ImpulseRole::kStart) dw = w_after;
  if (role == ImpulseRole::kStop) dw = -w_before;
  if (!as_impulse) return 2.0 * dw.norm();
  return PlateImpulseFor(*s.physical, z, Eigen::Vector3d(dw.x(), dw.y(), 0.0)).plate.norm();
}

// Its gradient with respect to (z, K, s) by central differences of the closed form (no integration).
Eigen::Matrix<double, 1, 6> ImpulseGradient(const ConstrainedSetup& s,
                                            const Eigen::Vector3d& z,
                                            const Eigen::Vector2d& k,
                                            double turn,
                                            ImpulseRole role,
                                            bool as_impulse) {
  Eigen::Matrix<double, 6, 1> v;
  v << z, k, turn;
  Eigen::Matrix<double, 1, 6> g;
  for (int i = 0; i < 6; ++i) {
    const double h = 1e-7 * std::max(1.0, std::abs(v[i]));
    Eigen::Matrix<double, 6, 1> a = v, b = v;
    a[i] += h;
    b[i] -= h;
    g[i] = (ImpulseMagnitude(s, a.head<3>(), a.segment<2>(3), a[5], role, as_impulse) -
            ImpulseMagnitude(s, b.head<3>(), b.segment<2>(3), b[5], role, as_impulse)) /
           (2 * h);
  }
  return g;
}

// The sample nodes of each flight: fractions 0 < f_1 < ... < f_m = 1 of its duration, the sub-chain
// cutting flight k at them (zero impulses: the same motion).
struct Samples {
  std::vector<std::vector<double>> fractions;  // per flight
  std::vector<int> offset;                     // node of impulse k in the sub-chain; offset[n] = last
  int nodes = 0;                               // sub-arcs in all

  explicit Samples(std::vector<std::vector<double>> f) : fractions(std::move(f)) {
    for (const auto& fk : fractions) {
      offset.push_back(nodes);
      nodes += static_cast<int>(fk.size());
    }
    offset.push_back(nodes);
  }
  // The sub-chain's parameters as functions of u (the Jacobian's columns).
  ChainColumns Columns() const {
    const int n = static_cast<int>(fractions.size());
    ChainColumns c;
    c.columns = 2 * n;
    for (int k = 0; k < n; ++k)
      for (std::size_t j = 0; j < fractions[static_cast<std::size_t>(k)].size(); ++j) {
        c.s_column.push_back(j == 0 ? k : -1);
        c.t_column.push_back(n + k);
        c.t_scale.push_back(Width(k, static_cast<int>(j)));
      }
    return c;
  }
  static Samples Uniform(int n, int m) {
    std::vector<double> f;
    for (int j = 1; j <= m; ++j) f.push_back(static_cast<double>(j) / m);
    return Samples(std::vector<std::vector<double>>(static_cast<std::size_t>(n), f));
  }
  double Width(int k, int j) const {
    const auto& f = fractions[static_cast<std::size_t>(k)];
    return f[static_cast<std::size_t>(j)] - (j == 0 ? 0.0 : f[static_cast<std::size_t>(j) - 1]);
  }
};

Eigen::VectorXd SubParameters(const Eigen::VectorXd& u, const Samples& sm) {
  const int n = static_cast<int>(sm.fractions.size());
  Eigen::VectorXd v = Eigen::VectorXd::Zero(2 * sm.nodes);
  for (int k = 0; k < n; ++k) {
    const int o = sm.offset[static_cast<std::size_t>(k)];
    v[o] = u[k];
    for (std::size_t j = 0; j < sm.fractions[static_cast<std::size_t>(k)].size(); ++j)
      v[sm.nodes + o + static_cast<int>(j)] = u[n + k] * sm.Width(k, static_cast<int>(j));
  }
  return v;
}

// Everything the optimiser needs at one u: arrival residual, objective, inequalities (g <= 0),
// each with its gradient with respect to u.
struct Evaluation {
  Eigen::VectorXd u;
  Eigen::Matrix<double, 5, 1> r = Eigen::Matrix<double, 5, 1>::Zero();
  Eigen::MatrixXd dr;
  double f = 0.0;
  Eigen::RowVectorXd df;
  Eigen::MatrixXd gauss_newton;  // the deviation's Gauss-Newton Hessian (zero for the other objectives)
  std::vector<double> g;
  std::vector<Eigen::RowVectorXd> dg;
  std::vector<std::string> names;
};

void AddConstraint(Evaluation* e, const std::string& name, double g, const Eigen::RowVectorXd& dg) {
  e->names.push_back(name);
  e->g.push_back(g);
  e->dg.push_back(dg);
}

// The plate, obstacles and stroke at one sample point x (with dx/du).
void AddPositionConstraints(const ConstrainedSetup& s,
                            const Eigen::Vector2d& x,
                            const Eigen::MatrixXd& dx,
                            Evaluation* e) {
  const RigLimits& l = s.limits;
  const double keep = l.clearance + s.sampling_margin;
  Eigen::Vector2d grad;
  if (l.plate) {
    const double d = SignedDistanceInside(*l.plate, x, &grad);
    AddConstraint(e, "plate", keep - d, -grad.transpose() * dx);
  }
  for (std::size_t i = 0; i < l.obstacles.size(); ++i) {
    const double d = SignedDistanceInside(l.obstacles[i], x, &grad);
    AddConstraint(e, "obstacles[" + std::to_string(i) + "]", keep + d, grad.transpose() * dx);
  }
  if (l.stroke) {
    const Eigen::Vector2d disp = 2.0 * (x - s.start.x);
    for (int a = 0; a < 2; ++a) {
      const std::string name = a == 0 ? "stroke.x" : "stroke.y";
      const double bound = (*l.stroke)[a] - 2.0 * s.sampling_margin;
      AddConstraint(e, name, disp[a] - bound, 2.0 * dx.row(a));
      AddConstraint(e, name, -disp[a] - bound, -2.0 * dx.row(a));
    }
  }
}

struct ImpulseTerm {
  double value = 0.0;
  Eigen::RowVectorXd gradient;
};

// Impulse k of the chain (k = n: the stop).
ImpulseRole RoleOf(const ConstrainedSetup& s, int k) {
  if (k == s.n) return ImpulseRole::kStop;
  return k == 0 && s.start_at_rest ? ImpulseRole::kStart : ImpulseRole::kTurn;
}

// The bounded magnitude of impulse k (k = n: the stop) and its gradient with respect to u.
ImpulseTerm ImpulseTermAt(const ConstrainedSetup& s,
                          const Samples& sm,
                          const std::vector<ChainNode>& nodes,
                          const ChainJacobian& cj,
                          const Eigen::VectorXd& u,
                          int k,
                          bool as_impulse) {
  const std::size_t node = static_cast<std::size_t>(sm.offset[static_cast<std::size_t>(k)]);
  const ImpulseRole role = RoleOf(s, k);
  const double turn = k < s.n ? u[k] : 0.0;
  ImpulseTerm t;
  t.value = ImpulseMagnitude(s, nodes[node].z, nodes[node].k, turn, role, as_impulse);
  const Eigen::Matrix<double, 1, 6> g = ImpulseGradient(s, nodes[node].z, nodes[node].k, turn, role, as_impulse);
  t.gradient = g.head<3>() * cj.dz[node] + g.segment<2>(3) * cj.dk[node];
  if (k < s.n) t.gradient[k] += g[5];
  return t;
}

int ImpulseCount(const ConstrainedSetup& s) { return s.n + (s.stop_at_goal ? 1 : 0); }

void AddImpulseTerms(const ConstrainedSetup& s,
                     const Samples& sm,
                     const std::vector<ChainNode>& nodes,
                     const ChainJacobian& cj,
                     const Eigen::VectorXd& u,
                     Evaluation* e) {
  const RigLimits& l = s.limits;
  const bool limit_v = !std::isinf(l.max_plate_velocity_change), limit_j = !std::isinf(l.ImpulseBound());
  const bool objective = s.objective == ArrivalObjective::kTotalImpulse;
  for (int k = 0; k < ImpulseCount(s); ++k) {
    if (limit_v) {
      const ImpulseTerm t = ImpulseTermAt(s, sm, nodes, cj, u, k, false);
      AddConstraint(
          e, "max_plate_velocity_change", t.value - (1 - kImpulseMargin) * l.max_plate_velocity_change, t.gradient);
    }
    if (limit_j) {
      const ImpulseTerm t = ImpulseTermAt(s, sm, nodes, cj, u, k, true);
      AddConstraint(e, "max_plate_impulse", t.value - (1 - kImpulseMargin) * l.ImpulseBound(), t.gradient);
    }
    if (objective) {
      const ImpulseTerm t = ImpulseTermAt(s, sm, nodes, cj, u, k, s.physical.has_value());
      e->f += t.value;
      e->df += t.gradient;
    }
  }
}

void AddObjective(const ConstrainedSetup& s,
                  const Samples& sm,
                  const std::vector<ChainNode>& nodes,
                  const ChainJacobian& cj,
                  Evaluation* e) {
  if (s.objective == ArrivalObjective::kTotalTime) {
    e->f = e->u.tail(s.n).sum();
    e->df.tail(s.n).setOnes();
  } else if (s.objective == ArrivalObjective::kDeviation) {
    for (int k = 1; k < s.n; ++k) {
      const std::size_t node = static_cast<std::size_t>(sm.offset[static_cast<std::size_t>(k)]);
      const Eigen::Vector2d d = nodes[node].x - s.planned[static_cast<std::size_t>(k)];
      e->f += d.squaredNorm();
      e->df += 2.0 * d.transpose() * cj.dx[node];
      e->gauss_newton += 2.0 * cj.dx[node].transpose() * cj.dx[node];
    }
  }
}

Evaluation Evaluate(const ConstrainedSetup& s, const Samples& sm, const Eigen::VectorXd& u, int* rollouts) {
  std::vector<ChainNode> nodes(static_cast<std::size_t>(sm.nodes) + 1);
  nodes[0] = s.start;
  ChainJacobian cj;
  const ChainColumns columns = sm.Columns();
  RollChain(s.lambda, SubParameters(u, sm), s.jacobian_integration, &nodes, &cj, &columns);
  ++*rollouts;
  Evaluation e;
  e.u = u;
  e.r = ArrivalResidual(nodes.back(), s.x1, s.A1);
  e.dr = ArrivalJacobian(cj, nodes.back(), s.A1);
  e.df = Eigen::RowVectorXd::Zero(2 * s.n);
  e.gauss_newton = Eigen::MatrixXd::Zero(2 * s.n, 2 * s.n);
  AddObjective(s, sm, nodes, cj, &e);
  for (std::size_t i = 1; i < nodes.size(); ++i) AddPositionConstraints(s, nodes[i].x, cj.dx[i], &e);
  AddImpulseTerms(s, sm, nodes, cj, u, &e);
  return e;
}

// The largest violation of the limits at the sample nodes of u, from a rollout without the Jacobian
// (the values of Evaluate's constraints; MeetsLimits needs no gradients).
double MaxViolationOfValues(const ConstrainedSetup& s, const Samples& sm, const Eigen::VectorXd& u) {
  std::vector<ChainNode> nodes(static_cast<std::size_t>(sm.nodes) + 1);
  nodes[0] = s.start;
  RollChain(s.lambda, SubParameters(u, sm), s.jacobian_integration, &nodes);
  Evaluation e;
  const Eigen::MatrixXd no_dx = Eigen::MatrixXd::Zero(2, 2 * s.n);
  for (std::size_t i = 1; i < nodes.size(); ++i) AddPositionConstraints(s, nodes[i].x, no_dx, &e);
  double worst = 0.0;
  for (double g : e.g) worst = std::max(worst, g);
  const RigLimits& l = s.limits;
  const bool limit_v = !std::isinf(l.max_plate_velocity_change), limit_j = !std::isinf(l.ImpulseBound());
  for (int k = 0; k < ImpulseCount(s); ++k) {
    const std::size_t node = static_cast<std::size_t>(sm.offset[static_cast<std::size_t>(k)]);
    const ImpulseRole role = RoleOf(s, k);
    const double turn = k < s.n ? u[k] : 0.0;
    if (limit_v)
      worst = std::max(worst,
                       ImpulseMagnitude(s, nodes[node].z, nodes[node].k, turn, role, false) -
                           (1 - kImpulseMargin) * l.max_plate_velocity_change);
    if (limit_j)
      worst = std::max(worst,
                       ImpulseMagnitude(s, nodes[node].z, nodes[node].k, turn, role, true) -
                           (1 - kImpulseMargin) * l.ImpulseBound());
  }
  return worst;
}

// The plate, obstacle and stroke constraints at `dense` points per flight of u (values only): for
// each flight, the fraction of its worst point when that point breaks a limit by more than half
// the sampling margin (the sample nodes missed it), else nothing.
std::vector<std::vector<double>> MissedPoints(const ConstrainedSetup& s,
                                              const Eigen::VectorXd& u,
                                              int dense,
                                              int* rollouts) {
  const Samples sm = Samples::Uniform(s.n, dense);
  std::vector<ChainNode> nodes(static_cast<std::size_t>(sm.nodes) + 1);
  nodes[0] = s.start;
  RollChain(s.lambda, SubParameters(u, sm), s.jacobian_integration, &nodes);
  ++*rollouts;
  std::vector<std::vector<double>> missed(static_cast<std::size_t>(s.n));
  for (int k = 0; k < s.n; ++k) {
    double worst = 0.5 * s.sampling_margin;
    for (int j = 0; j < dense; ++j) {
      Evaluation e;
      AddPositionConstraints(
          s, nodes[static_cast<std::size_t>(k * dense + j + 1)].x, Eigen::MatrixXd::Zero(2, 2 * s.n), &e);
      for (double g : e.g)
        if (g > worst) worst = g, missed[static_cast<std::size_t>(k)] = {static_cast<double>(j + 1) / dense};
    }
  }
  return missed;
}

// The optimisation over the free entries of u (the others fixed at `base`).
struct Stage {
  Stage(const ConstrainedSetup& setup,
        const Samples& samples,
        Eigen::VectorXd start,
        std::vector<int> free_entries,
        bool closest_arrival,
        Evaluation known = {})
      : s(&setup),
        sm(&samples),
        base(std::move(start)),
        free(std::move(free_entries)),
        closest(closest_arrival),
        last(std::move(known)) {}
  const ConstrainedSetup* s;
  const Samples* sm;
  Eigen::VectorXd base;
  std::vector<int> free;
  bool closest;     // minimise |arrival residual|^2 under the inequalities (no equalities)
  Evaluation last;  // the latest evaluation (or the caller's, at the samples `sm`): At reuses it
  int rollouts = 0;
  int evaluations = 0;

  Eigen::VectorXd Full(const double* v) const {
    Eigen::VectorXd u = base;
    for (std::size_t i = 0; i < free.size(); ++i) u[free[i]] = v[i];
    return u;
  }
  const Evaluation& At(const double* v) {
    const Eigen::VectorXd u = Full(v);
    if (last.u.size() != u.size() || last.u != u) {
      last = Evaluate(*s, *sm, u, &rollouts);
      ++evaluations;
    }
    return last;
  }
  void Gather(const Eigen::RowVectorXd& row, double* out) const {
    for (std::size_t i = 0; i < free.size(); ++i) out[i] = row[free[i]];
  }
};

double ObjectiveCallback(unsigned nv, const double* v, double* grad, void* data) {
  Stage& st = *static_cast<Stage*>(data);
  const Evaluation& e = st.At(v);
  if (st.closest) {
    if (grad) st.Gather(2.0 * e.r.transpose() * e.dr, grad);
    return e.r.squaredNorm();
  }
  if (grad) st.Gather(e.df, grad);
  (void)nv;
  return e.f;
}

void ArrivalCallback(unsigned m, double* result, unsigned nv, const double* v, double* grad, void* data) {
  Stage& st = *static_cast<Stage*>(data);
  const Evaluation& e = st.At(v);
  for (unsigned i = 0; i < m; ++i) {
    result[i] = e.r[i];
    if (grad) st.Gather(e.dr.row(i), grad + i * nv);
  }
}

void LimitsCallback(unsigned m, double* result, unsigned nv, const double* v, double* grad, void* data) {
  Stage& st = *static_cast<Stage*>(data);
  const Evaluation& e = st.At(v);
  for (unsigned i = 0; i < m && i < e.g.size(); ++i) {
    result[i] = e.g[i];
    if (grad) st.Gather(e.dg[i], grad + i * nv);
  }
}

// The lower bound of flight k: the shortest interval between two impulses (the last flight ends at
// an impulse only with the stop), and always a positive flight.
double FlightLowerBound(const ConstrainedSetup& s, int k) {
  const bool ends_at_impulse = k < s.n - 1 || s.stop_at_goal;
  return std::max(kMinFlight, ends_at_impulse ? s.limits.min_interval : 0.0);
}

// One SLSQP run; returns the best u found (NLopt leaves it in x also when it stops early).
Eigen::VectorXd RunSlsqp(Stage* st, int* evaluations) {
  const ConstrainedSetup& s = *st->s;
  const unsigned nv = static_cast<unsigned>(st->free.size());
  std::vector<double> x(nv), lb(nv);
  for (unsigned i = 0; i < nv; ++i) {
    const int j = st->free[i];
    x[i] = st->base[j];
    lb[i] = j < s.n ? -HUGE_VAL : FlightLowerBound(s, j - s.n);
    x[i] = std::max(x[i], lb[i]);
  }
  const Evaluation& first = st->At(x.data());
  nlopt::opt opt(nlopt::LD_SLSQP, nv);
  opt.set_lower_bounds(lb);
  opt.set_min_objective(ObjectiveCallback, st);
  if (!st->closest) opt.add_equality_mconstraint(ArrivalCallback, st, std::vector<double>(5, 1e-12));
  if (!first.g.empty()) opt.add_inequality_mconstraint(LimitsCallback, st, std::vector<double>(first.g.size(), 1e-10));
  opt.set_xtol_rel(1e-9);
  opt.set_ftol_rel(1e-9);
  opt.set_maxeval(s.max_evaluations);
  double f = 0.0;
  try {
    opt.optimize(x, f);
  } catch (const nlopt::roundoff_limited&) {  // x holds the last iterate
  } catch (const std::invalid_argument&) {    // SLSQP's "more equality constraints than free unknowns" etc.
  } catch (const nlopt::forced_stop&) {
  }
  *evaluations += st->evaluations;
  return st->Full(x.data());
}

double MaxViolation(const Evaluation& e) {
  double worst = 0.0;
  for (double g : e.g) worst = std::max(worst, g);
  return worst;
}

std::vector<std::string> ActiveNames(const ConstrainedSetup& s, const Evaluation& e) {
  std::vector<std::string> out;
  const auto add = [&out](const std::string& name) {
    if (std::find(out.begin(), out.end(), name) == out.end()) out.push_back(name);
  };
  for (std::size_t i = 0; i < e.g.size(); ++i)
    if (e.g[i] > -kActiveTolerance) add(e.names[i]);
  for (int k = 0; k < s.n; ++k)
    if (s.limits.min_interval > 0 && FlightLowerBound(s, k) == s.limits.min_interval &&
        e.u[s.n + k] <= s.limits.min_interval * (1 + 1e-9))
      add("min_interval");
  return out;
}

// The free entries that Newton steps move: flight times held at their lower bound stay there.
std::vector<int> NewtonEntries(const ConstrainedSetup& s,
                               const std::vector<int>& free_entries,
                               const Eigen::VectorXd& u) {
  std::vector<int> free;
  for (int j : free_entries)
    if (j < s.n || FlightLowerBound(s, j - s.n) <= kMinFlight || u[j] > FlightLowerBound(s, j - s.n) * (1 + 1e-9))
      free.push_back(j);
  return free;
}

// |arrival residual| + the sum of the violations: what RestoreFeasibility reduces.
double FeasibilityMerit(const Evaluation& e) {
  double sum = e.r.norm();
  for (double g : e.g) sum += std::max(g, 0.0);
  return sum;
}

// From a point SLSQP left off the arrival or just outside its tolerance (round-off, e.g. on the
// kinks of the total impulse at zero impulses): Newton steps (minimum norm) on the arrival
// conditions together with the violated inequalities, each pulled onto its bound, kept while they
// reduce FeasibilityMerit. A point within both tolerances is left unchanged. `known` (at the
// samples sm) is used instead of evaluating u again when it is at u.
Evaluation RestoreFeasibility(const ConstrainedSetup& s,
                              const Samples& sm,
                              const std::vector<int>& free_entries,
                              Eigen::VectorXd* u,
                              const Evaluation& known,
                              int* rollouts) {
  constexpr int kSteps = 6;
  Evaluation e = known.u.size() == u->size() && known.u == *u ? known : Evaluate(s, sm, *u, rollouts);
  const std::vector<int> free = NewtonEntries(s, free_entries, *u);
  for (int i = 0; i < kSteps && (MaxViolation(e) > kFeasibilityTolerance || e.r.norm() > kRestoreResidual); ++i) {
    std::vector<Eigen::RowVectorXd> rows;
    std::vector<double> rhs;
    for (int c = 0; c < 5; ++c) rows.push_back(e.dr.row(c)), rhs.push_back(-e.r[c]);
    for (std::size_t c = 0; c < e.g.size(); ++c)
      if (e.g[c] > 0) rows.push_back(e.dg[c]), rhs.push_back(-e.g[c]);
    Eigen::MatrixXd J(rows.size(), free.size());
    for (std::size_t r = 0; r < rows.size(); ++r)
      for (std::size_t c = 0; c < free.size(); ++c)
        J(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) = rows[r][free[c]];
    const Eigen::VectorXd step = internal::MinimumNormSolve(
        J, Eigen::Map<const Eigen::VectorXd>(rhs.data(), static_cast<Eigen::Index>(rhs.size())));
    Eigen::VectorXd trial = *u;
    for (std::size_t c = 0; c < free.size(); ++c) trial[free[c]] += step[static_cast<Eigen::Index>(c)];
    for (int k = 0; k < s.n; ++k)
      if (trial[s.n + k] < FlightLowerBound(s, k)) return e;
    Evaluation next = Evaluate(s, sm, trial, rollouts);
    if (!(FeasibilityMerit(next) < FeasibilityMerit(e))) return e;
    *u = trial;
    e = std::move(next);
  }
  return e;
}

// Newton steps (minimum norm) on the arrival conditions over the free entries, rolled at the final
// tolerance; flight times held at their lower bound stay there. `known` (at the samples sm) gives
// the Jacobian when it is at u. Returns true when u arrives within the tolerances.
bool Polish(const ConstrainedSetup& s,
            const Samples& sm,
            const std::vector<int>& free_entries,
            const Evaluation& known,
            Eigen::VectorXd* u,
            int* rollouts) {
  const std::vector<int> free = NewtonEntries(s, free_entries, *u);
  std::vector<ChainNode> nodes(static_cast<std::size_t>(s.n) + 1);
  nodes[0] = s.start;
  RollChain(s.lambda, *u, s.integration, &nodes);
  ++*rollouts;
  Eigen::Matrix<double, 5, 1> r = ArrivalResidual(nodes.back(), s.x1, s.A1);
  const auto arrived = [&s](const Eigen::Matrix<double, 5, 1>& r) {
    return r.head<2>().norm() <= s.position_tolerance && r.tail<3>().norm() <= s.orientation_tolerance;
  };
  for (int i = 0; i < 10 && free.size() >= 5; ++i) {
    if (arrived(r)) return true;
    const Eigen::MatrixXd dr =
        i == 0 && known.u.size() == u->size() && known.u == *u ? known.dr : Evaluate(s, sm, *u, rollouts).dr;
    Eigen::MatrixXd J(5, free.size());
    for (std::size_t c = 0; c < free.size(); ++c) J.col(static_cast<Eigen::Index>(c)) = dr.col(free[c]);
    const Eigen::VectorXd step = -J.transpose() * internal::FullPivLuSolve(J * J.transpose(), r);
    Eigen::VectorXd trial = *u;
    for (std::size_t c = 0; c < free.size(); ++c) trial[free[c]] += step[static_cast<Eigen::Index>(c)];
    if ((trial.tail(s.n).array() <= 0).any()) return arrived(r);
    RollChain(s.lambda, trial, s.integration, &nodes);
    ++*rollouts;
    const Eigen::Matrix<double, 5, 1> r_new = ArrivalResidual(nodes.back(), s.x1, s.A1);
    if (!(r_new.norm() < r.norm())) return arrived(r);
    *u = trial;
    r = r_new;
  }
  return arrived(r);
}

// Fixes the impulse times to the tick grid (the nearest multiples that keep the shortest interval)
// and returns the tick index of every impulse (and of the stop).
std::vector<long long> SnapToGrid(const ConstrainedSetup& s, Eigen::VectorXd* u) {
  const double tick = s.limits.tick;
  const long long gap = std::max<long long>(1, static_cast<long long>(std::ceil(s.limits.min_interval / tick - 1e-9)));
  const int count = ImpulseCount(s);
  std::vector<long long> index(static_cast<std::size_t>(count), 0);
  double t = 0.0;
  for (int k = 1; k < count; ++k) {
    t += (*u)[s.n + k - 1];
    index[static_cast<std::size_t>(k)] = std::max(std::llround(t / tick), index[static_cast<std::size_t>(k) - 1] + gap);
  }
  for (int k = 0; k + 1 < count; ++k)
    (*u)[s.n + k] =
        static_cast<double>(index[static_cast<std::size_t>(k) + 1] - index[static_cast<std::size_t>(k)]) * tick;
  return index;
}

std::vector<int> FreeEntries(const ConstrainedSetup& s, bool grid) {
  std::vector<int> free;
  for (int j = 0; j < 2 * s.n; ++j) {
    const bool time_fixed = grid && j >= s.n && (j < 2 * s.n - 1 || s.stop_at_goal);
    if (!time_fixed) free.push_back(j);
  }
  return free;
}

}  // namespace

bool LimitsAreSlack(const ConstrainedSetup& setup, const Eigen::VectorXd& u) {
  if (setup.objective != ArrivalObjective::kDeviation || setup.limits.tick > 0) return false;
  return MeetsLimits(setup, u);
}

std::vector<std::string> ActiveLimits(const ConstrainedSetup& setup, const Eigen::VectorXd& u) {
  int rollouts = 0;
  return ActiveNames(setup, Evaluate(setup, Samples::Uniform(setup.n, setup.samples_per_arc), u, &rollouts));
}

bool MeetsLimits(const ConstrainedSetup& setup, const Eigen::VectorXd& u) {
  for (int k = 0; k < setup.n; ++k)
    if (u[setup.n + k] < FlightLowerBound(setup, k)) return false;
  int rollouts = 0;
  const Samples sm = Samples::Uniform(setup.n, setup.samples_per_arc);
  if (MaxViolationOfValues(setup, sm, u) > 0.0) return false;
  const auto missed = MissedPoints(setup, u, kDenseSamples, &rollouts);
  return std::all_of(missed.begin(), missed.end(), [](const auto& m) { return m.empty(); });
}

namespace {

// The L1 merit of the Gauss-Newton steps: the deviation + rho (|r|_1 + the violations).
double Merit(const Evaluation& e, double rho) {
  double violation = e.r.lpNorm<1>();
  for (double g : e.g) violation += std::max(g, 0.0);
  return e.f + rho * violation;
}

// Sequential quadratic programming steps with the Gauss-Newton Hessian of the deviation (a sum of
// squares), which SLSQP's quasi-Newton model would have to learn from its iterates: each solves the
// QP of the deviation's Gauss-Newton model (Levenberg-damped) under the linearised arrival
// conditions, limits and flight bounds (dense_qp.h), and a backtracking line search on the L1 merit
// accepts it. Returns the evaluation at the last accepted u, from which SLSQP finishes.
Evaluation GaussNewtonSqp(const ConstrainedSetup& s,
                          const Samples& sm,
                          const std::vector<int>& free,
                          Eigen::VectorXd u,
                          int* evaluations,
                          int* rollouts) {
  const Eigen::Index nv = static_cast<Eigen::Index>(free.size());
  const auto at = [&free](Eigen::Index i) { return free[static_cast<std::size_t>(i)]; };
  Evaluation e = Evaluate(s, sm, u, rollouts);
  ++*evaluations;
  double rho = 1.0, damping = kSqpDamping;
  for (int it = 0; it < kSqpIterations; ++it) {
    // The QP over the free entries: min 1/2 d^T H d + df d, dr d = -r, dg d <= -g, t + d_t >= bound.
    Eigen::MatrixXd H(nv, nv), E(5, nv);
    Eigen::VectorXd c(nv);
    std::vector<Eigen::Index> times;
    for (Eigen::Index i = 0; i < nv; ++i) {
      c[i] = e.df[at(i)];
      for (Eigen::Index k = 0; k < nv; ++k) H(i, k) = e.gauss_newton(at(i), at(k));
      E.col(i) = e.dr.col(at(i));
      if (at(i) >= s.n) times.push_back(i);
    }
    H.diagonal().array() += damping * (1.0 + H.diagonal().maxCoeff());
    const Eigen::Index m = static_cast<Eigen::Index>(e.g.size()), mt = static_cast<Eigen::Index>(times.size());
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(m + mt, nv);
    Eigen::VectorXd b(m + mt);
    for (Eigen::Index i = 0; i < m; ++i) {
      for (Eigen::Index k = 0; k < nv; ++k) A(i, k) = e.dg[static_cast<std::size_t>(i)][at(k)];
      b[i] = -e.g[static_cast<std::size_t>(i)];
    }
    for (Eigen::Index i = 0; i < mt; ++i) {
      const Eigen::Index col = times[static_cast<std::size_t>(i)];
      A(m + i, col) = -1.0;
      b[m + i] = u[at(col)] - FlightLowerBound(s, at(col) - s.n);
    }
    const DenseQpResult qp = SolveDenseQp(H, c, E, -e.r, A, b);
    if (!qp.solved) break;
    const Eigen::VectorXd& d = qp.d;
    if (d.cwiseAbs().maxCoeff() <= kSqpStep * (1.0 + u.cwiseAbs().maxCoeff())) break;
    double multiplier = qp.equality_multipliers.cwiseAbs().maxCoeff();
    if (m + mt > 0) multiplier = std::max(multiplier, qp.inequality_multipliers.maxCoeff());
    rho = std::max(rho, 2.0 * multiplier);
    double violation = e.r.lpNorm<1>();
    for (double g : e.g) violation += std::max(g, 0.0);
    const double slope = std::min(c.dot(d) - rho * violation, 0.0);  // the merit's derivative along d
    const double merit = Merit(e, rho);
    bool accepted = false;
    for (double alpha = 1.0; alpha >= kSqpSmallestStep && !accepted; alpha *= 0.5) {
      Eigen::VectorXd trial = u;
      for (Eigen::Index i = 0; i < nv; ++i) trial[at(i)] += alpha * d[i];
      Evaluation next = Evaluate(s, sm, trial, rollouts);
      ++*evaluations;
      if (Merit(next, rho) <= merit + kArmijo * alpha * slope) {
        u = trial;
        e = std::move(next);
        accepted = true;
      }
    }
    damping = accepted ? std::max(kSqpDamping, damping * 0.1) : damping * 100.0;
  }
  return e;
}

// SLSQP rounds, each followed by a dense look at the flights; a flight whose worst point breaks a
// limit between the sample nodes gets that point as a new node (an exchange method for the
// semi-infinite constraint "every point of the path"). Returns true when no point was missed.
// `last` is the evaluation at the final u and samples, or empty after a round that added nodes.
bool SolveWithExchange(const ConstrainedSetup& s,
                       Samples* sm,
                       const std::vector<int>& free,
                       Eigen::VectorXd* u,
                       ConstrainedOutcome* out,
                       Evaluation* last) {
  *last = Evaluation();
  for (int round = 0; round < kExchangeRounds; ++round) {
    // The evaluation at the Gauss-Newton steps' end is SLSQP's first.
    Evaluation start;
    if (s.objective == ArrivalObjective::kDeviation) {
      start = GaussNewtonSqp(s, *sm, free, *u, &out->evaluations, &out->rollouts);
      *u = start.u;
    }
    Stage st(s, *sm, *u, free, false, std::move(start));
    *u = RunSlsqp(&st, &out->evaluations);
    out->rollouts += st.rollouts;
    // Still far outside at its own sample nodes (more than the sampling margin's half, the largest
    // miss the exchange adds): more nodes only add constraints, so a further round would repeat
    // the failure. A round that ends just outside is run again.
    Evaluation at_u = RestoreFeasibility(s, *sm, free, u, st.last, &out->rollouts);
    if (MaxViolation(at_u) > kRestartViolation * s.sampling_margin) {
      *last = std::move(at_u);
      return false;
    }
    const auto missed = MissedPoints(s, *u, kDenseSamples, &out->rollouts);
    if (std::all_of(missed.begin(), missed.end(), [](const auto& m) { return m.empty(); })) {
      *last = std::move(at_u);
      return true;
    }
    auto fractions = sm->fractions;
    for (std::size_t k = 0; k < missed.size(); ++k)
      for (double f : missed[k]) {
        auto& fk = fractions[k];
        if (std::find(fk.begin(), fk.end(), f) == fk.end()) fk.insert(std::upper_bound(fk.begin(), fk.end(), f), f);
      }
    *sm = Samples(fractions);
  }
  return false;
}

// The start of the closest-arrival search: u, or u with its turns scaled by 1/2, 1/4, ... (the
// impulses shrink with them) down to none (s_k = 0: the ball rolls on with impulses of zero size),
// the first that meets the limits, else the one that breaks them least (SLSQP may not find
// feasibility from far outside). A scaled turn keeps the impulse bounds off their kink at s = 0,
// where the central differences of |impulse| give no direction.
Eigen::VectorXd LeastViolating(const ConstrainedSetup& s, const Samples& sm, const Eigen::VectorXd& u, int* rollouts) {
  Eigen::VectorXd best = u;
  double least = MaxViolation(Evaluate(s, sm, u, rollouts));
  for (int halvings = 1; halvings <= kTurnHalvings + 1 && least > 0; ++halvings) {
    Eigen::VectorXd scaled = u;
    scaled.head(s.n) *= halvings > kTurnHalvings ? 0.0 : std::ldexp(1.0, -halvings);
    const double violation = MaxViolation(Evaluate(s, sm, scaled, rollouts));
    if (violation < least) best = scaled, least = violation;
  }
  return best;
}

}  // namespace

ConstrainedOutcome SolveConstrainedArrival(const ConstrainedSetup& s, const Eigen::VectorXd& u0) {
  const bool grid = s.limits.tick > 0;
  const std::vector<int> free = FreeEntries(s, grid);
  if (free.size() < 5)
    ThrowInvalid("rig.tick",
                 s.limits.tick,
                 "fixes the impulse times, which leaves " + std::to_string(free.size()) +
                     " unknowns for the five arrival conditions: needs impulses >= 4 (>= 5 with stop_at_goal)");
  ConstrainedOutcome out;
  Samples sm = Samples::Uniform(s.n, s.samples_per_arc);
  Eigen::VectorXd u = u0;
  Evaluation last;  // at u and the samples sm, when known
  bool covered = SolveWithExchange(s, &sm, FreeEntries(s, false), &u, &out, &last);
  if (grid) {
    out.ticks = SnapToGrid(s, &u);
    covered = SolveWithExchange(s, &sm, free, &u, &out, &last);
  }
  const bool arrived = Polish(s, sm, free, last, &u, &out.rollouts);
  Evaluation e = last.u.size() == u.size() && last.u == u ? std::move(last) : Evaluate(s, sm, u, &out.rollouts);
  out.feasible = covered && MaxViolation(e) <= kFeasibilityTolerance;
  out.arrived = out.feasible && arrived;
  if (!out.arrived && !s.closest_arrival) {  // the limits that stop it at the solver's end point
    out.blocking = ActiveNames(s, e);
    if (grid) out.blocking.push_back("tick");
  } else if (!out.arrived) {  // the closest feasible arrival, and the limits that stop it
    u = LeastViolating(s, sm, u, &out.rollouts);
    Stage closest(s, sm, u, free, true);
    u = RunSlsqp(&closest, &out.evaluations);
    out.rollouts += closest.rollouts;
    e = Evaluate(s, sm, u, &out.rollouts);
    out.feasible = MaxViolation(e) <= kFeasibilityTolerance;
    out.blocking = ActiveNames(s, e);
    if (grid) out.blocking.push_back("tick");
  }
  out.active = ActiveNames(s, e);
  if (grid) out.active.push_back("tick");
  out.u = u;
  return out;
}

}  // namespace plateball::internal
