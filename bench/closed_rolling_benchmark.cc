// The rolling along an elastica: the closed form of elastica_closed_rolling.h (costate
// frame and twist, Legendre's Pi) against the sixth-order Magnus tables of elastica_rolling.h,
// at k = 0.8, rate 0.9 (oscillating G = 0.81, rotating G = 0.5184), lengths L = 6 and L = 20.
//  - BM_ClosedRollingBuildAndRoll: construct ElasticaClosedRolling (K, the complete Pi, the frame
//    and Pi at s = 0) and evaluate Rolling(L): the cost of one rolling of a new elastica.
//  - BM_ClosedRollingRoll: Rolling(0.3, L) on a constructed object (two incomplete Pi, two
//    Jacobi evaluations); BM_ClosedRollingRollFromZero: Rolling(L) = Q(0, L), the frame and Pi at
//    s = 0 kept from the construction (one incomplete Pi, one Jacobi evaluation).
//  - BM_TableSearchBuildAndRoll: ElasticaRollingTable at the search's setting (12 steps per
//    period, max_step 0.5) + Rolling(L); BM_TableFineBuildAndRoll: the polish's setting (160,
//    0.02). Both count the table's construction, as the search builds one per candidate.
// Counter error_vs_dopri5: max |entry| of Q(0, L) minus a Dormand-Prince 5(4) integration at
// step tolerance 1e-15 (outside the timed loop).
#include <benchmark/benchmark.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "dopri5.h"
#include "elastica_closed_rolling.h"
#include "elastica_rolling.h"

namespace {

using namespace plateball;

Elastica Shape(int regime) {
  ElasticaParameters p;
  p.regime = regime == 0 ? PendulumRegime::kOscillating : PendulumRegime::kRotating;
  p.rate = 0.9;
  p.modulus = 0.8;
  p.phase = 0.3;
  p.heading_w = 0.4;
  return Elastica(p);
}

Eigen::Matrix3d DopriRolling(const Elastica& e, double length) {
  std::array<double, 9> y{1, 0, 0, 0, 1, 0, 0, 0, 1};  // row-major Q
  auto rhs = [&e](const std::array<double, 9>& q, std::array<double, 9>& dq, double s) {
    const Eigen::Vector2d t = e.Tangent(s);
    for (int c = 0; c < 3; ++c) {  // (e3 x x') x column
      dq[c] = t.x() * q[6 + c];
      dq[3 + c] = t.y() * q[6 + c];
      dq[6 + c] = -t.x() * q[c] - t.y() * q[3 + c];
    }
  };
  double s = 0.0, h = 0.01;
  while (s < length) {
    h = std::min(h, length - s);
    std::array<double, 9> trial = y;
    const double err = internal::DormandPrince5Step<9>(rhs, trial, s, h, 1e-15, 1e-15);
    if (err <= 1.0) {
      y = trial;
      s = h == length - s ? length : s + h;
    }
    h *= std::clamp(0.9 * std::pow(std::max(err, 1e-10), -0.2), 0.2, 5.0);
  }
  Eigen::Matrix3d q;
  q << y[0], y[1], y[2], y[3], y[4], y[5], y[6], y[7], y[8];
  return q;
}

void ReportError(benchmark::State& state, const Elastica& e, double length, const Eigen::Matrix3d& q) {
  state.counters["error_vs_dopri5"] = (q - DopriRolling(e, length)).cwiseAbs().maxCoeff();
  state.counters["periods"] = length / e.Period();
}

void BM_ClosedRollingBuildAndRoll(benchmark::State& state) {
  const Elastica e = Shape(static_cast<int>(state.range(0)));
  const double length = static_cast<double>(state.range(1));
  Eigen::Matrix3d q;
  for (auto _ : state) {
    const internal::ElasticaClosedRolling closed(e);
    q = closed.Rolling(length);
    benchmark::DoNotOptimize(q.data());
  }
  ReportError(state, e, length, q);
}

void TimeClosedRolling(benchmark::State& state, bool from_zero) {
  const Elastica e = Shape(static_cast<int>(state.range(0)));
  const double length = static_cast<double>(state.range(1));
  const internal::ElasticaClosedRolling closed(e);
  Eigen::Matrix3d q;
  for (auto _ : state) {
    q = from_zero ? closed.Rolling(length) : closed.Rolling(0.3, length);
    benchmark::DoNotOptimize(q.data());
  }
  state.counters["periods"] = length / e.Period();
}

void BM_ClosedRollingRoll(benchmark::State& state) { TimeClosedRolling(state, false); }
void BM_ClosedRollingRollFromZero(benchmark::State& state) { TimeClosedRolling(state, true); }

void TableBuildAndRoll(benchmark::State& state, int steps_per_period, double max_step) {
  const Elastica e = Shape(static_cast<int>(state.range(0)));
  const double length = static_cast<double>(state.range(1));
  Eigen::Matrix3d q;
  for (auto _ : state) {
    const internal::ElasticaRollingTable table(e, length, steps_per_period, max_step);
    q = table.Rolling(length);
    benchmark::DoNotOptimize(q.data());
  }
  ReportError(state, e, length, q);
}

void BM_TableSearchBuildAndRoll(benchmark::State& state) { TableBuildAndRoll(state, 12, 0.5); }
void BM_TableFineBuildAndRoll(benchmark::State& state) { TableBuildAndRoll(state, 160, 0.02); }

// Arguments: regime (0 oscillating, 1 rotating), L.
void Args(benchmark::internal::Benchmark* b) { b->ArgsProduct({{0, 1}, {6, 20}}); }
BENCHMARK(BM_ClosedRollingBuildAndRoll)->Apply(Args);
BENCHMARK(BM_ClosedRollingRoll)->Apply(Args);
BENCHMARK(BM_ClosedRollingRollFromZero)->Apply(Args);
BENCHMARK(BM_TableSearchBuildAndRoll)->Apply(Args);
BENCHMARK(BM_TableFineBuildAndRoll)->Apply(Args);

}  // namespace

BENCHMARK_MAIN();
