// Command-line parsing shared by `plateball` and `isoparallel_solve`: the same value checks and
// the same exit codes for the same mistakes in both tools.
#pragma once

#include <CLI/CLI.hpp>
#include <cstdint>
#include <optional>
#include <string>

namespace plateball::tools {

/// Parses argv into `app` (and its subcommands). Every option that takes a value rejects an empty
/// or blank value (CLI11 would read "" as 0). Returns std::nullopt when the run should go on, else
/// the exit code: 0 for --help/--version, kExitBadInput (3) for a value that is not a number or
/// out of its range ("PROGRAM: invalid input: command line: --OPTION: ..."), kExitUsage (2) for
/// other command-line errors (unknown option, missing argument).
std::optional<int> ParseCommandLine(CLI::App& app, int argc, char** argv, const std::string& program);

/// A seed: a decimal integer in [0, 2^64 - 1] (CLI11 would read "-1" as 2^64 - 1 and clamp larger
/// values). Throws std::invalid_argument "command line: OPTION: value "TEXT": must be an integer
/// in [0, 2^64 - 1]".
std::uint64_t ParseSeedOption(const std::string& option, const std::string& text);

/// The help's type name of a seed option.
inline constexpr const char* kSeedTypeName = "UINT64";

}  // namespace plateball::tools
