// T2 of docs/benchmarks.md: follow the circle p(tau) = (2 cos tau - 2, 2 sin tau),
// tau in [0, 2 pi], from (theta, phi, psi) = (pi/3, 0.4, 0.1), lambda = 2, mu = 1, A0 = I, with
// uniform partitions n = 16 ... 1024. Per n: wall time of the whole plan (joins, arcs with
// orientation, rolling reference, polyline, bounds), the final error ||A_ref(2 pi) - A_n||, the
// reported bound. BM_T2Slopes: the fitted log-log slopes of error and time against n.
#include <benchmark/benchmark.h>

#include <cmath>

#include "plateball/convergence.h"
#include "plateball/impulse_planner.h"
#include "plateball/partition.h"
#include "plateball/task_adapters.h"

namespace {

using namespace plateball;

Problem T2Problem() {
  Problem p;
  p.model = BallModel::FromLambda(2.0);
  p.initial = {M_PI / 3, 0.4, 0.1};
  p.mu = 1.0;
  p.x0 = {0, 0};
  p.plan = PlanTask{};
  p.plan->path = PathSpec{CircleSpec{{-2, 0}, 2, 0, 2 * M_PI}};
  return p;
}

void BM_T2Plan(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const BallModel model = BallModel::FromLambda(2.0);
  const Path path({SmoothCurve::Circle({-2, 0}, 2, 0, 2 * M_PI)});
  const PlanProblem problem{
      model, {M_PI / 3, 0.4, 0.1}, 1.0, Eigen::Matrix3d::Identity(), path, {UniformParameter{n}}, {}};
  PlanSummary plan;
  for (auto _ : state) {
    plan = PlanImpulses(problem);
    benchmark::DoNotOptimize(plan.steps.data());
  }
  state.counters["orientation_error"] = plan.measured_error;
  state.counters["bound"] = plan.bounds.a_posteriori;
  state.counters["theorem_2_6"] = plan.bounds.theorem_2_6;
  state.counters["polyline_error"] = plan.polyline_error;
  state.counters["max_pass_miss"] = plan.max_pass_miss;
  state.counters["ok"] = plan.IsSolutionUsable() ? 1 : 0;
}
BENCHMARK(BM_T2Plan)->RangeMultiplier(2)->Range(16, 1024)->Unit(benchmark::kMillisecond);

void BM_T2Slopes(benchmark::State& state) {
  const ConvergenceSetup setup = ConvergenceSetupFor(T2Problem(), {16, 32, 64, 128, 256, 512, 1024}, "ns", true);
  ConvergenceStudy study;
  for (auto _ : state) {
    study = RunConvergenceStudy(setup.problem, setup.options);
    benchmark::DoNotOptimize(study.rows.data());
  }
  state.counters["slope"] = study.error_slope.value_or(NAN);
  state.counters["bound_slope"] = study.bound_slope.value_or(NAN);
  state.counters["time_slope"] = study.time_slope.value_or(NAN);
  state.counters["bound_holds"] = study.bound_holds ? 1 : 0;
}
BENCHMARK(BM_T2Slopes)->Unit(benchmark::kMillisecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
