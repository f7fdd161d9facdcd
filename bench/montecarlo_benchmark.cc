// T6 of docs/benchmarks.md: T2's circle with n = 64 executed 10,000 times with the
// feedback strategy (re-join to the next pass point after each impulse) under a seeded relative
// error of 1e-3 in the magnitude of every plate velocity change, and the same with open loop.
//   BM_T6Trial/feedback, /open_loop: one trial (Execute) per iteration: the time per trial.
//   BM_T6Study/threads:1, /threads:2: the whole study (RunMonteCarlo, 10,000 trials per strategy)
//     once; counters: seconds per trial and the median / 95th percentile / maximum of the final
//     orientation error (rad, against rolling exactly along the circle) for both strategies.
// The speed-up with 2 processes is measured with the tool: mpirun -np 2 plateball montecarlo
// (README, "Execution under errors").
#include <benchmark/benchmark.h>

#include <cmath>
#include <memory>

#include "plateball/execution.h"
#include "plateball/monte_carlo.h"

namespace {

using namespace plateball;

PlanProblem T2Circle() {
  PlanProblem p;
  p.model = BallModel::FromLambda(2.0);
  p.initial = {M_PI / 3, 0.4, 0.1};
  p.mu = 1.0;
  p.path = Path({SmoothCurve::Circle({-2.0, 0.0}, 2.0, 0.0, 2 * M_PI)});
  p.partition = {UniformParameter{64}};
  return p;
}

ErrorModel T6Errors() {
  ErrorModel e;
  e.impulse_magnitude = 1e-3;
  return e;
}

void BM_T6Trial(benchmark::State& state) {
  ExecutionProblem p;
  p.nominal = std::make_shared<NominalPlan>(MakeNominalPlan(T2Circle()));
  p.strategy = state.range(0) == 0 ? ExecutionStrategy::kFeedback : ExecutionStrategy::kOpenLoop;
  p.errors = T6Errors();
  double worst = 0;
  for (auto _ : state) {
    const ExecutionSummary s = Execute(p);
    worst = std::max(worst, s.orientation_error);
    benchmark::DoNotOptimize(s.position_error);
    ++p.trial;
  }
  state.SetLabel(ToString(p.strategy));
  state.counters["max_orientation_error"] = worst;
}
BENCHMARK(BM_T6Trial)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);

void BM_T6Study(benchmark::State& state) {
  MonteCarloProblem p;
  p.plan = T2Circle();
  p.strategies = {ExecutionStrategy::kFeedback, ExecutionStrategy::kOpenLoop};
  p.scenarios = {{"impulse_magnitude=1e-3", T6Errors()}};
  p.trials = 10'000;
  MonteCarloOptions o;
  o.threads = static_cast<int>(state.range(0));
  o.keep_trials = false;
  MonteCarloSummary s;
  for (auto _ : state) s = RunMonteCarlo(p, o);
  const MonteCarloCell& fb = s.cells.at(0);
  const MonteCarloCell& ol = s.cells.at(1);
  state.counters["us_per_trial"] = benchmark::Counter(
      2.0 * p.trials * 1e-6, benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  // A cell where no trial completed has no distribution: NaN counters say so.
  const Distribution none{NAN, NAN, NAN, NAN};
  const Distribution fo = fb.orientation_error.value_or(none), fp = fb.position_error.value_or(none);
  const Distribution oo = ol.orientation_error.value_or(none), op = ol.position_error.value_or(none);
  state.counters["feedback_median"] = fo.median;
  state.counters["feedback_p95"] = fo.p95;
  state.counters["feedback_max"] = fo.max;
  state.counters["feedback_pos_median"] = fp.median;
  state.counters["open_loop_median"] = oo.median;
  state.counters["open_loop_p95"] = oo.p95;
  state.counters["open_loop_max"] = oo.max;
  state.counters["open_loop_pos_median"] = op.median;
  state.counters["failed"] = static_cast<double>(s.failed_trials);
}
BENCHMARK(BM_T6Study)->ArgName("threads")->Arg(1)->Arg(2)->Iterations(1)->UseRealTime()->Unit(benchmark::kSecond);

}  // namespace

BENCHMARK_MAIN();
