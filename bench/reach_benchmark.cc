// Standard task T3 (docs/benchmarks.md): reach distant points from the paper's
// Figure 8 state, lambda = 2, mu = 1, (theta0, phi0, psi0) = (-pi/3, pi/2, 0) as the paper gives
// it, targets (6, 0), (0, 10), (-12, 5). Each iteration is one complete Reach() call (scan,
// refinement of every solution below 5 periods, end states). Counters: the earliest solution,
// how many distinct solutions with t below 5 periods were found, the solver's residual, and the
// accuracy reached, measured outside the timed loop by a direct integration (no periodicity).
#include <benchmark/benchmark.h>

#include <cmath>
#include <vector>

#include "plateball/free_motion.h"
#include "plateball/reach.h"

namespace {

using namespace plateball;

const Eigen::Vector2d kTargets[] = {{6.0, 0.0}, {0.0, 10.0}, {-12.0, 5.0}};

ReachProblem T3Problem(int k) {
  ReachProblem p;
  p.model = BallModel::FromLambda(2.0);
  p.start = {-M_PI / 3, M_PI / 2, 0.0};
  p.mu = 1.0;
  p.target = kTargets[k];
  return p;
}

double DirectMiss(const ReachProblem& p, const ReachSolution& s) {
  AngleState a = p.start;
  a.psi += s.delta_psi;
  FreeMotionStart start;
  start.state = StateFromAngles(a, p.mu, p.model);
  start.x0 = p.x0;
  start.A0 = FreeMotion::FromAngles(p.model, a, p.mu, p.x0, p.A0).start().A0;
  return (IntegrateFreeMotion(p.model, start, {s.t})[0].x - p.target).norm();
}

void BM_T3ReachTarget(benchmark::State& state) {
  const int k = static_cast<int>(state.range(0));
  const ReachProblem problem = T3Problem(k);
  ReachOptions options;
  options.horizon_periods = 5.0;
  ReachSummary summary;
  for (auto _ : state) {
    summary = Reach(problem, options);
    benchmark::DoNotOptimize(summary.solutions.data());
  }
  state.SetLabel("target (" + std::to_string(static_cast<int>(kTargets[k].x())) + ", " +
                 std::to_string(static_cast<int>(kTargets[k].y())) + "): " + ToString(summary.status));
  state.counters["solutions_below_5_periods"] = static_cast<double>(summary.solutions.size());
  state.counters["tight_evaluations"] = summary.tight_evaluations;
  state.counters["candidates"] = summary.candidates;
  if (summary.IsSolutionUsable()) {
    const ReachSolution& e = summary.Earliest();
    state.counters["earliest_delta_psi"] = e.delta_psi;
    state.counters["earliest_t"] = e.t;
    state.counters["earliest_periods"] = e.periods;
    state.counters["solver_residual"] = e.residual;
    double worst = 0.0;
    for (const ReachSolution& s : summary.solutions) worst = std::max(worst, DirectMiss(problem, s));
    state.counters["direct_miss_max"] = worst;  // accuracy reached (independent integration)
  }
}
BENCHMARK(BM_T3ReachTarget)->DenseRange(0, 2)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
