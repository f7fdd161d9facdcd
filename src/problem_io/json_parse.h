// Parsing JSON text for the problem reader: one pass, no duplicate keys, nesting at most
// limits::kMaxJsonDepth, no NUL byte; every error names the line, column and field.
#pragma once

#include <string>

#include "problem_io/field_reader.h"

namespace plateball::internal::problem_io {

/// The document of `text`; malformed JSON is reported through `reader` (its source name), naming
/// the document `root_field` ("(document)" for a file, the option or argument that gave the text else)
/// and a value inside it by its path under `root_field`.
json ParseJson(const std::string& text, const FieldReader& reader, const std::string& root_field = "(document)");

}  // namespace plateball::internal::problem_io
