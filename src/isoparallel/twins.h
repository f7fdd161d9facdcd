// The twin search of the general-target isoparallel solver (isoparallel.h), exposed for tests:
// solutions of a general target often come in close pairs born at a fold of the shooting map
// (section 2.2's rotation trick, free-length form), and the solver follows each new solution by a
// search for its twin across the fold (docs/paper_notes.md, "General targets", points 6 and 9).
#pragma once

#include <vector>

#include "plateball/isoparallel.h"

namespace plateball::internal {

// The solutions the twin search finds from `solution` (a solution of `problem`, e.g. from
// SolveIsoparallel), polished to options.tolerance and distinct from `solution`; not verified by
// rolling (VerifyRolling does that).
std::vector<IsoparallelSolution> IsoparallelTwins(const IsoparallelProblem& problem,
                                                  const IsoparallelSolution& solution,
                                                  const IsoparallelOptions& options = {});

}  // namespace plateball::internal
