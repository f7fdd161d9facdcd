#include "common/output_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <system_error>

#include "common/errors.h"

namespace plateball::tools {
namespace {

namespace fs = std::filesystem;

std::string ErrnoText(int err) { return std::strerror(err); }

std::string DirectoryOf(const std::string& path) {
  const fs::path parent = fs::path(path).parent_path();
  return parent.empty() ? std::string(".") : parent.string();
}

bool IsExistingNonRegular(const std::string& path) {
  struct stat st {};
  return ::stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode);
}

// Writes all of `text` to `fd`; returns 0 or the errno of the failure.
int WriteAll(int fd, const std::string& text) {
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0) {
      if (errno == EINTR) continue;
      return errno;
    }
    done += static_cast<std::size_t>(n);
  }
  return 0;
}

void WriteInPlace(const std::string& path, const std::string& text) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
  if (fd < 0) throw IoError(path + ": cannot open for writing: " + ErrnoText(errno));
  const int err = WriteAll(fd, text);
  const int close_err = ::close(fd) == 0 ? 0 : errno;
  if (err != 0 || close_err != 0) throw IoError(path + ": write failed: " + ErrnoText(err != 0 ? err : close_err));
}

// The mode a new file gets (0666 less the umask), or the existing file's mode.
mode_t TargetMode(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) return st.st_mode & 07777;
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return 0666 & ~mask;
}

void WriteAtomically(const std::string& path, const std::string& text) {
  std::string temp = (fs::path(DirectoryOf(path)) / ("." + fs::path(path).filename().string() + ".tmpXXXXXX")).string();
  const int fd = ::mkstemp(temp.data());
  if (fd < 0) throw IoError(path + ": cannot create a temporary file in " + DirectoryOf(path) + ": " + ErrnoText(errno));
  int err = WriteAll(fd, text);
  if (err == 0 && ::fchmod(fd, TargetMode(path)) != 0) err = errno;
  if (err == 0 && ::fsync(fd) != 0) err = errno;
  if (::close(fd) != 0 && err == 0) err = errno;
  if (err == 0 && ::rename(temp.c_str(), path.c_str()) != 0) err = errno;
  if (err != 0) {
    ::unlink(temp.c_str());
    throw IoError(path + ": write failed (the previous file, if any, is unchanged): " + ErrnoText(err));
  }
}

// Two paths name the same file (both existing and equivalent, or the same normalised path).
bool SameFile(const std::string& a, const std::string& b) {
  std::error_code ec;
  if (fs::equivalent(a, b, ec) && !ec) return true;
  const fs::path na = fs::weakly_canonical(fs::absolute(a, ec), ec);
  const fs::path nb = fs::weakly_canonical(fs::absolute(b, ec), ec);
  return na == nb;
}

void CheckWritable(const PathArgument& out) {
  if (IsExistingNonRegular(out.path)) {
    if (::access(out.path.c_str(), W_OK) != 0) throw IoError(out.path + ": cannot write (" + out.option + "): " + ErrnoText(errno));
    return;
  }
  const std::string dir = DirectoryOf(out.path);
  struct stat st {};
  if (::stat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
    throw IoError(out.path + ": cannot write (" + out.option + "): the directory " + dir + " does not exist");
  if (::access(dir.c_str(), W_OK | X_OK) != 0)
    throw IoError(out.path + ": cannot write (" + out.option + "): the directory " + dir + " is not writable");
}

}  // namespace

bool IsStandardOutput(const std::string& path) { return path.empty() || path == "-"; }

void WriteOutput(const std::string& path, const std::string& text) {
  if (IsStandardOutput(path)) {
    std::cout << text;
    FlushStandardOutput();
  } else if (IsExistingNonRegular(path)) {
    WriteInPlace(path, text);
  } else {
    WriteAtomically(path, text);
  }
}

void FlushStandardOutput() {
  std::cout.flush();
  if (!std::cout) throw IoError("standard output: write failed");
}

void CheckOutputPaths(const std::vector<PathArgument>& outputs, const std::vector<PathArgument>& inputs) {
  for (std::size_t i = 0; i < outputs.size(); ++i) {
    const PathArgument& a = outputs[i];
    if (a.path.empty()) continue;
    for (std::size_t k = 0; k < i; ++k) {
      const PathArgument& b = outputs[k];
      if (b.path.empty()) continue;
      const bool both_stdout = a.path == "-" && b.path == "-";
      if (both_stdout || (a.path != "-" && b.path != "-" && SameFile(a.path, b.path)))
        throw std::invalid_argument("command line: " + b.option + " and " + a.option + ": value " + a.path +
                                    ": two outputs name the same " + (both_stdout ? "standard output" : "file"));
    }
    if (a.path == "-") continue;
    for (const PathArgument& in : inputs)
      if (!in.path.empty() && in.path != "-" && SameFile(a.path, in.path))
        throw std::invalid_argument("command line: " + a.option + " and " + in.option + ": value " + a.path +
                                    ": the output would overwrite the input file");
  }
  for (const PathArgument& a : outputs)
    if (!IsStandardOutput(a.path)) CheckWritable(a);
}

}  // namespace plateball::tools
