// T5(a) of docs/benchmarks.md: the Figure 7 goal ((0, 0) -> (3, 3), identity
// reorientation, lambda = 2, mu = 1) reached exactly with 12 impulses along the shortest
// isoparallel path. Timed: SolveExactArrival (warm start by the paper's plan + the constrained
// Gauss-Newton); the isoparallel solve is done once outside the loop. Counters: the arrival
// errors of the independent re-integration (ReplayExactArrival), the deviation D and the largest
// pass-point displacement, the largest distance of the trajectory from the reference (sampled),
// the iterations, the total time and the paper's plan's orientation error.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "plateball/exact_arrival.h"
#include "plateball/fewest_impulses.h"
#include "plateball/free_motion.h"
#include "plateball/impulse.h"
#include "plateball/isoparallel.h"
#include "plateball/isoparallel_plan.h"
#include "plateball/so3.h"
#include "plateball/task_adapters.h"

namespace {

using namespace plateball;

Problem Figure7() {
  Problem p;
  p.name = "figure7";
  p.model = BallModel::FromLambda(2.0);
  p.initial = {0.0, 0.0, 0.0};
  p.mu = 1.0;
  IsoparallelTask t;
  t.goal = {3.0, 3.0};
  t.impulses = 12;
  t.solver.starts = 1024;
  t.solver.tolerance = 1e-12;
  p.isoparallel = t;
  return p;
}

// max over the trajectory (24 samples per arc) of the distance to the reference (2000 samples).
double MaxDistanceFromReference(const ExactArrivalProblem& p, const ExactArrivalSummary& s) {
  std::vector<Eigen::Vector2d> ref;
  for (const SmoothCurve& c : p.reference.pieces())
    for (int i = 0; i <= 2000; ++i) ref.push_back(c.Value(c.Begin() + (c.End() - c.Begin()) * i / 2000.0));
  double worst = 0.0;
  for (const ExactImpulse& e : s.impulses) {
    FreeMotionStart fs;
    fs.state = EnergyPreservingImpulse(e.angles_before, p.mu, e.delta_psi, p.model).state_after;
    fs.x0 = e.position;
    fs.A0 = AlignOrientationToAxis(Eigen::Matrix3d::Identity(), fs.state.z);
    std::vector<double> times;
    for (int i = 0; i <= 24; ++i) times.push_back(e.duration * i / 24.0);
    for (const MotionSample& q : IntegrateFreeMotion(p.model, fs, times)) {
      double d = std::numeric_limits<double>::infinity();
      for (const Eigen::Vector2d& r : ref) d = std::min(d, (q.x - r).norm());
      worst = std::max(worst, d);
    }
  }
  return worst;
}

void BM_T5aExactArrivalFigure7(benchmark::State& state) {
  const Problem file = Figure7();
  const IsoparallelSetup iso = IsoparallelSetupFor(file);
  const IsoparallelSummary solved = SolveIsoparallel(iso.problem, iso.options);
  if (!solved.IsSolutionUsable()) {
    state.SkipWithError("isoparallel solve failed");
    return;
  }
  const ExactArrivalSetup setup = ExactArrivalSetupFor(file, solved.Shortest(), static_cast<int>(state.range(0)));
  ExactArrivalSummary s;
  for (auto _ : state) {
    s = SolveExactArrival(setup.problem, setup.options);
    benchmark::DoNotOptimize(s.impulses.data());
  }
  const ReplayResult replay = ReplayExactArrival(setup.problem, s.impulses);
  state.counters["arrived"] = s.IsSolutionUsable() ? 1 : 0;
  state.counters["position_error"] = replay.position_error;
  state.counters["orientation_error"] = replay.orientation_error;
  state.counters["deviation"] = s.deviation;
  state.counters["max_pass_displacement"] = s.max_pass_displacement;
  state.counters["max_distance_from_path"] = MaxDistanceFromReference(setup.problem, s);
  state.counters["iterations"] = s.iterations;
  state.counters["total_time"] = s.total_time;
  state.counters["paper_orientation_error"] = s.planned_orientation_error;
}
BENCHMARK(BM_T5aExactArrivalFigure7)->Arg(12)->Arg(24)->Unit(benchmark::kMillisecond);

// T5(b): the fewest impulses for the Figure 7 goal (problems/figure7_fewest.json, rolling start,
// stop at the goal) and for the rotation problem's goal (problems/isoparallel_rotation_fewest.json,
// from rest). Timed: SolveFewestImpulses (the whole search with its Pareto rows). Counters: the
// fewest count, its total time and path length, the arrival errors of the independent
// re-integration, the rows of the Pareto table (time_n, length_n) and the rollouts.
// The two problems as in their files (the benchmark does not read files).
FewestImpulsesSetup FewestSetup(bool rotation) {
  FewestImpulsesSetup setup;
  FewestImpulsesProblem& p = setup.problem;
  p.model = BallModel::FromLambda(2.0);
  p.mu = 1.0;
  if (rotation) {
    p.A0 = ExpSO3(Eigen::Vector3d(M_PI / 2, 0.0, 0.0));
    p.initial = InitialAnglesFromOrientation(p.A0, 0.0);
    p.x1 = {2.0, 1.0};
    p.A1 = Eigen::Quaterniond(0.409347959705932, 0.757852860408873, 0.435631125878677, -0.261378675527206)
               .normalized()
               .toRotationMatrix();
    p.start_at_rest = true;
  } else {
    p.initial = {0.0, 0.0, 0.0};
    p.x1 = {3.0, 3.0};
    p.stop_at_goal = true;
  }
  setup.options.starts = 16;
  return setup;
}

void BM_T5bFewestImpulses(benchmark::State& state, bool rotation) {
  const FewestImpulsesSetup setup = FewestSetup(rotation);
  FewestImpulsesSummary s;
  for (auto _ : state) {
    s = SolveFewestImpulses(setup.problem, setup.options);
    benchmark::DoNotOptimize(s.counts.data());
  }
  const FewestImpulsesCount* f = s.Fewest();
  if (!f) {
    state.SkipWithError(s.BriefReport().c_str());
    return;
  }
  const ReplayResult replay = ReplayExactArrival(ReplayProblemFor(setup.problem, f->impulses), f->plan);
  state.counters["fewest"] = s.fewest;
  state.counters["total_time"] = f->total_time;
  state.counters["path_length"] = f->path_length;
  state.counters["position_error"] = replay.position_error;
  state.counters["orientation_error"] = replay.orientation_error;
  state.counters["rollouts"] = s.rollouts;
  for (const FewestImpulsesCount& c : s.counts) {
    if (!c.reached) continue;
    state.counters["time_" + std::to_string(c.impulses)] = c.total_time;
    state.counters["length_" + std::to_string(c.impulses)] = c.path_length;
  }
}
BENCHMARK_CAPTURE(BM_T5bFewestImpulses, figure7, false)->Unit(benchmark::kMillisecond);
BENCHMARK_CAPTURE(BM_T5bFewestImpulses, rotation, true)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
