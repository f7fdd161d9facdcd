// Internal: a deterministic parallel loop for the solvers (results do not depend on the thread
// count: every index runs the same code, the partition is static).
#pragma once

#include <algorithm>
#include <thread>
#include <vector>

namespace plateball::internal {

/// Runs job(i) for i in [0, n) on `threads` threads, index i on thread i mod threads.
template <class Job>
void ParallelFor(int n, int threads, Job&& job) {
  threads = std::max(1, std::min(threads, n));
  if (threads == 1) {
    for (int i = 0; i < n; ++i) job(i);
    return;
  }
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t)
    pool.emplace_back([&, t] {
      for (int i = t; i < n; i += threads) job(i);
    });
  for (int i = 0; i < n; i += threads) job(i);
  for (auto& th : pool) th.join();
}

}  // namespace plateball::internal
