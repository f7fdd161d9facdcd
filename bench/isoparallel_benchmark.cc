// T4 of the standard benchmarks (docs/benchmarks.md): the isoparallel problem of
// Figure 7, from (0, 0) to (3, 3) with final reorientation equal to the identity.
// Figures (counters): the length of the shortest path found, the number of distinct solutions
// (all up to 3x the shortest), the final orientation residual of the shortest one (verified by
// VerifyRolling, Runge-Kutta-Fehlberg 7(8) at 1e-13, independent of the solver) and the wall time of the
// whole solve (the benchmark's time), with the seed and the number of starts stated.
// Tolerances: shooting residual 1e-12 (options.tolerance).
// The identity target is solved by the family enumeration (isoparallel_families.h: complete up
// to 3x, certified); BM_T4...Shooting runs the multi-start shooting on the same problem for
// comparison (its solution count grows with the number of starts). BM_ConjugateTimesFigure7:
// the first conjugate time of each of the 47 solutions (src/isoparallel_conjugate.h).
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <cmath>

#include "isoparallel_conjugate.h"
#include "plateball/isoparallel.h"
#include "plateball/so3.h"

namespace {

using namespace plateball;

void Report(benchmark::State& state, const IsoparallelOptions& options, const IsoparallelSummary& summary) {
  state.counters["starts"] = options.enumerate_families ? 0 : options.starts;
  state.counters["seed"] = static_cast<double>(options.seed);
  state.counters["threads"] = options.threads;
  state.counters["solutions"] = static_cast<double>(summary.solutions.size());
  state.counters["complete"] = summary.complete ? 1 : 0;
  state.counters["periods_searched"] = summary.periods_searched;
  state.counters["local_solves"] = summary.local_solves;
  if (summary.IsSolutionUsable()) {
    state.counters["shortest_length"] = summary.Shortest().length;
    state.counters["shortest_residual"] = summary.Shortest().orientation_residual;
    state.counters["shortest_family"] = summary.Shortest().family ? 1 : 0;
    double worst = 0.0;
    for (const auto& s : summary.solutions) worst = std::max(worst, s.orientation_residual);
    state.counters["worst_residual"] = worst;
  }
}

IsoparallelProblem Figure7() {
  IsoparallelProblem problem;
  problem.goal = {3.0, 3.0};
  return problem;
}

void BM_T4IsoparallelFigure7(benchmark::State& state) {
  IsoparallelOptions options;
  options.seed = 1;
  options.threads = static_cast<int>(state.range(0));
  IsoparallelSummary summary;
  for (auto _ : state) {
    summary = SolveIsoparallel(Figure7(), options);
    benchmark::DoNotOptimize(summary.solutions.data());
  }
  Report(state, options, summary);
}

void BM_T4IsoparallelFigure7Shooting(benchmark::State& state) {
  IsoparallelOptions options;
  options.enumerate_families = false;
  options.starts = static_cast<int>(state.range(0));
  options.seed = 1;
  IsoparallelSummary summary;
  for (auto _ : state) {
    summary = SolveIsoparallel(Figure7(), options);
    benchmark::DoNotOptimize(summary.solutions.data());
  }
  Report(state, options, summary);
}

// T4b: the problem of problems/isoparallel_rotation.json as in the file (the benchmark does not
// read files): (0, 0) to (2, 1), start orientation a quarter turn about e1, the goal orientation's
// quaternion; the default options (4096 deterministic shapes, each with its (phase, length)
// plane scanned, for a target other than the identity).
void BM_T4bIsoparallelRotation(benchmark::State& state) {
  IsoparallelProblem problem;
  problem.goal = {2.0, 1.0};
  problem.start_orientation = ExpSO3(Eigen::Vector3d(M_PI / 2, 0.0, 0.0));
  problem.goal_orientation =
      Eigen::Quaterniond(0.409347959705932, 0.757852860408873, 0.435631125878677, -0.261378675527206)
          .normalized()
          .toRotationMatrix();
  IsoparallelOptions options;
  options.threads = 1;
  IsoparallelSummary summary;
  for (auto _ : state) {
    summary = SolveIsoparallel(problem, options);
    benchmark::DoNotOptimize(summary.solutions.data());
  }
  Report(state, options, summary);
  state.counters["starts"] = options.starts;  // shapes of the two-stage search, not the enumeration
  state.counters["seed"] = 0;                 // not used for this target
}

// The first conjugate times of Figure 7's 47 solutions (the solve is set up once, untimed).
// Counters: the solutions, how many are locally optimal, the largest relative distance
// |conjugate time - length| / length among those (a family's end is conjugate: ~0).
void BM_ConjugateTimesFigure7(benchmark::State& state) {
  const IsoparallelSummary summary = SolveIsoparallel(Figure7());
  int local = 0;
  double end_gap = 0.0;
  for (auto _ : state) {
    local = 0;
    end_gap = 0.0;
    for (const IsoparallelSolution& s : summary.solutions) {
      const internal::ConjugateTime c = internal::FirstConjugateTime(internal::ConjugateProblem::kPlateBall,
                                                                     internal::ExtremalDataOf(s.parameters),
                                                                     kConjugateSearchFactor * s.length);
      if (c.found && c.time >= s.length * (1 - kConjugateEndTolerance)) {
        ++local;
        end_gap = std::max(end_gap, std::abs(c.time - s.length) / s.length);
      }
      benchmark::DoNotOptimize(c.time);
    }
  }
  state.counters["solutions"] = static_cast<double>(summary.solutions.size());
  state.counters["locally_optimal"] = local;
  state.counters["end_gap"] = end_gap;
}

}  // namespace

BENCHMARK(BM_ConjugateTimesFigure7)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();

BENCHMARK(BM_T4bIsoparallelRotation)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();

BENCHMARK(BM_T4IsoparallelFigure7)
    ->ArgNames({"threads"})
    ->Arg(1)
    ->Arg(2)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

BENCHMARK(BM_T4IsoparallelFigure7Shooting)
    ->ArgNames({"starts"})
    ->Arg(64)
    ->Arg(256)
    ->Unit(benchmark::kMillisecond)
    ->MeasureProcessCPUTime()
    ->UseRealTime();

BENCHMARK_MAIN();
