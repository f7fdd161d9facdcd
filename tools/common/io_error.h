// The exception of a file the tool had to read or write and could not (exit code 5). Its own
// header so that output_file does not depend on errors (which runs the tools with output_file).
#pragma once

#include <stdexcept>

namespace plateball::tools {

/// A file the tool had to read or write could not be (exit code kExitIoError).
class IoError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace plateball::tools
