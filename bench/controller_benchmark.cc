// T10 of docs/benchmarks.md: the controller's Update in a real-time loop. The circle of T2 with
// n = 32 (problems/circle.json), driven in a closed loop by the simulated rig (src/simulated_rig.h)
// under impulse magnitude and direction errors of 2%, a lambda error of 2%, an energy loss of 0.1%
// per impulse and measurement noise of 1e-4 per tick (contact point, orientation, angular
// velocity), at a tick of T / 95000 (T = 16.4, the plan's duration: 1.7e-4 s): 10^5 Updates, the
// whole lap (32 impulses, with feedback_exact 10 exact re-plans) and 5000 ticks after it. Each
// Update is timed with steady_clock; the counters are the p50, p99 and max of those times (us),
// the impulses, the exact re-plans, the ticks that exhausted the budget (50 ms) and the largest
// distance of the controller's estimate from the true contact point.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <vector>

#include "plateball/controller.h"
#include "plateball/problem_io.h"
#include "plateball/task_adapters.h"
#include "simulated_rig.h"

namespace {

using namespace plateball;

constexpr long kTicks = 100000;

std::shared_ptr<const NominalPlan> Circle() {
  static std::shared_ptr<const NominalPlan> plan;
  if (!plan) {
    const Problem problem = ReadProblemFile(std::string(PLATEBALL_SOURCE_DIR) + "/problems/circle.json");
    const PlanSetup setup = PlanSetupFor(problem, 32);
    plan = std::make_shared<NominalPlan>(MakeNominalPlan(setup.problem, setup.options));
  }
  return plan;
}

double Quantile(std::vector<double> v, double q) {
  const std::size_t i = static_cast<std::size_t>(q * static_cast<double>(v.size() - 1));
  std::nth_element(v.begin(), v.begin() + static_cast<long>(i), v.end());
  return v[i];
}

void BM_T10ControllerUpdate(benchmark::State& state) {
  const auto strategy = static_cast<ExecutionStrategy>(state.range(0));
  ErrorModel errors;
  errors.impulse_magnitude = 0.02;
  errors.impulse_angle = 0.02;
  errors.lambda = 0.02;
  errors.energy_loss = 0.001;
  const double tick_period = Circle()->plan.total_time / 95000.0;
  ControllerOptions options;
  options.tick_period = tick_period;
  options.strategy = strategy;
  options.time_budget = 0.05;
  std::vector<double> times(kTicks);
  int impulses = 0, exhausted = 0, exact = 0;
  double gap = 0.0;
  for (auto _ : state) {
    state.PauseTiming();
    Controller controller(Circle(), options);
    internal::SimulatedRig rig(*Circle(), errors, 1, 0, 1e-4);
    impulses = exhausted = exact = 0;
    gap = 0.0;
    state.ResumeTiming();
    for (long tick = 0; tick < kTicks; ++tick) {
      const ControllerMeasurement m = rig.Measure(tick);
      const auto t0 = std::chrono::steady_clock::now();
      const ControllerOutput& out = controller.Update(static_cast<double>(tick) * tick_period, m);
      times[static_cast<std::size_t>(tick)] =
          std::chrono::duration<double, std::micro>(std::chrono::steady_clock::now() - t0).count();
      if (out.impulse) {
        rig.Impulse(out.impulse_index, out.delta_omega);
        ++impulses;
      }
      if (out.budget_exhausted) ++exhausted;
      if (out.exact_replan) ++exact;
      gap = std::max(gap, (rig.x() - out.now.x).norm());
      rig.Roll(tick_period);
    }
  }
  state.counters["p50_us"] = Quantile(times, 0.5);
  state.counters["p99_us"] = Quantile(times, 0.99);
  state.counters["max_us"] = *std::max_element(times.begin(), times.end());
  state.counters["impulses"] = impulses;
  state.counters["budget_exhausted"] = exhausted;
  state.counters["exact_replans"] = exact;
  state.counters["estimate_gap"] = gap;
}
BENCHMARK(BM_T10ControllerUpdate)
    ->Arg(static_cast<int>(ExecutionStrategy::kFeedback))
    ->Arg(static_cast<int>(ExecutionStrategy::kFeedbackExact))
    ->Iterations(1)
    ->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
