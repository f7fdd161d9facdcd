// Fuzz entry points, shared by the libFuzzer targets (fuzz/*_fuzzer.cc) and the regression test
// that replays fuzz/regressions/ (tests/fuzz_regression_test.cc). Each returns normally for any
// input; a defect (crash, uncaught unexpected exception, NaN in a result reported as valid, a
// broken round trip) aborts.
#pragma once

#include <cstddef>
#include <cstdint>

namespace plateball::fuzz {

/// The problem-file reader: any bytes either parse or throw std::invalid_argument; a parsed
/// problem written and read again gives the same canonical text.
void ProblemReader(const std::uint8_t* data, std::size_t size);

/// Public solve entry points fed with arbitrary numbers (the bytes read as doubles, NaN and
/// infinities included): state conversions, free motion, join, impulses and a short plan.
void SolveEntries(const std::uint8_t* data, std::size_t size);

/// Reach fed with arbitrary start, energy, model, target and options (small scan sizes so that
/// one input runs in milliseconds): an error names the input, a solution is finite and hits the
/// target to its tolerance.
void ReachEntry(const std::uint8_t* data, std::size_t size);

/// The isoparallel entry (SolveIsoparallel) fed with arbitrary start, goal, orientations and
/// options (few starts): an error names the input, a reported solution is finite.
void IsoparallelEntry(const std::uint8_t* data, std::size_t size);

/// `plateball steer` on a problem file (any bytes): the reader, then as the tool does it the
/// exact arrival along the plan path or the shortest isoparallel path (with the rig's limits when
/// the file has a rig section), or the fewest-impulse search, with the work capped (few impulses,
/// iterations, starts and integration steps) so that one input runs in milliseconds. An error is
/// std::invalid_argument (bad input) or std::runtime_error (a reported failure); a result reported
/// as usable is finite.
void SteerEntry(const std::uint8_t* data, std::size_t size);

/// `plateball view` on a result document (any bytes; normally a mutated result of steer, simulate,
/// plan, montecarlo, isoparallel or identify): the view's reader and re-simulation with few
/// samples. The result's problem.file is looked up by its file name in the source tree's problems/
/// folder only. An error is std::invalid_argument naming the result file (or the problem file) and
/// the field, or std::runtime_error; the page data is finite.
/// Defined in fuzz/view_entry.cc (it needs the view's sources of tools/).
void ViewEntry(const std::uint8_t* data, std::size_t size);

}  // namespace plateball::fuzz
