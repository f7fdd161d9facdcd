// How the command-line tools turn failures into messages and exit codes (exit_codes.h).
#pragma once

#include <functional>
#include <iostream>
#include <stdexcept>
#include <string>

#include "common/io_error.h"

namespace plateball::tools {

/// `text` for a terminal: C0 control characters other than line feed and tab, and DEL, are shown
/// as "\xNN" (a name with ESC sequences could otherwise retitle or clear the terminal).
std::string TerminalSafe(const std::string& text);

/// The exit code of a run that ended with the exception currently being handled, after printing
/// "PROGRAM: KIND: message" on `err`. Call it only inside a catch block. The mapping:
///   plateball::ProblemFileReadError, IoError      -> kExitIoError (5)      "cannot read/write"
///   std::invalid_argument (a field and its value) -> kExitBadInput (3)     "invalid input"
///   other std::runtime_error (an integration that  -> kExitNoSolution (4)  "computation failed"
///     exceeded max_steps, ...)
///   anything else                                 -> kExitInternalError (6) "internal error"
int ReportCurrentException(const std::string& program, std::ostream& err = std::cerr);

/// Runs `run` and returns its exit code, or ReportCurrentException's when it throws; then flushes
/// standard output: a failed write to it (a full disk) is reported as an IoError (exit code 5).
int RunWithExitCodes(const std::string& program, const std::function<int()>& run, std::ostream& err = std::cerr);

}  // namespace plateball::tools
