// T1 of docs/benchmarks.md: join two close points (Lemma 2.1).
// lambda = 2, mu = 1, (theta, phi, psi) = (pi/3, 0.4, 0.1) at x0 = 0, 64 targets at distance 0.05.
// Reports the time per join (the benchmark's own statistics give the median over repetitions),
// how many joins succeed and the largest miss |x(t) - target| measured by an independent
// integration (IntegrateFreeMotion).
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

#include "plateball/free_motion.h"
#include "plateball/join.h"

namespace {

using namespace plateball;

std::vector<Eigen::Vector2d> T1Targets() {
  std::vector<Eigen::Vector2d> t;
  for (int k = 0; k < 64; ++k) {
    const double b = 2 * M_PI * k / 64;
    t.emplace_back(0.05 * std::cos(b), 0.05 * std::sin(b));
  }
  return t;
}

double IndependentMiss(const BallModel& model, const AngleState& start, const JoinSummary& j) {
  FreeMotionStart fs;
  fs.state = StateFromAngles({start.theta, start.phi, start.psi + j.delta_psi}, 1.0, model);
  const Eigen::Vector3d z = fs.state.z;
  Eigen::Vector3d e1 = (Eigen::Vector3d::UnitX() - z.x() * z).normalized();
  fs.A0.col(0) = e1;
  fs.A0.col(1) = z.cross(e1);
  fs.A0.col(2) = z;
  return (IntegrateFreeMotion(model, fs, {j.t}).front().x - j.target).norm();
}

void BM_T1Join(benchmark::State& state) {
  const BallModel model = BallModel::FromLambda(2.0);
  const AngleState start{M_PI / 3, 0.4, 0.1};
  const std::vector<Eigen::Vector2d> targets = T1Targets();
  JoinOptions options;  // integration tolerances 1e-12, residual 1e-12
  std::size_t i = 0;
  double iterations = 0;
  long joins = 0;
  for (auto _ : state) {
    const JoinSummary j = Join(JoinProblem{model, start, 1.0, {0, 0}, targets[i]});
    benchmark::DoNotOptimize(&j);
    iterations += j.iterations;
    ++joins;
    i = (i + 1) % targets.size();
  }
  // Accuracy outside the timed loop: every target once.
  int ok = 0;
  double worst = 0.0;
  for (const auto& target : targets) {
    const JoinSummary j = Join(JoinProblem{model, start, 1.0, {0, 0}, target}, options);
    if (j.IsSolutionUsable()) ++ok;
    worst = std::max(worst, IndependentMiss(model, start, j));
  }
  state.counters["succeeded"] = ok;
  state.counters["targets"] = static_cast<double>(targets.size());
  state.counters["max_miss"] = worst;
  state.counters["mean_iterations"] = iterations / std::max<long>(1, joins);
}
BENCHMARK(BM_T1Join)->Unit(benchmark::kMicrosecond)->Repetitions(5)->ReportAggregatesOnly(true);

}  // namespace

BENCHMARK_MAIN();
