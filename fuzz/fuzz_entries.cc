#include "fuzz_entries.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "plateball/ball_model.h"
#include "plateball/ball_state.h"
#include "plateball/exact_arrival.h"
#include "plateball/fewest_impulses.h"
#include "plateball/free_motion.h"
#include "plateball/impulse.h"
#include "plateball/impulse_planner.h"
#include "plateball/isoparallel.h"
#include "plateball/join.h"
#include "plateball/path.h"
#include "plateball/problem_io.h"
#include "plateball/reach.h"
#include "plateball/rig_reference.h"
#include "plateball/so3.h"
#include "plateball/task_adapters.h"

namespace plateball::fuzz {
namespace {

[[noreturn]] void Defect(const std::string& what) {
  std::fprintf(stderr, "fuzz defect: %s\n", what.c_str());
  std::abort();
}

template <typename Derived>
void RequireFiniteResult(const char* what, const Eigen::MatrixBase<Derived>& m) {
  if (!m.allFinite()) Defect(std::string(what) + " is not finite in a result reported as valid");
}
void RequireFiniteResult(const char* what, double v) {
  if (!std::isfinite(v)) Defect(std::string(what) + " is not finite in a result reported as valid");
}

/// Reads doubles from the input, 8 bytes each; past the end it yields 0.
class Numbers {
 public:
  Numbers(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}
  double Next() {
    double v = 0.0;
    if (pos_ + sizeof(double) <= size_) std::memcpy(&v, data_ + pos_, sizeof(double));
    pos_ += sizeof(double);
    return v;
  }
  // A number in a plausible range half of the time (so that the solvers get exercised), raw otherwise.
  double Mixed(double lo, double hi) {
    const double v = Next();
    if (!std::isfinite(v) || (pos_ / 8) % 2 == 0) return v;
    const double f = std::abs(std::fmod(v, 1.0));
    return lo + (hi - lo) * f;
  }

 private:
  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t pos_ = 0;
};

}  // namespace

void ProblemReader(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  Problem p;
  try {
    p = ParseProblem(text, "fuzz.json");
  } catch (const std::invalid_argument&) {
    return;  // a clear error is the expected outcome for most inputs
  }
  const std::string once = WriteProblemJson(p);
  Problem q;
  try {
    q = ParseProblem(once, "roundtrip.json");
  } catch (const std::invalid_argument& e) {
    Defect(std::string("a written problem does not read back: ") + e.what());
  }
  if (WriteProblemJson(q) != once) Defect("problem round trip is not stable");
}

void SolveEntries(const std::uint8_t* data, std::size_t size) {
  Numbers in(data, size);
  const double lambda = in.Mixed(0.05, 10.0);
  const AngleState angles{in.Mixed(-4.0, 4.0), in.Mixed(-4.0, 4.0), in.Mixed(-4.0, 4.0)};
  const double mu = in.Mixed(0.01, 10.0);
  const Eigen::Vector2d target(in.Mixed(-0.2, 0.2), in.Mixed(-0.2, 0.2));
  const double delta_psi = in.Mixed(-7.0, 7.0);
  const double factor = in.Mixed(0.1, 3.0);
  const double t = in.Mixed(-50.0, 50.0);
  const double radius = in.Mixed(0.1, 3.0);
  const double n_raw = std::fmod(in.Mixed(0.0, 6.0), 6.0);  // NaN for a non-finite input
  const int n = 2 + (std::isfinite(n_raw) ? static_cast<int>(std::abs(n_raw)) : 0);

  BallModel model = BallModel::FromLambda(1.0);
  try {
    model = BallModel::FromLambda(lambda);
  } catch (const std::invalid_argument&) {
    return;
  }
  try {
    const BallState s = StateFromAngles(angles, mu, model);
    RequireFiniteResult("state.z", s.z);
    RequireFiniteResult("state.omega", s.omega);
    const AngleState back = AnglesFromState(s, model);
    RequireFiniteResult("angles.theta", back.theta);
    RequireFiniteResult("angles.psi", back.psi);
  } catch (const std::invalid_argument&) {
  }
  try {
    const Impulse a = EnergyPreservingImpulse(angles, mu, delta_psi, model);
    RequireFiniteResult("impulse.delta_omega", a.delta_omega);
    const Impulse b = EnergyChangingImpulse(angles, mu, factor, model);
    RequireFiniteResult("impulse.mu_after", b.mu_after);
  } catch (const std::invalid_argument&) {
  }
  try {
    const FreeMotion m = FreeMotion::FromAngles(model, angles, mu);
    const MotionSample s = m.At(t);
    RequireFiniteResult("sample.x", s.x);
    RequireFiniteResult("sample.A", s.A);
    RequireFiniteResult("sample.energy", s.energy);
  } catch (const std::invalid_argument&) {
  } catch (const std::runtime_error&) {  // a reported integration failure (step bound)
  }
  try {
    const JoinSummary j = Join(JoinProblem{model, angles, mu, Eigen::Vector2d::Zero(), target});
    if (j.IsSolutionUsable()) {
      RequireFiniteResult("join.t", j.t);
      RequireFiniteResult("join.delta_psi", j.delta_psi);
      RequireFiniteResult("join.x_after", j.x_after);
      if (j.residual > 1e-9) Defect("join reported converged with residual " + std::to_string(j.residual));
    }
  } catch (const std::invalid_argument&) {
  }
  try {
    const Path path = PathFromSpec(PathSpec{CircleSpec{Eigen::Vector2d(-radius, 0.0), radius, 0.0, 1.0}});
    std::vector<double> taus;
    for (int k = 0; k <= n; ++k) taus.push_back(static_cast<double>(k) / n);
    const PlanSummary plan =
        PlanImpulses(PlanProblem{model, angles, mu, Eigen::Matrix3d::Identity(), path, {ExplicitTaus{taus}}, {}});
    if (plan.IsSolutionUsable()) {
      RequireFiniteResult("plan.measured_error", plan.measured_error);
      RequireFiniteResult("plan.A_impulsive", plan.A_impulsive);
    }
  } catch (const std::invalid_argument&) {
  }
}

void ReachEntry(const std::uint8_t* data, std::size_t size) {
  Numbers in(data, size);
  ReachProblem p;
  ReachOptions o;  // small scan sizes: milliseconds per input
  o.scan_directions = o.scan_steps_per_period = 16, o.max_candidates = 4, o.max_refine_iterations = 10;
  o.global_max_evaluations = 20;
  try {
    p.model = BallModel::FromLambda(in.Mixed(0.05, 10.0));
    p.start = {in.Mixed(-4.0, 4.0), in.Mixed(-4.0, 4.0), in.Mixed(-4.0, 4.0)};
    p.mu = in.Mixed(0.1, 10.0);
    p.x0 = {in.Mixed(-5.0, 5.0), in.Mixed(-5.0, 5.0)};
    p.target = {in.Mixed(-5.0, 5.0), in.Mixed(-5.0, 5.0)};
    o.horizon_periods = in.Mixed(0.0, 3.0);
    o.tolerance = in.Mixed(1e-12, 1e-6);
    const ReachSummary s = Reach(p, o);
    for (const ReachSolution& r : s.solutions) {
      RequireFiniteResult("reach.t", r.t);
      RequireFiniteResult("reach.delta_psi", r.delta_psi);
      if (!(r.residual <= 10.0 * o.tolerance)) Defect("reach solution with residual " + std::to_string(r.residual));
    }
  } catch (const std::invalid_argument&) {
  }
}

void IsoparallelEntry(const std::uint8_t* data, std::size_t size) {
  Numbers in(data, size);
  IsoparallelProblem p;
  IsoparallelOptions o;  // few starts: milliseconds per input
  o.starts = 8, o.max_iterations = 20;
  try {
    p.start = {in.Mixed(-5.0, 5.0), in.Mixed(-5.0, 5.0)};
    p.goal = p.start + Eigen::Vector2d(in.Mixed(-6.0, 6.0), in.Mixed(-6.0, 6.0));
    p.start_orientation = ExpSO3(Eigen::Vector3d(in.Mixed(-1.0, 1.0), in.Mixed(-1.0, 1.0), in.Mixed(-1.0, 1.0)));
    p.goal_orientation = ExpSO3(Eigen::Vector3d(in.Mixed(-1.0, 1.0), in.Mixed(-1.0, 1.0), in.Mixed(-1.0, 1.0)));
    o.length_cap_factor = in.Mixed(1.0, 3.0);
    o.enumerate_families = in.Next() > 0;
    if (in.Next() > 0) p.goal_orientation = p.start_orientation;  // identity targets: the family search
    const IsoparallelSummary s = SolveIsoparallel(p, o);
    for (const IsoparallelSolution& r : s.solutions) {
      RequireFiniteResult("isoparallel.length", r.length);
      RequireFiniteResult("isoparallel.endpoint_error", r.endpoint_error);
      RequireFiniteResult("isoparallel.orientation_error", r.orientation_error);
    }
  } catch (const std::invalid_argument&) {
  }
}

namespace {

// Caps of the steer entry: small enough that one input (under ASan + UBSan) takes milliseconds to
// a few tenths of a second, large enough that the solvers converge on the seeds.
constexpr int kSteerMaxImpulses = 6;
constexpr int kSteerMaxIterations = 6;
constexpr int kSteerMaxStarts = 3;
constexpr long kSteerMaxSteps = 100'000;

void CapIntegration(IntegrationOptions* o) { o->max_steps = std::min(o->max_steps, kSteerMaxSteps); }

void RequireFiniteImpulses(const std::vector<ExactImpulse>& impulses) {
  for (const ExactImpulse& k : impulses) {
    RequireFiniteResult("steer impulse t", k.t_impulse);
    RequireFiniteResult("steer impulse position", k.position);
    RequireFiniteResult("steer impulse delta_psi", k.delta_psi);
    RequireFiniteResult("steer impulse duration", k.duration);
    RequireFiniteResult("steer impulse delta_omega", k.delta_omega);
    RequireFiniteResult("steer impulse mu_after", k.mu_after);
  }
}

void SteerExact(const Problem& p) {
  ExactArrivalSetup setup;
  IsoparallelSummary solved;
  if (p.plan || !p.isoparallel) {
    setup = ExactArrivalSetupFor(p);
  } else {
    IsoparallelSetup iso = IsoparallelSetupFor(p);
    iso.options.starts = std::min(iso.options.starts, 8);
    iso.options.max_iterations = std::min(iso.options.max_iterations, 20);
    solved = SolveIsoparallel(iso.problem, iso.options);
    if (!solved.IsSolutionUsable()) return;
    const ReferenceChoice choice =
        p.rig.Empty() ? ReferenceChoice{} : ChooseIsoparallelReference(solved, p.rig, solved.Shortest().start);
    setup = ExactArrivalSetupFor(p, solved.solutions.at(choice.index));
  }
  setup.problem.impulses = std::min(setup.problem.impulses, kSteerMaxImpulses);
  setup.options.max_iterations = std::min(setup.options.max_iterations, kSteerMaxIterations);
  setup.options.warm_start.integration.max_steps =
      std::min(setup.options.warm_start.integration.max_steps, kSteerMaxSteps);
  CapIntegration(&setup.options.integration);
  CapIntegration(&setup.options.jacobian_integration);
  const ExactArrivalSummary s = SolveExactArrival(setup.problem, setup.options);
  if (!s.IsSolutionUsable()) return;
  RequireFiniteImpulses(s.impulses);
  RequireFiniteResult("steer total_time", s.total_time);
  RequireFiniteResult("steer deviation", s.deviation);
  RequireFiniteResult("steer position_error", s.position_error);
  RequireFiniteResult("steer orientation_error", s.orientation_error);
  const ReplayResult replay = ReplayExactArrival(setup.problem, s.impulses, {1e-12, 1e-12, kSteerMaxSteps});
  RequireFiniteResult("steer replay position_error", replay.position_error);
  if (!setup.problem.limits.Empty()) CheckRigLimits(setup.problem, s, {}, 8);
}

void SteerFewest(const Problem& p) {
  FewestImpulsesSetup setup = FewestImpulsesSetupFor(p);
  FewestImpulsesOptions& o = setup.options;
  o.max_impulses = std::min(o.max_impulses, kSteerMaxImpulses / 2);
  o.pareto_counts = std::min(o.pareto_counts, 2);
  o.starts = std::min(o.starts, kSteerMaxStarts);
  o.adaptive_starts = std::min(o.adaptive_starts, kSteerMaxStarts);
  o.arrivals_per_count = 1;
  o.max_iterations = std::min(o.max_iterations, kSteerMaxIterations);
  CapIntegration(&o.integration);
  CapIntegration(&o.search_integration);
  const FewestImpulsesSummary s = SolveFewestImpulses(setup.problem, o);
  if (!s.IsSolutionUsable()) return;
  RequireFiniteResult("fewest max_total_time", s.max_total_time);
  for (const FewestImpulsesCount& c : s.counts) {
    if (!c.reached) continue;
    RequireFiniteImpulses(c.plan);
    RequireFiniteResult("fewest total_time", c.total_time);
    RequireFiniteResult("fewest path_length", c.path_length);
    RequireFiniteResult("fewest position_error", c.position_error);
    RequireFiniteResult("fewest orientation_error", c.orientation_error);
  }
}

}  // namespace

void SteerEntry(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const Problem p = ParseProblem(text, "fuzz.json");
    if (!p.steer) return;
    if (p.steer->fewest)
      SteerFewest(p);
    else
      SteerExact(p);
  } catch (const std::invalid_argument&) {
  } catch (const std::runtime_error&) {  // a reported failure (an integration over its step bound)
  }
}

}  // namespace plateball::fuzz
