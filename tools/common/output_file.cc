#include "common/output_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "common/invalid_input.h"
#include "common/io_error.h"

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
int WriteAll(int fd, std::string_view text) {
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

// The mode a new file gets (0666 less the umask), or the existing file's mode.
mode_t TargetMode(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) return st.st_mode & 07777;
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return 0666 & ~mask;
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
    if (::access(out.path.c_str(), W_OK) != 0)
      throw IoError(out.path + ": cannot write (" + out.option + "): " + ErrnoText(errno));
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
  WriteOutputStreamed(path, [&text](const OutputSink& sink) { sink(text); });
}

namespace {

// Buffers the sink's text and writes it to `fd` a MiB at a time; the first failure is kept.
class BufferedFd {
 public:
  explicit BufferedFd(int fd) : fd_(fd) { buffer_.reserve(kChunk); }
  void Append(std::string_view text) {
    if (buffer_.empty() && text.size() >= kChunk) {  // a whole document: no copy
      if (err_ == 0) err_ = WriteAll(fd_, text);
      return;
    }
    buffer_.append(text);
    if (buffer_.size() >= kChunk) Flush();
  }
  int Flush() {
    if (err_ == 0) err_ = WriteAll(fd_, buffer_);
    buffer_.clear();
    return err_;
  }

 private:
  static constexpr std::size_t kChunk = std::size_t{1} << 20;
  int fd_;
  int err_ = 0;
  std::string buffer_;
};

// ---- temporary files removed on SIGINT, SIGTERM and SIGHUP
// The paths live in fixed buffers so that the signal handler reads them without allocating.
constexpr int kMaxLiveTemps = 32;
constexpr std::size_t kMaxTempPath = 4096;
char g_live_path[kMaxLiveTemps][kMaxTempPath];
volatile std::sig_atomic_t g_live_used[kMaxLiveTemps];

extern "C" void RemoveTemporariesAndReraise(int sig) {
  for (int i = 0; i < kMaxLiveTemps; ++i)
    if (g_live_used[i]) ::unlink(g_live_path[i]);  // async-signal-safe
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

// Installs the handler once, for the signals whose action is still the default (a handler that
// the program or a library such as MPI installed is left alone).
void InstallTemporaryCleanup() {
  static const bool installed = [] {
    for (const int sig : {SIGINT, SIGTERM, SIGHUP}) {
      struct sigaction old {};
      if (::sigaction(sig, nullptr, &old) != 0 || old.sa_handler != SIG_DFL) continue;
      struct sigaction act {};
      act.sa_handler = RemoveTemporariesAndReraise;
      sigemptyset(&act.sa_mask);
      ::sigaction(sig, &act, nullptr);
    }
    return true;
  }();
  (void)installed;
}

// The slot of a registered temporary path, or -1 (too many or too long: not removed on a signal).
int RegisterTemporary(const std::string& temp) {
  InstallTemporaryCleanup();
  if (temp.size() >= kMaxTempPath) return -1;
  for (int i = 0; i < kMaxLiveTemps; ++i) {
    if (g_live_used[i]) continue;
    std::memcpy(g_live_path[i], temp.c_str(), temp.size() + 1);
    g_live_used[i] = 1;
    return i;
  }
  return -1;
}

void UnregisterTemporary(int slot) {
  if (slot >= 0) g_live_used[slot] = 0;
}

// A written temporary file waiting to be renamed over its path.
struct PendingOutput {
  std::string temp;
  std::string path;
  int slot;
};
// Non-null inside WithOutputsTogether: renames wait for the end of the run.
std::vector<PendingOutput>* g_pending = nullptr;

void DiscardPending(std::vector<PendingOutput>* pending) {
  for (const PendingOutput& p : *pending) {
    ::unlink(p.temp.c_str());
    UnregisterTemporary(p.slot);
  }
  pending->clear();
}

void WriteStreamedAtomically(const std::string& path, const std::function<void(const OutputSink&)>& produce) {
  std::string temp = (fs::path(DirectoryOf(path)) / ("." + fs::path(path).filename().string() + ".tmpXXXXXX")).string();
  const int fd = ::mkstemp(temp.data());
  if (fd < 0)
    throw IoError(path + ": cannot create a temporary file in " + DirectoryOf(path) + ": " + ErrnoText(errno));
  const int slot = RegisterTemporary(temp);
  BufferedFd out(fd);
  try {
    produce([&out](std::string_view text) { out.Append(text); });
  } catch (...) {
    ::close(fd);
    ::unlink(temp.c_str());
    UnregisterTemporary(slot);
    throw;
  }
  int err = out.Flush();
  if (err == 0 && ::fchmod(fd, TargetMode(path)) != 0) err = errno;
  if (err == 0 && ::fsync(fd) != 0) err = errno;
  if (::close(fd) != 0 && err == 0) err = errno;
  if (err == 0 && g_pending != nullptr) {
    g_pending->push_back({temp, path, slot});
    return;
  }
  if (err == 0 && ::rename(temp.c_str(), path.c_str()) != 0) err = errno;
  if (err != 0) ::unlink(temp.c_str());
  UnregisterTemporary(slot);
  if (err != 0) throw IoError(path + ": write failed (the previous file, if any, is unchanged): " + ErrnoText(err));
}

}  // namespace

void WriteOutputStreamed(const std::string& path, const std::function<void(const OutputSink&)>& produce) {
  if (IsStandardOutput(path)) {
    produce([](std::string_view text) { std::cout.write(text.data(), static_cast<std::streamsize>(text.size())); });
    FlushStandardOutput();
  } else if (IsExistingNonRegular(path)) {
    const int fd = ::open(path.c_str(), O_WRONLY | O_TRUNC | O_CLOEXEC);
    if (fd < 0) throw IoError(path + ": cannot open for writing: " + ErrnoText(errno));
    BufferedFd out(fd);
    try {
      produce([&out](std::string_view text) { out.Append(text); });
    } catch (...) {
      ::close(fd);
      throw;
    }
    const int err = out.Flush();
    const int close_err = ::close(fd) == 0 ? 0 : errno;
    if (err != 0 || close_err != 0) throw IoError(path + ": write failed: " + ErrnoText(err != 0 ? err : close_err));
  } else {
    WriteStreamedAtomically(path, produce);
  }
}

int WithOutputsTogether(const std::function<int()>& run) {
  if (g_pending != nullptr) return run();  // nested: the outer call puts the outputs in place
  std::vector<PendingOutput> pending;
  g_pending = &pending;
  int code = 0;
  try {
    code = run();
  } catch (...) {
    g_pending = nullptr;
    DiscardPending(&pending);
    throw;
  }
  g_pending = nullptr;
  for (std::size_t i = 0; i < pending.size(); ++i) {
    if (::rename(pending[i].temp.c_str(), pending[i].path.c_str()) == 0) {
      UnregisterTemporary(pending[i].slot);
      continue;
    }
    const int err = errno;
    std::vector<PendingOutput> rest(pending.begin() + static_cast<std::ptrdiff_t>(i), pending.end());
    DiscardPending(&rest);
    throw IoError(pending[i].path + ": write failed (the previous file, if any, is unchanged): " + ErrnoText(err));
  }
  return code;
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
        ThrowInvalidInput(CommandLineField(b.option + " and " + a.option),
                          a.path,
                          std::string("two outputs name the same ") + (both_stdout ? "standard output" : "file"));
    }
    if (a.path == "-") continue;
    for (const PathArgument& in : inputs)
      if (!in.path.empty() && in.path != "-" && SameFile(a.path, in.path))
        ThrowInvalidInput(
            CommandLineField(a.option + " and " + in.option), a.path, "the output would overwrite the input file");
  }
  for (const PathArgument& a : outputs)
    if (!IsStandardOutput(a.path)) CheckWritable(a);
}

}  // namespace plateball::tools
