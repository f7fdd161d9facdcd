#include "common/input_file.h"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>

#include "common/limits.h"
#include "common/errors.h"
#include "plateball/problem_io.h"

namespace plateball::tools {
namespace {

// At most kMaxInputFileBytes + 1 bytes of `in` (so that /dev/zero or a huge file ends at once).
std::string ReadBounded(std::istream& in, const std::string& name) {
  std::string text(kMaxInputFileBytes + 1, '\0');
  in.read(text.data(), static_cast<std::streamsize>(text.size()));
  if (in.bad()) throw IoError(name + ": read error");
  text.resize(static_cast<std::size_t>(in.gcount()));
  if (text.size() > kMaxInputFileBytes)
    throw std::invalid_argument(name + ": (document): value (more than " + std::to_string(kMaxInputFileBytes >> 20) +
                                " MiB): the file is larger than the limit of " +
                                std::to_string(kMaxInputFileBytes >> 20) + " MiB");
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
  Problem p = ParseProblem(ReadInputText(path), "(standard input)");
  p.source = "(standard input)";
  return p;
}

}  // namespace plateball::tools
