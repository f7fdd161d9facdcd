// Parsing JSON text for the problem reader: one pass, no duplicate keys, nesting at most
// limits::kMaxJsonDepth, no NUL byte; every error names the line, column and field.
#pragma once

#include <string>

#include "problem_io/field_reader.h"

namespace plateball::internal::problem_io {

/// The document of `text`; malformed JSON is reported through `reader` (its source name).
json ParseJson(const std::string& text, const FieldReader& reader);

}  // namespace plateball::internal::problem_io
