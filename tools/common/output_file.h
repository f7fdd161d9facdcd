// Where the command-line tools write: standard output ("-" or no path) or a file, replaced
// atomically. Output paths are checked before any work is done.
#pragma once

#include <functional>
#include <string>
#include <string_view>
#include <vector>

namespace plateball::tools {

/// True for the path that means standard output: "-" (or an empty path: the option not given).
bool IsStandardOutput(const std::string& path);

/// Writes `text` to standard output (IsStandardOutput) or to the file `path`. A file is written to
/// a temporary file in the same directory and renamed over `path` only when every byte is written,
/// so on any failure (full disk, unwritable directory) the previous file is untouched and no partial
/// file is left. A path that exists and is not a regular file (/dev/null, a FIFO) is written in
/// place. Throws IoError (exit code 5) naming the path, or "standard output".
void WriteOutput(const std::string& path, const std::string& text);

/// Appends text to an output being written (WriteOutputStreamed).
using OutputSink = std::function<void(std::string_view)>;

/// WriteOutput for a large output produced piece by piece (streamed sample tables): `produce`
/// writes through the sink, which buffers 1 MiB at a time, so memory stays flat in the output's
/// size. A file is still written to a temporary file and renamed only when `produce` returns and
/// every byte is written; when `produce` throws, the temporary file is removed and the exception
/// passes on (the previous file is untouched).
void WriteOutputStreamed(const std::string& path, const std::function<void(const OutputSink&)>& produce);

/// Runs `run` with the outputs of WriteOutput and WriteOutputStreamed to files held back: each is
/// written completely to its temporary file, and the renames over the paths wait until `run`
/// returns; then they follow one another (so a run's --out and --svg, or --out and --csv, replace
/// the previous files together: a concurrent reader or writer can only fall between two renames, a
/// window of microseconds, not of the run's duration). When `run` throws, every temporary file is
/// removed and no output is replaced. Temporary files are also removed on SIGINT, SIGTERM and
/// SIGHUP (when the program has no handler of its own for them). RunWithExitCodes calls it.
int WithOutputsTogether(const std::function<int()>& run);

/// Flushes standard output; throws IoError("standard output: write failed") when any write to it
/// failed (a full disk, a closed pipe). RunWithExitCodes calls it after every run.
void FlushStandardOutput();

/// A path given on the command line and the option (or argument) that gave it.
struct PathArgument {
  std::string option;  ///< e.g. "--out", "PROBLEM.json"
  std::string path;    ///< empty: not given
};

/// Checks, before any work, the output paths of a run: no two outputs name the same file (or both
/// standard output), no output is one of the input files (std::invalid_argument naming both
/// options, exit code 3), and each output file can be created: its directory exists and is
/// writable, or it is an existing writable non-regular file (IoError naming the path, exit code 5).
void CheckOutputPaths(const std::vector<PathArgument>& outputs, const std::vector<PathArgument>& inputs = {});

}  // namespace plateball::tools
