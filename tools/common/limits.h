// Limits of the command-line tools' own inputs (command-line values and the samples file of
// `plateball roll`), in one place. Each is checked before any work; exceeding one is bad input
// (exit code 3) with a message naming the option or file and the limit. The problem-file reader
// has its own table (src/problem_io.cc); the values shared with it are equal.
#pragma once

#include <cstddef>

namespace plateball::tools {

/// Size of a file read by a tool (the problem reader's limit too): 64 MiB.
inline constexpr std::size_t kMaxInputFileBytes = std::size_t{64} << 20;
/// Nesting depth of arrays and objects in a JSON file read by a tool.
inline constexpr int kMaxJsonDepth = 64;
/// Characters of an offending value quoted in a message.
inline constexpr std::size_t kMaxValueTextChars = 80;
/// Points of a path given to `plateball roll` (--points or --samples-file), and samples of
/// `plateball simulate` (as the problem-file reader).
inline constexpr std::size_t kMaxPoints = 1'000'000;
inline constexpr long long kMaxSamples = 1'000'000;
/// Impulses of a plan over all smooth pieces (n x pieces; the reader's and MakePartition's limit).
inline constexpr long long kMaxPartitionSteps = 10'000;
/// |t_end| / period below which a free motion is evaluated (free_motion.h: "|t| <= 1e12 periods").
inline constexpr double kMaxPeriods = 1e12;

}  // namespace plateball::tools
