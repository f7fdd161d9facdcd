// The one message of bad input to a tool, the library's format (src/check.h):
//   "FIELD: value VALUE: what is wrong"
// thrown as std::invalid_argument, which the tools report with exit code 3 (errors.h). FIELD names
// what the user wrote: "FILE: section.key" for a file, "command line: --option" for an option.
#pragma once

#include <string>

namespace plateball::tools {

/// The source of a command-line value in messages: "command line: --samples: value ...".
inline constexpr const char* kCommandLine = "command line";

/// "command line: OPTION", the FIELD of a command-line option.
inline std::string CommandLineField(const std::string& option) { return std::string(kCommandLine) + ": " + option; }

/// Throws std::invalid_argument("FIELD: value VALUE: WHAT").
[[noreturn]] void ThrowInvalidInput(const std::string& field, const std::string& value, const std::string& what);

}  // namespace plateball::tools
