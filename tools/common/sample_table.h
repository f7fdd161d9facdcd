// Large sample tables streamed to their output: `plateball simulate --samples 100000`
// writes its samples one at a time, as JSON or CSV, in memory that does not grow with the sample
// count; the file is still replaced atomically (output_file.h: WriteOutputStreamed).
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "common/json_output.h"

namespace plateball::tools {

class Progress;

/// The i-th sample (0-based) of a table, as the JSON object the document shows.
using SampleSource = std::function<Json(std::size_t)>;

/// Writes `header` with a last key "samples" holding samples 0 ... count-1: byte for byte what
/// WriteJson would write for the whole document, without holding it. `progress` (may be null) is
/// updated with the number of samples written.
void WriteSampleDocument(
    const std::string& path, Json header, std::size_t count, const SampleSource& sample, Progress* progress);

/// Writes the samples as CSV: a line of column names, then a line per sample. The columns are the
/// sample's keys in order, nested keys joined by '.', array elements by their index (x.0, x.1,
/// orientation.0.0, ...), as the converge CSV of docs/output_contract.md; numbers in the shortest
/// form that reads back to the same double.
void WriteSampleCsv(const std::string& path, std::size_t count, const SampleSource& sample, Progress* progress);

/// The columns of one sample: (name, value) for every number, string or boolean in it. Throws
/// std::logic_error naming the column of a non-finite number.
std::vector<std::pair<std::string, std::string>> CsvColumns(const Json& sample);

}  // namespace plateball::tools
