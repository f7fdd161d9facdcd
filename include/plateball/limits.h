// The sizes of plateball's inputs, each given once with the reason for its value. The problem
// reader (problem_io.h), the library's checks, the command-line tools, the Python binding and the
// documentation's Limits table (docs/guide/problem_files.md) all use these constants; a value
// beyond one is an input error naming the field or option, the value and the limit.
#pragma once

#include <cstddef>

namespace plateball::limits {

/// Bytes of a problem file, from a file, standard input or a string: a problem file holds at most
/// a few lists of 10^5 points (about 5 MB), so 16 MiB is generous and bounds the parser's memory.
inline constexpr std::size_t kMaxProblemFileBytes = std::size_t{16} << 20;
/// Bytes of any other JSON input of the tools (a result for `plateball view`, the samples file of
/// `plateball roll`): a simulation result of kMaxSamples samples is about 30 MB.
inline constexpr std::size_t kMaxResultFileBytes = std::size_t{64} << 20;
/// Nesting depth of arrays and objects in a JSON input: real files nest at most 10 levels; the
/// bound keeps the reader's recursion shallow.
inline constexpr int kMaxJsonDepth = 64;
/// Samples of a simulation and sample points of a path, 2 ... 10^5, in a file, on the command
/// line and in Python: `plateball view` draws a result of this many samples.
inline constexpr int kMaxSamples = 100'000;
/// Points of a path given to `plateball roll` (--points or --samples-file): roll follows them in
/// one linear pass, and 10^6 points [x, y] (about 40 MB) fit kMaxResultFileBytes.
inline constexpr std::size_t kMaxPoints = 1'000'000;
/// Steps of a plan over all smooth pieces (partition n x pieces) and impulse indices: `plan --n
/// 10000` takes 1.2 s and 116 MB; the bound keeps one call under ~10 s and ~1 GB.
inline constexpr int kMaxPartitionSteps = 10'000;
/// |x|, |y| of positions and targets: beyond it the solvers' absolute accuracy (about 2e-16 |x|)
/// no longer resolves the joins.
inline constexpr double kMaxCoordinate = 1e6;
/// Elements of a list in a problem file (reach targets, path pieces, energy changes, converge_n):
/// each element costs a solve, so 10^5 already means hours.
inline constexpr long long kMaxListLength = 100'000;
/// Reach horizon in free-motion periods, (0, 100]: times the 256 candidates per period this is the
/// refinement budget of one reach call (~1.3 s at 100).
inline constexpr double kMaxHorizonPeriods = 100.0;
/// Nesting of piecewise paths: real paths nest once or twice; the bound keeps recursion shallow.
inline constexpr int kMaxPieceDepth = 8;
/// Rolling length sqrt(mu) T of the fewest-impulse search's time window, in ball radii: its
/// rollouts grow faster than the window (a goal 300 radii away: about 10 s; 1000 radii: minutes),
/// so a longer move is planned along a path and steered exactly piece by piece.
inline constexpr double kMaxFewestWindowLength = 500.0;

}  // namespace plateball::limits
