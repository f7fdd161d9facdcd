// The public entry points of the problem reader and writer (problem_io.h). The reader is one
// class per file section (src/problem_io/section_readers.h) on checked accessors
// (src/problem_io/field_reader.h); the writer is src/problem_io/writer.cc.
#include "plateball/problem_io.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <variant>

#include "plateball/limits.h"
#include "problem_io/json_parse.h"
#include "problem_io/section_readers.h"
#include "problem_io/writer.h"

namespace plateball {
namespace {

using internal::problem_io::DocumentReader;
using internal::problem_io::FieldReader;
using internal::problem_io::ParseJson;
using json = nlohmann::json;

// The one message for a problem text above limits::kMaxProblemFileBytes (a file, standard input
// or a string).
std::string TooLargeMessage(const std::string& source_name) {
  return source_name + ": (file): value (more than " + std::to_string(limits::kMaxProblemFileBytes) +
         " bytes): larger than the " + std::to_string(limits::kMaxProblemFileBytes >> 20) +
         " MiB limit of a problem file";
}

}  // namespace

std::string ToString(const PathSpec& spec) {
  static const char* const kNames[] = {"line", "circle", "ellipse", "lemniscate", "sine", "samples", "piecewise"};
  static_assert(std::variant_size_v<PathSpec::Shape> == 7, "one name per path shape");
  return kNames[spec.shape.index()];
}

Problem ParseProblem(const std::string& json_text, const std::string& source_name) {
  const FieldReader reader(source_name);
  if (json_text.size() > limits::kMaxProblemFileBytes) throw std::invalid_argument(TooLargeMessage(source_name));
  try {
    const json root = ParseJson(json_text, reader);
    return DocumentReader(reader).Document(root);
  } catch (const std::invalid_argument&) {
    throw;
  } catch (const json::exception& e) {
    // Not expected (every access is checked); kept so that no input escapes as another type.
    reader.Fail("(document)", "(unknown)", std::string("unexpected JSON error: ") + e.what());
  }
}

Problem ReadProblemFile(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw ProblemFileReadError(path + ": (file): value \"" + path + "\": is a directory, not a problem file");
  // Opening a FIFO blocks until a writer appears (an endless device is cut off by the size limit).
  if (std::filesystem::is_fifo(path, ec) || std::filesystem::is_socket(path, ec))
    throw ProblemFileReadError(path + ": (file): value \"" + path +
                               "\": a FIFO or socket, not a file; give a file, or \"-\" for standard input");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ProblemFileReadError(path + ": (file): value \"" + path + "\": cannot open the file for reading");
  std::string text;
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
    text.append(buffer, static_cast<std::size_t>(in.gcount()));
    if (text.size() > limits::kMaxProblemFileBytes) throw std::invalid_argument(TooLargeMessage(path));
  }
  if (in.bad()) throw ProblemFileReadError(path + ": (file): value \"" + path + "\": read error");
  return ParseProblem(text, path);
}

std::string WriteProblemJson(const Problem& p) { return internal::problem_io::WriteDocument(p); }

Eigen::Matrix3d ParseOrientation(const std::string& json_text,
                                 const std::string& field,
                                 const std::string& source_name) {
  const FieldReader reader(source_name);
  try {
    const json root = ParseJson(json_text, reader, field);
    return reader.Orientation(root, field);
  } catch (const std::invalid_argument&) {
    throw;
  } catch (const json::exception& e) {
    reader.Fail(field, "(unknown)", std::string("unexpected JSON error: ") + e.what());
  }
}

}  // namespace plateball
