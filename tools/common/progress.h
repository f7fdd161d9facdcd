// Progress with an estimated time of arrival on standard error, for every command that can run
// longer than a second, and the --quiet / --progress options of every tool.
//
// When it is shown (docs/command_line.md, "Progress"):
//   default     on a terminal only, and only once the run has taken a second: one line rewritten
//               in place ("plateball simulate: 41% (410000 of 1000000), 3 s elapsed, ETA 4 s"),
//               cleared when the run ends; nothing on a pipe or file, so logs and tests never
//               depend on timing;
//   --progress  also on a pipe or file: a line per second, then a final line
//               "LABEL: done (N of N) in T s" (always printed, so a test can look for it);
//   --quiet     nothing on standard error but errors (also no per-target summary lines).
//
//   Progress progress("plateball reach", targets.size());
//   for (...) { ...; progress.Update(k + 1); }
#pragma once

#include <CLI/CLI.hpp>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <mutex>
#include <string>
#include <thread>

namespace plateball::tools {

enum class ProgressMode { kAuto, kAlways, kQuiet };

/// Adds --quiet and --progress (mutually exclusive) to `app`; they set ProgressSetting(). Nothing
/// when `app` already has a --quiet of its own (a command that reports its progress itself).
void AddProgressOptions(CLI::App& app);
ProgressMode ProgressSetting();
void SetProgressSetting(ProgressMode mode);
/// False under --quiet: informational lines on standard error (summaries) are printed.
bool Verbose();

/// "41% (410 of 1000), 3 s elapsed, ETA 4 s" for `done` of `total` units after `elapsed`
/// seconds; "3 s elapsed" when the total is unknown (0). The ETA assumes the remaining units take
/// as long as the finished ones did on average.
std::string ProgressText(double done, double total, double elapsed);

/// A progress reporter: a background thread prints at most once a second while the object lives.
/// Update() may be called from any thread.
class Progress {
 public:
  /// `total` units of work (0: unknown; the line then shows the elapsed time only).
  Progress(std::string label, double total);
  Progress(std::string label, double total, ProgressMode mode, bool terminal);
  ~Progress();
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  void Update(double done) { done_.store(done); }
  void SetTotal(double total) { total_.store(total); }

 private:
  void Run();
  void Print(bool final_line);
  std::string label_;
  std::atomic<double> done_{0}, total_{0};
  ProgressMode mode_;
  bool terminal_;
  bool printed_ = false;
  std::chrono::steady_clock::time_point start_;
  std::mutex mu_;
  std::condition_variable cv_;
  bool finished_ = false;
  std::thread thread_;
};

}  // namespace plateball::tools
