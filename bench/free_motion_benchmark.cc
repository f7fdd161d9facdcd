// Free motion: the time to integrate one period with x and A (constructing FreeMotion,
// which stores every accepted step for dense evaluation), and the time to evaluate a far time
// (t = 1000.3 T) from the stored period. lambda = 2, mu = 1, (theta, phi, psi) = (pi/3, 0.4, 0.1)
// (the state of the standard tasks), tolerances 1e-12. The accuracy reached is reported as
// counters, computed outside the timed loops against independent references:
//  - z_period_error, omega_period_error: |z(T) - z(0)|, |omega(T) - omega(0)| of a direct
//    integration (the state is exactly T-periodic, docs/paper_notes.md);
//  - energy_error: max |mu(t) - mu| over 200 samples of the stored period;
//  - far_x_error_vs_direct, far_A_error_vs_direct: At(1000.3 T) against a direct integration over
//    1000.3 periods at tolerances 1e-13. That reference is the less accurate of the two: its own
//    global error there is ~1.5e-7 (it moves by that much between tolerances 1e-13 and 3e-14,
//    while At moves by ~2e-9 between 1e-12 and 3e-14);
//  - far_x_self_convergence, far_A_self_convergence: At(1000.3 T) at tolerances 1e-12 against the
//    same evaluation from a period stored at 3e-14 (an estimate of At's own error);
//  - closed_form_theta_error: the angles of At(t) against the appendix's closed form (corrected).
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

#include "plateball/angle_form.h"
#include "plateball/closed_forms.h"
#include "plateball/free_motion.h"

namespace {

using namespace plateball;

const AngleState kStart{M_PI / 3, 0.4, 0.1};
constexpr double kMu = 1.0;

BallModel Model() { return BallModel::FromLambda(2.0); }

void BM_FreeMotionOnePeriod(benchmark::State& state) {
  const BallModel model = Model();
  int steps = 0;
  for (auto _ : state) {
    const FreeMotion m = FreeMotion::FromAngles(model, kStart, kMu);
    steps = m.StoredSteps();
    benchmark::DoNotOptimize(m.DriftPerPeriod());
  }
  const FreeMotion m = FreeMotion::FromAngles(model, kStart, kMu);
  const MotionSample end = IntegrateFreeMotion(model, m.start(), {m.Period()}).front();
  double energy = 0.0;
  for (const MotionSample& s : m.Sample(0.0, m.Period(), 200)) energy = std::max(energy, std::abs(s.energy - kMu));
  double theta = 0.0;
  const AppendixSolution closed(model, kStart, kMu);
  for (const MotionSample& s : m.Sample(0.0, m.Period(), 50))
    theta = std::max(theta, std::abs(s.angles.theta - closed.Theta(s.t)));
  state.counters["stored_steps"] = steps;
  state.counters["z_period_error"] = (end.state.z - m.start().state.z).norm();
  state.counters["omega_period_error"] = (end.state.omega - m.start().state.omega).norm();
  state.counters["energy_error"] = energy;
  state.counters["closed_form_theta_error"] = theta;
}
BENCHMARK(BM_FreeMotionOnePeriod)->Unit(benchmark::kMicrosecond);

void BM_IntegrateFreeMotionDirectOnePeriod(benchmark::State& state) {
  // The second method, for comparison: the same period without storing the steps.
  const BallModel model = Model();
  const FreeMotionStart start = FreeMotion::FromAngles(model, kStart, kMu).start();
  const double period = 2.0 * M_PI / std::sqrt(kMu);
  for (auto _ : state) benchmark::DoNotOptimize(IntegrateFreeMotion(model, start, {period}).front().x);
}
BENCHMARK(BM_IntegrateFreeMotionDirectOnePeriod)->Unit(benchmark::kMicrosecond);

void BM_AngleFormOnePeriod(benchmark::State& state) {
  // The paper's angle form (19)-(21), (25)-(26) over one period (the independent check).
  const BallModel model = Model();
  const double period = 2.0 * M_PI / std::sqrt(kMu);
  for (auto _ : state) benchmark::DoNotOptimize(IntegrateAngleForm(model, kStart, kMu, {0, 0}, {period}).t_reached);
}
BENCHMARK(BM_AngleFormOnePeriod)->Unit(benchmark::kMicrosecond);

void FarTime(benchmark::State& state, bool with_orientation) {
  const BallModel model = Model();
  const FreeMotion m = FreeMotion::FromAngles(model, kStart, kMu, {0, 0}, Eigen::Matrix3d::Identity());
  const double t = 1000.3 * m.Period();
  for (auto _ : state) {
    if (with_orientation) {
      benchmark::DoNotOptimize(m.At(t).A);
    } else {
      benchmark::DoNotOptimize(m.PositionAt(t));
    }
  }
  IntegrationOptions tight;
  tight.absolute_tolerance = tight.relative_tolerance = 1e-13;
  const MotionSample direct = IntegrateFreeMotion(model, m.start(), {t}, tight).front();
  const MotionSample far = m.At(t);
  IntegrationOptions finest;
  finest.absolute_tolerance = finest.relative_tolerance = 3e-14;
  const MotionSample fine =
      FreeMotion::FromAngles(model, kStart, kMu, {0, 0}, Eigen::Matrix3d::Identity(), finest).At(t);
  state.counters["far_x_error_vs_direct"] = (far.x - direct.x).norm();
  state.counters["far_A_error_vs_direct"] = (far.A - direct.A).norm();
  state.counters["far_x_self_convergence"] = (far.x - fine.x).norm();
  state.counters["far_A_self_convergence"] = (far.A - fine.A).norm();
  state.counters["distance_travelled"] = far.x.norm();
}

void BM_FreeMotionFarTimeAt(benchmark::State& state) { FarTime(state, true); }
BENCHMARK(BM_FreeMotionFarTimeAt)->Unit(benchmark::kMicrosecond);

void BM_FreeMotionFarTimePositionAt(benchmark::State& state) { FarTime(state, false); }
BENCHMARK(BM_FreeMotionFarTimePositionAt)->Unit(benchmark::kMicrosecond);

}  // namespace

BENCHMARK_MAIN();
