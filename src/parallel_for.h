// Internal: deterministic parallel loops for the solvers (results do not depend on the thread
// count: every index runs the same code). ParallelFor partitions statically; ParallelForDynamic
// hands the next index to whichever thread is free (jobs of very unequal cost).
#pragma once

#include <algorithm>
#include <atomic>
#include <exception>
#include <thread>
#include <vector>

namespace plateball::internal {

/// Runs job(i) for i in [0, n) on `threads` threads, index i on thread i mod threads. An
/// exception thrown by a job never reaches std::terminate: each thread stops at its first one,
/// and after every thread has joined the exception of the lowest index is rethrown on the calling
/// thread (deterministic for any thread count when jobs fail independently of each other).
template <class Job>
void ParallelFor(int n, int threads, Job&& job) {
  threads = std::max(1, std::min(threads, n));
  std::vector<std::exception_ptr> failure(static_cast<std::size_t>(std::max(threads, 1)));
  std::vector<int> failed_at(failure.size(), n);
  auto run = [&](int t) {
    for (int i = t; i < n; i += threads) {
      try {
        job(i);
      } catch (...) {
        failure[t] = std::current_exception();
        failed_at[t] = i;
        return;
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(run, t);
  run(0);
  for (auto& th : pool) th.join();
  const auto first = std::min_element(failed_at.begin(), failed_at.end()) - failed_at.begin();
  if (failure[first]) std::rethrow_exception(failure[first]);
}

/// As ParallelFor, but each next index (in increasing order) goes to the first free thread, for
/// jobs of very unequal cost. Every index runs (a failing job does not stop the others); the
/// exception of the lowest failing index is rethrown after every thread joined.
template <class Job>
void ParallelForDynamic(int n, int threads, Job&& job) {
  std::atomic<int> next{0};
  std::vector<std::exception_ptr> failure(static_cast<std::size_t>(std::max(n, 1)));
  ParallelFor(std::max(1, std::min(threads, n)), threads, [&](int) {
    for (int i = next++; i < n; i = next++) {
      try {
        job(i);
      } catch (...) {
        failure[static_cast<std::size_t>(i)] = std::current_exception();
      }
    }
  });
  for (const std::exception_ptr& e : failure)
    if (e) std::rethrow_exception(e);
}

}  // namespace plateball::internal
