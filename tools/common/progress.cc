#include "common/progress.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <sstream>

namespace plateball::tools {
namespace {

ProgressMode g_mode = ProgressMode::kAuto;

std::string Seconds(double s) {
  std::ostringstream os;
  if (s < 10)
    os.precision(2), os << s;
  else
    os << std::llround(s);
  return os.str() + " s";
}

}  // namespace

void AddProgressOptions(CLI::App& app) {
  // A command with its own --quiet reports its progress itself.
  if (app.get_option_no_throw("--quiet") != nullptr) return;
  CLI::Option* quiet = app.add_flag_callback(
      "--quiet,-q",
      [] { SetProgressSetting(ProgressMode::kQuiet); },
      "no progress and no summary lines on standard error (errors only)");
  CLI::Option* progress = app.add_flag_callback(
      "--progress",
      [] { SetProgressSetting(ProgressMode::kAlways); },
      "show the progress (with an ETA) also when standard error is not a terminal, and a final \"done\" line");
  quiet->excludes(progress);
}

ProgressMode ProgressSetting() { return g_mode; }
void SetProgressSetting(ProgressMode mode) { g_mode = mode; }
bool Verbose() { return g_mode != ProgressMode::kQuiet; }

std::string ProgressText(double done, double total, double elapsed) {
  std::ostringstream os;
  if (total > 0) {
    const double fraction = std::clamp(done / total, 0.0, 1.0);
    os << std::llround(100 * fraction) << "% (" << std::llround(done) << " of " << std::llround(total) << "), ";
    os << Seconds(elapsed) << " elapsed";
    if (fraction > 0 && fraction < 1) os << ", ETA " << Seconds(elapsed * (1 - fraction) / fraction);
  } else {
    os << Seconds(elapsed) << " elapsed";
  }
  return os.str();
}

Progress::Progress(std::string label, double total)
    : Progress(std::move(label), total, ProgressSetting(), ::isatty(STDERR_FILENO) == 1) {}

Progress::Progress(std::string label, double total, ProgressMode mode, bool terminal)
    : label_(std::move(label)), mode_(mode), terminal_(terminal), start_(std::chrono::steady_clock::now()) {
  total_.store(total);
  const bool shown = mode_ == ProgressMode::kAlways || (mode_ == ProgressMode::kAuto && terminal_);
  if (shown) thread_ = std::thread([this] { Run(); });
}

Progress::~Progress() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(mu_);
    finished_ = true;
  }
  cv_.notify_all();
  thread_.join();
  if (mode_ == ProgressMode::kAlways) {
    Print(true);
  } else if (printed_) {
    std::cerr << "\r\033[K" << std::flush;  // a terminal's line is cleared at the end
  }
}

void Progress::Run() {
  std::unique_lock<std::mutex> lock(mu_);
  // The first line after one second, then one a second.
  while (!cv_.wait_for(lock, std::chrono::seconds(1), [this] { return finished_; })) Print(false);
}

void Progress::Print(bool final_line) {
  const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  const double total = total_.load();
  std::string text = label_ + ": ";
  if (final_line)
    text += "done" +
            (total > 0 ? " (" + std::to_string(std::llround(total)) + " of " + std::to_string(std::llround(total)) + ")"
                       : std::string()) +
            " in " + Seconds(elapsed);
  else
    text += ProgressText(done_.load(), total, elapsed);
  if (terminal_ && !final_line)
    std::cerr << "\r\033[K" << text << std::flush;
  else
    std::cerr << (terminal_ && printed_ ? "\r\033[K" : "") << text << "\n" << std::flush;
  printed_ = true;
}

}  // namespace plateball::tools
