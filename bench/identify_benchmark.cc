// Identification (docs/benchmarks.md, T8): fitting lambda, mu and the state to 2,000 samples of
// the contact point over two periods. The track is the library's FreeMotion (lambda = 1.3, mu = 4,
// (theta, phi, psi) = (0.8, 0.3, 0.2), x0 = (0.5, -0.2)) with seeded Gaussian noise sigma = 0.005
// (seed 1), or without noise. Timed: the whole Identify call; the variants are the full run
// (multi-start, fit, profile interval; also on two threads, wall time), the run without the profile
// interval, and the fit from a given guess. Counters (outside the timed loop): lambda_error = |lambda - 1.3|, mu_error,
// lambda_se (the standard error), x0_error and theta_error (the state), the 95% interval's half
// width, starts and iterations. The impulse variant: 2,000 samples of the circle of
// problems/circle.json planned with 8 impulses (lambda = 2, mu = 1; 250 per flight, each flight
// FreeMotion from the plan's state after its impulse), noise 0.005, the 7 impulse times given;
// counters lambda_error, lambda_se and the largest delta psi error over its standard error.
// The frame variants: the same 2,000 samples with measured orientations (the motion's A(t) from
// A0 = identity turned onto the axis, times exp(hat(e)), e ~ N(0, 0.005^2 I)) or body rates A^T
// omega (noise 0.005), sigma given; counters lambda_error and lambda_se.
#include <benchmark/benchmark.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <random>

#include "kinematics.h"
#include "plateball/free_motion.h"
#include "plateball/identify.h"
#include "plateball/impulse_planner.h"
#include "plateball/problem_io.h"
#include "plateball/so3.h"
#include "plateball/task_adapters.h"

namespace {

using namespace plateball;

constexpr double kLambda = 1.3, kMu = 4.0;
const AngleState kAngles{0.8, 0.3, 0.2};
const Eigen::Vector2d kX0{0.5, -0.2};

IdentifyProblem Track(double sigma) {
  const FreeMotion motion = FreeMotion::FromAngles(BallModel::FromLambda(kLambda), kAngles, kMu, kX0);
  std::mt19937_64 rng(1);
  std::normal_distribution<double> noise(0.0, 1.0);
  IdentifyProblem p;
  constexpr int kSamples = 2000;
  for (int i = 0; i < kSamples; ++i) {
    const double t = 2.0 * motion.Period() * i / (kSamples - 1);
    p.t.push_back(t);
    p.x.push_back(motion.PositionAt(t) + sigma * Eigen::Vector2d(noise(rng), noise(rng)));
  }
  return p;
}

void Run(benchmark::State& state, double sigma, bool profile, bool guess, int threads = 1) {
  const IdentifyProblem p = Track(sigma);
  IdentifyOptions o;
  o.profile_interval = profile;
  o.threads = threads;
  if (guess) o.guess = IdentifyGuess{1.0, 3.5, {0.7, 0.4, 0.1}, kX0, {}};
  IdentifySummary s;
  for (auto _ : state) {
    s = Identify(p, o);
    benchmark::DoNotOptimize(s.status);
  }
  if (s.status != IdentifyStatus::kIdentified) state.SkipWithError(s.BriefReport().c_str());
  state.counters["lambda_error"] = std::abs(s.lambda - kLambda);
  state.counters["mu_error"] = std::abs(s.mu - kMu);
  // The state: x0 (radii) and theta up to z -> -z (theta -> pi - theta gives the same track).
  state.counters["x0_error"] = (s.x0 - kX0).norm();
  state.counters["theta_error"] =
      std::min(std::abs(s.angles.theta - kAngles.theta), std::abs(M_PI - s.angles.theta - kAngles.theta));
  state.counters["lambda_se"] = s.standard_errors.empty() ? -1 : s.standard_errors[0];
  state.counters["interval_half_width"] = profile ? 0.5 * (s.lambda_high - s.lambda_low) : 0.0;
  state.counters["starts"] = s.starts;
  state.counters["iterations"] = s.iterations;
  state.counters["profile_fits"] = s.profile_fits;
}

/// The circle plan's track (see the header) and the plan's delta psi of its impulses 1..7.
IdentifyProblem ImpulseTrack(std::vector<double>* delta_psi) {
  const Problem problem = ReadProblemFile(std::string(PLATEBALL_SOURCE_DIR) + "/problems/circle.json");
  const PlanSetup setup = PlanSetupFor(problem, 8);
  const PlanSummary plan = PlanImpulses(setup.problem, setup.options);
  std::mt19937_64 rng(1);
  std::normal_distribution<double> noise(0.0, 1.0);
  IdentifyProblem p;
  Eigen::Vector2d x = Eigen::Vector2d::Zero();
  constexpr int kPerFlight = 250;
  for (std::size_t k = 0; k < plan.steps.size(); ++k) {
    const PlanStep& step = plan.steps[k];
    if (k > 0) {
      p.impulse_times.push_back(step.t_impulse);
      delta_psi->push_back(step.delta_psi);
    }
    const FreeMotion flight = FreeMotion::FromAngles(BallModel::FromLambda(2.0), step.impulse.after, step.mu, x);
    for (int i = k == 0 ? 0 : 1; i <= kPerFlight; ++i) {
      const double tau = step.duration * i / kPerFlight;
      p.t.push_back(step.t_impulse + tau);
      p.x.push_back(flight.PositionAt(tau) + 0.005 * Eigen::Vector2d(noise(rng), noise(rng)));
    }
    x = flight.PositionAt(step.duration);
  }
  return p;
}

void BM_IdentifyImpulsesFull(benchmark::State& state) {
  std::vector<double> truth;
  const IdentifyProblem p = ImpulseTrack(&truth);
  IdentifySummary s;
  for (auto _ : state) {
    s = Identify(p);
    benchmark::DoNotOptimize(s.status);
  }
  if (s.status != IdentifyStatus::kIdentified) state.SkipWithError(s.BriefReport().c_str());
  state.counters["samples"] = static_cast<double>(p.t.size());
  state.counters["lambda_error"] = std::abs(s.lambda - 2.0);
  state.counters["lambda_se"] = s.standard_errors.empty() ? -1 : s.standard_errors[0];
  double worst = 0.0;
  for (std::size_t k = 0; k < s.delta_psi.size(); ++k)
    worst = std::max(worst, std::abs(internal::WrapPi(s.delta_psi[k] - truth[k])) / s.standard_errors[7 + k]);
  state.counters["delta_psi_error_over_se"] = worst;
  state.counters["starts"] = s.starts;
  state.counters["iterations"] = s.iterations;
}

/// The 2,000-sample track with sigma 0.005 given and orientations or body rates (see the header).
IdentifyProblem FrameTrack(bool orientation) {
  const FreeMotion motion = FreeMotion::FromAngles(BallModel::FromLambda(kLambda), kAngles, kMu, kX0);
  std::mt19937_64 rng(1);
  std::normal_distribution<double> noise(0.0, 1.0);
  IdentifyProblem p;
  constexpr int kSamples = 2000;
  constexpr double kSigma = 0.005;
  for (int i = 0; i < kSamples; ++i) {
    const double t = 2.0 * motion.Period() * i / (kSamples - 1);
    const MotionSample m = motion.At(t);
    p.t.push_back(t);
    p.x.push_back(m.x + kSigma * Eigen::Vector2d(noise(rng), noise(rng)));
    p.sigma.push_back(kSigma);
    const Eigen::Vector3d e(noise(rng), noise(rng), noise(rng));
    if (orientation) {
      const Eigen::Quaterniond q(Eigen::Matrix3d(m.A * ExpSO3(kSigma * e)));
      p.orientation.emplace_back(q.w(), q.x(), q.y(), q.z());
      p.sigma_orientation.push_back(kSigma);
    } else {
      p.body_rate.push_back(m.A.transpose() * m.state.omega + kSigma * e);
      p.sigma_body_rate.push_back(kSigma);
    }
  }
  return p;
}

void RunFrame(benchmark::State& state, bool orientation) {
  const IdentifyProblem p = FrameTrack(orientation);
  IdentifySummary s;
  for (auto _ : state) {
    s = Identify(p);
    benchmark::DoNotOptimize(s.status);
  }
  if (s.status != IdentifyStatus::kIdentified) state.SkipWithError(s.BriefReport().c_str());
  state.counters["lambda_error"] = std::abs(s.lambda - kLambda);
  state.counters["lambda_se"] = s.standard_errors.empty() ? -1 : s.standard_errors[0];
  state.counters["interval_half_width"] = 0.5 * (s.lambda_high - s.lambda_low);
  state.counters["starts"] = s.starts;
}

void BM_IdentifyOrientationFull(benchmark::State& state) { RunFrame(state, true); }
void BM_IdentifyBodyRateFull(benchmark::State& state) { RunFrame(state, false); }
void BM_IdentifyNoisyFull(benchmark::State& state) { Run(state, 0.005, true, false); }
void BM_IdentifyNoisyNoProfile(benchmark::State& state) { Run(state, 0.005, false, false); }
void BM_IdentifyNoisyFromGuess(benchmark::State& state) { Run(state, 0.005, false, true); }
void BM_IdentifyNoiselessFull(benchmark::State& state) { Run(state, 0.0, true, false); }
// The full run on two threads (the CLI's default on a 2-core machine): wall time.
void BM_IdentifyNoisyFullTwoThreads(benchmark::State& state) { Run(state, 0.005, true, false, 2); }

BENCHMARK(BM_IdentifyNoisyFull)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_IdentifyNoisyFullTwoThreads)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_IdentifyNoisyNoProfile)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_IdentifyNoisyFromGuess)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_IdentifyNoiselessFull)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_IdentifyImpulsesFull)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_IdentifyOrientationFull)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_IdentifyBodyRateFull)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
