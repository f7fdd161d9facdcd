#include "common/input_file.h"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>

#include "common/errors.h"
#include "common/invalid_input.h"
#include "common/limits.h"
#include "plateball/problem_io.h"

namespace plateball::tools {
namespace {

// At most `limit` + 1 bytes of `in` (so that /dev/zero or a huge file ends at once).
std::string ReadAtMost(std::istream& in, const std::string& name, std::size_t limit) {
  std::string text(limit + 1, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (in.bad()) throw IoError(name + ": read error");
  text.resize(static_cast<std::size_t>(in.gcount()));
  return text;
}

// At most kMaxResultFileBytes of `in`; a larger input is an input error.
std::string ReadBounded(std::istream& in, const std::string& name) {
  std::string text = ReadAtMost(in, name, kMaxResultFileBytes);
  if (text.size() > kMaxResultFileBytes)
    ThrowInvalidInput(name + ": (document)",
                      "(more than " + std::to_string(kMaxResultFileBytes >> 20) + " MiB)",
                      "the file is larger than the limit of " + std::to_string(kMaxResultFileBytes >> 20) + " MiB");
  return text;
}

}  // namespace

bool IsStandardInput(const std::string& path) { return path == "-"; }

std::string ReadInputText(const std::string& path) {
  if (IsStandardInput(path)) return ReadBounded(std::cin, "standard input");
  // Opening a FIFO blocks until a writer appears (an endless device is cut off by ReadBounded).
  std::error_code ec;
  if (std::filesystem::is_fifo(path, ec) || std::filesystem::is_socket(path, ec))
    throw IoError(path + ": a FIFO or socket, not a file; give a file, or \"-\" for standard input");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot open the file for reading");
  return ReadBounded(in, path);
}

Problem ReadProblemInput(const std::string& path) {
  if (!IsStandardInput(path)) return ReadProblemFile(path);
  // A problem on standard input has the problem file's limit: read one byte past it, and the
  // reader refuses the text with the same message as for a file.
  Problem p = ParseProblem(ReadAtMost(std::cin, "standard input", kMaxProblemFileBytes), "(standard input)");
  p.source = "(standard input)";
  return p;
}

}  // namespace plateball::tools
