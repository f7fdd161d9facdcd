// Figure 7 (problems/figure7.json) for the exact-arrival tests: the isoparallel solve and the
// exact-arrival problem along its shortest path, each built once per test program.
#pragma once

#include "plateball/exact_arrival.h"
#include "plateball/isoparallel.h"

namespace plateball::testing {

/// The isoparallel solutions of problems/figure7.json ((0, 0) -> (3, 3), identity, lambda = 2).
const IsoparallelSummary& Figure7Isoparallel();

/// Exact arrival at Figure 7's goal with 12 impulses along the shortest path, through the task
/// adapters the tools use.
const ExactArrivalProblem& Figure7ExactArrival();

}  // namespace plateball::testing
