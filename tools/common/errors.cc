#include "common/errors.h"

#include <exception>

#include "common/exit_codes.h"
#include "common/output_file.h"
#include "plateball/problem_io.h"

namespace plateball::tools {

std::string TerminalSafe(const std::string& text) {
  static const char kHex[] = "0123456789abcdef";
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if ((u < 0x20 && c != '\n' && c != '\t') || u == 0x7f) {
      out += "\\x";
      out += kHex[u >> 4];
      out += kHex[u & 15];
    } else {
      out += c;
    }
  }
  return out;
}

int ReportCurrentException(const std::string& program, std::ostream& err) {
  try {
    throw;
  } catch (const ProblemFileReadError& e) {
    err << program << ": cannot read: " << TerminalSafe(e.what()) << "\n";
    return kExitIoError;
  } catch (const IoError& e) {
    err << program << ": I/O error: " << TerminalSafe(e.what()) << "\n";
    return kExitIoError;
  } catch (const std::invalid_argument& e) {
    err << program << ": invalid input: " << TerminalSafe(e.what()) << "\n";
    return kExitBadInput;
  } catch (const std::runtime_error& e) {
    err << program << ": computation failed: " << TerminalSafe(e.what()) << "\n";
    return kExitNoSolution;
  } catch (const std::exception& e) {
    err << program << ": internal error (please report): " << TerminalSafe(e.what()) << "\n";
    return kExitInternalError;
  } catch (...) {
    err << program << ": internal error (please report): unknown exception\n";
    return kExitInternalError;
  }
}

int RunWithExitCodes(const std::string& program, const std::function<int()>& run, std::ostream& err) {
  try {
    const int code = WithOutputsTogether(run);  // a run's output files are put in place together
    FlushStandardOutput();                      // a write error on standard output is an I/O failure (exit code 5)
    return code;
  } catch (...) {
    return ReportCurrentException(program, err);
  }
}

}  // namespace plateball::tools
