// T11 of docs/benchmarks.md: constrained exact arrival on a finite plate. The Figure 7 goal
// (problems/figure7_rig.json: (0, 0) -> (3, 3), identity reorientation, lambda = 2, mu = 1, n = 12
// along the shortest isoparallel path) on a disk plate of radius 3 about (1.5, 1.5), which cuts the
// free optimum, with one disk obstacle of radius 0.25 on the free optimum's path and a clearance of
// 0.05. Timed: SolveExactArrival (the free optimum, then SLSQP under the limits); the isoparallel
// solve is done once outside the loop. Counters: the replayed arrival errors, the independent check
// (passed, the smallest plate and obstacle margins), the deviation, the SLSQP evaluations.
//
// T12: the constrained fewest-impulse search on the same goal (problems/figure7_fewest_rig.json:
// rolling, stop at the goal) with the same disk plate, which cuts the free fewest answer (two
// straight rolls reaching 5.9 from the plate's centre), and one disk obstacle. Timed:
// SolveFewestImpulses. Counters: the fewest count within the limits, its total time, its
// independent check, the constrained solves and their SLSQP evaluations.
//
// T13: the path-following plan honouring a rig (PlanImpulsesOnRig) on T2's circle, 64 impulses:
// tests/data/plan_rig_blocked.json (an obstacle of radius 1.998 inside the flights' inward bow:
// the partition is refined) and tests/data/plan_rig_tick.json (the same with a 1 kHz tick: the
// partition points slide onto the grid). Timed: PlanImpulsesOnRig, its final independent check
// included. Counters: the final segments, points added and slid, rounds, the check and its
// obstacle margin, the largest miss of a partition point.
#include <benchmark/benchmark.h>

#include <string>

#include "plateball/exact_arrival.h"
#include "plateball/fewest_impulses.h"
#include "plateball/isoparallel.h"
#include "plateball/problem_io.h"
#include "plateball/rig_planner.h"
#include "plateball/task_adapters.h"

namespace {

using namespace plateball;

void BM_T11ConstrainedSteerFigure7(benchmark::State& state) {
  const Problem file = ReadProblemFile(std::string(PLATEBALL_SOURCE_DIR) + "/problems/figure7_rig.json");
  const IsoparallelSetup iso = IsoparallelSetupFor(file);
  const IsoparallelSummary solved = SolveIsoparallel(iso.problem, iso.options);
  if (!solved.IsSolutionUsable()) {
    state.SkipWithError("isoparallel solve failed");
    return;
  }
  const ExactArrivalSetup setup = ExactArrivalSetupFor(file, solved.Shortest());
  ExactArrivalSummary s;
  for (auto _ : state) {
    s = SolveExactArrival(setup.problem, setup.options);
    benchmark::DoNotOptimize(s.impulses.data());
  }
  const ReplayResult replay = ReplayExactArrival(setup.problem, s.impulses);
  const RigCheck check = CheckRigLimits(setup.problem, s);
  state.counters["arrived"] = s.IsSolutionUsable() ? 1 : 0;
  state.counters["position_error"] = replay.position_error;
  state.counters["orientation_error"] = replay.orientation_error;
  state.counters["check_passed"] = check.passed ? 1 : 0;
  state.counters["plate_margin"] = check.margins.count("plate") ? check.margins.at("plate") : 0.0;
  state.counters["obstacle_margin"] = check.margins.count("obstacles[0]") ? check.margins.at("obstacles[0]") : 0.0;
  state.counters["deviation"] = s.deviation;
  state.counters["evaluations"] = s.limits.evaluations;
}
BENCHMARK(BM_T11ConstrainedSteerFigure7)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();

void BM_T12ConstrainedFewestFigure7(benchmark::State& state) {
  const Problem file = ReadProblemFile(std::string(PLATEBALL_SOURCE_DIR) + "/problems/figure7_fewest_rig.json");
  const FewestImpulsesSetup setup = FewestImpulsesSetupFor(file);
  FewestImpulsesSummary s;
  for (auto _ : state) {
    s = SolveFewestImpulses(setup.problem, setup.options);
    benchmark::DoNotOptimize(s.counts.data());
  }
  const FewestImpulsesCount* f = s.Fewest();
  state.counters["found"] = s.IsSolutionUsable() ? 1 : 0;
  state.counters["fewest"] = s.fewest;
  state.counters["total_time"] = f ? f->total_time : 0.0;
  state.counters["check_passed"] = f && f->check && f->check->passed ? 1 : 0;
  if (f) {
    const ReplayResult replay = ReplayExactArrival(ReplayProblemFor(setup.problem, f->impulses), f->plan);
    state.counters["position_error"] = replay.position_error;
    state.counters["orientation_error"] = replay.orientation_error;
  }
  state.counters["constrained_solves"] = s.constrained_solves;
  state.counters["evaluations"] = s.evaluations;
  state.counters["rollouts"] = s.rollouts;
}
BENCHMARK(BM_T12ConstrainedFewestFigure7)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();

void BM_T13PlanOnRig(benchmark::State& state) {
  const char* files[] = {"/tests/data/plan_rig_blocked.json", "/tests/data/plan_rig_tick.json"};
  const Problem file = ReadProblemFile(std::string(PLATEBALL_SOURCE_DIR) + files[state.range(0)]);
  const PlanSetup setup = PlanSetupFor(file);
  RigPlanSummary s;
  for (auto _ : state) {
    s = PlanImpulsesOnRig(setup.problem, file.rig, file.physical, setup.options);
    benchmark::DoNotOptimize(s.plan.steps.data());
  }
  state.counters["ok"] = s.IsSolutionUsable() ? 1 : 0;
  state.counters["segments"] = s.plan.segments;
  state.counters["points_added"] = s.points_added;
  state.counters["points_slid"] = s.points_slid;
  state.counters["rounds"] = s.rounds;
  state.counters["check_passed"] = s.check.passed ? 1 : 0;
  state.counters["obstacle_margin"] = s.check.margins.count("obstacles[0]") ? s.check.margins.at("obstacles[0]") : 0.0;
  state.counters["max_pass_miss"] = s.plan.max_pass_miss;
}
BENCHMARK(BM_T13PlanOnRig)->DenseRange(0, 1)->Unit(benchmark::kMillisecond)->MeasureProcessCPUTime()->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
