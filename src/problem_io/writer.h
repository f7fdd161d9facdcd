// The problem writer behind WriteProblemJson (problem_io.h).
#pragma once

#include <string>

#include "plateball/problem.h"

namespace plateball::internal::problem_io {

/// The JSON text of `p` (every field, defaults included); throws std::invalid_argument naming the
/// field for a non-finite value.
std::string WriteDocument(const Problem& p);

}  // namespace plateball::internal::problem_io
