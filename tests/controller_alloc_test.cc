// The controller's Update allocates no heap memory after construction (controller.h): a counting
// global operator new in this executable of its own counts every allocation made while an Update
// runs, over a whole noisy circle run (more than 10^4 ticks).
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <memory>
#include <new>
#include <vector>

#include "plateball/controller.h"
#include "plateball/problem_io.h"
#include "plateball/task_adapters.h"
#include "simulated_rig.h"
#include "support/test_support.h"

namespace {
bool counting = false;
long allocations = 0;

void* Allocate(std::size_t size) {
  if (counting) ++allocations;
  if (void* p = std::malloc(size == 0 ? 1 : size)) return p;
  throw std::bad_alloc();
}
}  // namespace

void* operator new(std::size_t size) { return Allocate(size); }
void* operator new[](std::size_t size) { return Allocate(size); }
void* operator new(std::size_t size, const std::nothrow_t&) noexcept {
  if (counting) ++allocations;
  return std::malloc(size == 0 ? 1 : size);
}
void* operator new[](std::size_t size, const std::nothrow_t& t) noexcept { return operator new(size, t); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }
// Over-aligned types (none in the controller, but a counted allocation must not slip past).
void* operator new(std::size_t size, std::align_val_t a) {
  if (counting) ++allocations;
  if (void* p = std::aligned_alloc(
          static_cast<std::size_t>(a),
          (size + static_cast<std::size_t>(a) - 1) / static_cast<std::size_t>(a) * static_cast<std::size_t>(a)))
    return p;
  throw std::bad_alloc();
}
void operator delete(void* p, std::align_val_t) noexcept { std::free(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { std::free(p); }

namespace plateball {
namespace {

constexpr double kTick = 1e-3;              // a 1 kHz loop: the circle takes ~1.26e4 ticks
constexpr double kMeasurementNoise = 1e-4;  // per tick, on x, A (rotation vector) and omega

std::shared_ptr<const NominalPlan> Circle() {
  const Problem problem = ReadProblemFile(plateball::testing::SourcePath("problems/circle.json"));
  const PlanSetup setup = PlanSetupFor(problem, 32);
  return std::make_shared<NominalPlan>(MakeNominalPlan(setup.problem, setup.options));
}

struct Counts {
  long ticks = 0, impulse_ticks = 0, exact_ticks = 0;
  long quiet_allocations = 0;  // on ticks without an impulse
  long join_allocations = 0;   // on ticks whose impulse is a re-join (or a continued exact tail)
  long exact_allocations = 0;  // on ticks with a new exact re-plan
  ControllerStatus last = ControllerStatus::kNotRun;
};

Counts NoisyCircle(ExecutionStrategy strategy) {
  const std::shared_ptr<const NominalPlan> plan = Circle();
  ControllerOptions o;
  o.tick_period = kTick;
  o.strategy = strategy;
  Controller c(plan, o);
  internal::SimulatedRig rig(*plan, testing::ControllerTestErrors(), 3, 0, kMeasurementNoise);
  Counts n;
  for (long tick = 0; tick < 20000; ++tick) {
    const ControllerMeasurement m = rig.Measure(tick);
    allocations = 0;
    counting = true;
    const ControllerOutput& out = c.Update(static_cast<double>(tick) * kTick, m);
    counting = false;
    ++n.ticks;
    n.last = out.status;
    if (!out.impulse) {
      n.quiet_allocations += allocations;
    } else if (out.exact_replan) {
      ++n.exact_ticks;
      n.exact_allocations += allocations;
    } else {
      ++n.impulse_ticks;
      n.join_allocations += allocations;
    }
    if (out.impulse) rig.Impulse(out.impulse_index, out.delta_omega);
    if (out.status != ControllerStatus::kOk && out.status != ControllerStatus::kMeasurementRejected) break;
    rig.Roll(kTick);
  }
  return n;
}

TEST(ControllerAllocation, TheCounterCounts) {
  allocations = 0;
  counting = true;
  auto v = std::make_unique<std::vector<double>>(100);
  counting = false;
  EXPECT_EQ(allocations, 2);  // the vector object and its buffer
}

TEST(ControllerAllocation, FeedbackUpdatesAllocateNothing) {
  const Counts n = NoisyCircle(ExecutionStrategy::kFeedback);
  EXPECT_EQ(n.last, ControllerStatus::kDone);
  EXPECT_GT(n.ticks, 10000);
  EXPECT_EQ(n.impulse_ticks, 32);
  EXPECT_EQ(n.quiet_allocations, 0);
  EXPECT_EQ(n.join_allocations, 0);
}

TEST(ControllerAllocation, OnlyTheExactReplansAllocate) {
  const Counts n = NoisyCircle(ExecutionStrategy::kFeedbackExact);
  EXPECT_EQ(n.last, ControllerStatus::kDone);
  EXPECT_EQ(n.quiet_allocations, 0);
  EXPECT_EQ(n.join_allocations, 0);
  // exact_window = 12: new exact re-plans while 12 ... 3 impulses remain (the solver's vectors, the
  // reference path); the last two impulses continue that plan without allocating.
  EXPECT_EQ(n.exact_ticks, 10);
  EXPECT_GT(n.exact_allocations, 0);
  std::printf("allocations per exact re-plan: %.0f\n", static_cast<double>(n.exact_allocations) / 10.0);
}

}  // namespace
}  // namespace plateball
