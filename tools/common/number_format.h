// The one number formatter of the command-line tools: every number printed as text (CSV cells,
// messages, captions) is the shortest text that reads back as the same double. JSON documents
// (json_output.h) use the same rule.
#pragma once

#include <string>

namespace plateball::tools {

/// Shortest text that reads back as the same double: "0.1", "1e+200", "-3", "inf", "nan".
std::string FormatNumber(double value);

}  // namespace plateball::tools
