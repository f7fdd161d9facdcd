#include "common/sample_table.h"

#include <cmath>
#include <stdexcept>

#include "common/number_format.h"
#include "common/output_file.h"
#include "common/progress.h"

namespace plateball::tools {
namespace {

void Flatten(const Json& j, const std::string& name, std::vector<std::pair<std::string, std::string>>* out) {
  const auto child = [&name](const std::string& key) { return name.empty() ? key : name + "." + key; };
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) Flatten(it.value(), child(it.key()), out);
  } else if (j.is_array()) {
    for (std::size_t i = 0; i < j.size(); ++i) Flatten(j[i], child(std::to_string(i)), out);
  } else if (j.is_number_float()) {
    const double v = j.get<double>();
    if (!std::isfinite(v)) throw std::logic_error("output value " + name + " = " + FormatNumber(v) + " is not finite");
    out->emplace_back(name, FormatNumber(v));
  } else if (j.is_string()) {
    out->emplace_back(name, j.get<std::string>());
  } else {
    out->emplace_back(name, j.dump());
  }
}

}  // namespace

std::vector<std::pair<std::string, std::string>> CsvColumns(const Json& sample) {
  std::vector<std::pair<std::string, std::string>> out;
  Flatten(sample, "", &out);
  return out;
}

void WriteSampleDocument(
    const std::string& path, Json header, std::size_t count, const SampleSource& sample, Progress* progress) {
  header["samples"] = Json::array();
  std::string head = DumpJson(header);
  const std::string tail = "\"samples\": []\n}\n";
  if (head.size() < tail.size() || head.compare(head.size() - tail.size(), tail.size(), tail) != 0)
    throw std::logic_error("WriteSampleDocument: \"samples\" is not the document's last key");
  head.resize(head.size() - 5);  // "...\"samples\": " without "[]\n}\n"
  WriteOutputStreamed(path, [&](const OutputSink& sink) {
    sink(head);
    sink(count == 0 ? "[]" : "[\n");
    for (std::size_t i = 0; i < count; ++i) {
      sink(i ? ",\n    " : "    ");
      sink(DumpJsonAt(sample(i), 4));
      if (progress) progress->Update(static_cast<double>(i + 1));
    }
    sink(count == 0 ? "\n}\n" : "\n  ]\n}\n");
  });
}

void WriteSampleCsv(const std::string& path, std::size_t count, const SampleSource& sample, Progress* progress) {
  WriteOutputStreamed(path, [&](const OutputSink& sink) {
    std::string line;
    for (std::size_t i = 0; i < count; ++i) {
      const auto columns = CsvColumns(sample(i));
      if (i == 0) {
        line.clear();
        for (const auto& [name, value] : columns) line += (line.empty() ? "" : ",") + name;
        sink(line + "\n");
      }
      line.clear();
      for (std::size_t c = 0; c < columns.size(); ++c) line += (c ? "," : "") + columns[c].second;
      sink(line + "\n");
      if (progress) progress->Update(static_cast<double>(i + 1));
    }
  });
}

}  // namespace plateball::tools
