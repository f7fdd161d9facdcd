// Finite pulses (docs/rig.md): T2's circle with n = 64 executed open loop once with ideal impulses and
// with centred constant-force pulses of duration f x (shortest flight), f = 0.05, 0.2 (Arg: f in %).
//   BM_CirclePulses/0: ideal impulses (the reference); /5, /20: centred pulses.
// Counters: deviation of the final contact point (radii) and orientation (rad) from the ideal run,
// and the pulse duration; the time is one Execute.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "plateball/execution.h"
#include "plateball/so3.h"

namespace {

using namespace plateball;

std::shared_ptr<const NominalPlan> Circle() {
  PlanProblem p;
  p.model = BallModel::FromLambda(2.0);
  p.initial = {M_PI / 3, 0.4, 0.1};
  p.mu = 1.0;
  p.path = Path({SmoothCurve::Circle({-2.0, 0.0}, 2.0, 0.0, 2 * M_PI)});
  p.partition = {UniformParameter{64}};
  static const auto plan = std::make_shared<NominalPlan>(MakeNominalPlan(p));
  return plan;
}

ExecutionSummary Run(double pulse_duration) {
  ExecutionProblem p;
  p.nominal = Circle();
  p.strategy = ExecutionStrategy::kOpenLoop;
  p.errors.pulse_duration = pulse_duration;
  return Execute(p);
}

void BM_CirclePulses(benchmark::State& state) {
  double shortest = Circle()->plan.total_time;
  for (const PlanStep& s : Circle()->plan.steps) shortest = std::min(shortest, s.duration);
  const double duration = 0.01 * static_cast<double>(state.range(0)) * shortest;
  const ExecutionSummary ideal = Run(0.0);
  ExecutionSummary run;
  for (auto _ : state) {
    run = Run(duration);
    benchmark::DoNotOptimize(run.x_final);
  }
  state.counters["pulse_duration"] = duration;
  state.counters["position_deviation"] = (run.x_final - ideal.x_final).norm();
  state.counters["orientation_deviation"] = RotationAngle(run.A_final, ideal.A_final);
}
BENCHMARK(BM_CirclePulses)->Arg(0)->Arg(5)->Arg(20)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
