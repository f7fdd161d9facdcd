// What the command-line tools read: a file, or standard input when the path is "-".
#pragma once

#include <string>

#include "plateball/problem.h"

namespace plateball::tools {

/// True for the path that means standard input: "-".
bool IsStandardInput(const std::string& path);

/// The whole text of the file `path` (or of standard input for "-"), at most kMaxResultFileBytes
/// (plateball/limits.h): a larger input is std::invalid_argument "PATH: (document): value (more
/// than 64 MiB): ..." (exit code 3); an unreadable one IoError naming the path (exit code 5).
std::string ReadInputText(const std::string& path);

/// The problem file `path` (problem_io.h's ReadProblemFile), or the problem read from standard
/// input for "-" (its source name "(standard input)"); either is refused above
/// limits::kMaxProblemFileBytes without reading further.
Problem ReadProblemInput(const std::string& path);

}  // namespace plateball::tools
