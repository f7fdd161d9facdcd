#include "common/errors.h"

#include <exception>

#include "common/exit_codes.h"
#include "common/output_file.h"
#include "plateball/problem_io.h"

namespace plateball::tools {

int ReportCurrentException(const std::string& program, std::ostream& err) {
  try {
    throw;
  } catch (const ProblemFileReadError& e) {
    err << program << ": cannot read: " << e.what() << "\n";
    return kExitIoError;
  } catch (const IoError& e) {
    err << program << ": I/O error: " << e.what() << "\n";
    return kExitIoError;
  } catch (const std::invalid_argument& e) {
    err << program << ": invalid input: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const std::runtime_error& e) {
    err << program << ": computation failed: " << e.what() << "\n";
    return kExitNoSolution;
  } catch (const std::exception& e) {
    err << program << ": internal error (please report): " << e.what() << "\n";
    return kExitInternalError;
  } catch (...) {
    err << program << ": internal error (please report): unknown exception\n";
    return kExitInternalError;
  }
}

int RunWithExitCodes(const std::string& program, const std::function<int()>& run, std::ostream& err) {
  try {
    const int code = run();
    FlushStandardOutput();  // a write error on standard output is an I/O failure (exit code 5)
    return code;
  } catch (...) {
    return ReportCurrentException(program, err);
  }
}

}  // namespace plateball::tools
