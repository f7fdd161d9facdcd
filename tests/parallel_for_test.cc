// The solvers' parallel loops (src/parallel_for.h): every index runs exactly once on any thread
// count, and the exception of the lowest failing index reaches the caller after every thread joined.
#include "parallel_for.h"

#include <gtest/gtest.h>

#include <atomic>
#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace plateball::internal {
namespace {

template <class Loop>
void ExpectEveryIndexOnce(Loop loop) {
  for (int threads : {1, 2, 3, 8})
    for (int n : {0, 1, 2, 7, 50}) {
      std::vector<std::atomic<int>> runs(static_cast<std::size_t>(n));
      loop(n, threads, [&](int i) { ++runs[static_cast<std::size_t>(i)]; });
      for (int i = 0; i < n; ++i)
        EXPECT_EQ(runs[static_cast<std::size_t>(i)].load(), 1) << n << " " << threads << " " << i;
    }
}

TEST(ParallelFor, EveryIndexRunsOnce) {
  ExpectEveryIndexOnce([](int n, int t, auto&& job) { ParallelFor(n, t, job); });
  ExpectEveryIndexOnce([](int n, int t, auto&& job) { ParallelForDynamic(n, t, job); });
}

std::string Thrown(const std::function<void()>& f) {
  try {
    f();
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "none";
}

TEST(ParallelFor, TheLowestFailingIndexIsRethrown) {
  auto job = [](int i) {
    if (i == 3 || i == 7) throw std::runtime_error(std::to_string(i));
  };
  for (int threads : {1, 2, 4}) {
    EXPECT_EQ(Thrown([&] { ParallelFor(10, threads, job); }), "3") << threads;
    EXPECT_EQ(Thrown([&] { ParallelForDynamic(10, threads, job); }), "3") << threads;
  }
  // The dynamic loop runs every index even after a failure.
  std::atomic<int> ran{0};
  EXPECT_EQ(Thrown([&] {
              ParallelForDynamic(10, 2, [&](int i) {
                ++ran;
                job(i);
              });
            }),
            "3");
  EXPECT_EQ(ran.load(), 10);
}

}  // namespace
}  // namespace plateball::internal
