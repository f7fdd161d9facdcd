// The MuJoCo twin's cost (docs/benchmarks.md): writing the machine's MJCF for a plan, and one replay
// of the circle plan (problems/circle_physical.json, 64 impulses, 12.4 s) at dt = 1e-3 with ideal jumps.
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include "common/json_output.h"
#include "common/plan_json.h"
#include "plateball/impulse_planner.h"
#include "plateball/problem_io.h"
#include "plateball/task_adapters.h"
#include "rig/mujoco_twin.h"
#include "rig/rig_plan.h"

namespace {

using namespace plateball;
using namespace plateball::tools;

// The circle plan's result, written once as `plateball plan` writes it.
const std::string& CircleResult() {
  static const std::string file = [] {
    const std::string problem = std::string(PLATEBALL_SOURCE_DIR) + "/problems/circle_physical.json";
    const Problem p = ReadProblemFile(problem);
    const PlanSetup setup = PlanSetupFor(p);
    const PlanSummary plan = PlanImpulses(setup.problem, setup.options);
    Json doc = HeaderJson("plateball", "plan", p, problem);
    Json initial = InitialJson(p);
    initial["orientation"] = ToJson(plan.A0);
    doc["initial"] = std::move(initial);
    Append(doc, PlanSummaryToJson(plan, true));
    const std::string out = std::string(PLATEBALL_BINARY_DIR) + "/twin_benchmark_circle.json";
    std::ofstream(out) << DumpJson(doc);
    return out;
  }();
  return file;
}

// Reading the result and writing the MJCF (the export without its file writes).
void BM_RigExport(benchmark::State& state) {
  for (auto _ : state) {
    const rig::RigPlan plan = rig::ReadRigPlan(CircleResult());
    benchmark::DoNotOptimize(rig::TwinMjcf(plan.physical, plan.x0, plan.A0, rig::TwinSettings{}));
  }
}
BENCHMARK(BM_RigExport)->Unit(benchmark::kMillisecond);

// One replay: the model's compilation, settling and 12.4 s of RK4 at dt = 1e-3 (12453 steps).
void BM_RigReplayCircle(benchmark::State& state) {
  const rig::RigPlan plan = rig::ReadRigPlan(CircleResult());
  const rig::PlannedTrajectory reference(plan);
  double error = 0.0;
  for (auto _ : state) error = rig::ReplayInTwin(plan, reference, rig::ReplayOptions{}).orientation_error;
  state.counters["orientation_error"] = error;
}
BENCHMARK(BM_RigReplayCircle)->Unit(benchmark::kSecond)->Iterations(3);

}  // namespace

BENCHMARK_MAIN();
