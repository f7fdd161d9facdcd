// Limits of the command-line tools. The sizes shared with the library, the problem reader and
// Python (file bytes, nesting depth, samples, points, plan steps) are plateball/limits.h's, named
// here for the tools' code; the two below are the tools' own. Each is checked before any work;
// exceeding one is bad input (exit code 3) with a message naming the option or file and the limit.
#pragma once

#include <cstddef>

#include "plateball/limits.h"

namespace plateball::tools {

using limits::kMaxCoordinate;
using limits::kMaxJsonDepth;
using limits::kMaxPartitionSteps;
using limits::kMaxPoints;
using limits::kMaxProblemFileBytes;
using limits::kMaxResultFileBytes;
using limits::kMaxSamples;

/// Characters of an offending value quoted in a message: enough to recognise it on one line.
inline constexpr std::size_t kMaxValueTextChars = 80;
/// |t_end| / period below which a free motion is evaluated (free_motion.h: "|t| <= 1e12 periods").
inline constexpr double kMaxPeriods = 1e12;

}  // namespace plateball::tools
