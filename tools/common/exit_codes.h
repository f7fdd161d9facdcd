// Exit codes shared by `plateball` and `isoparallel_solve`.
#pragma once

namespace plateball::tools {

enum ExitCode : int {
  kExitSuccess = 0,
  kExitUsage = 2,          ///< bad command line (unknown option, missing argument)
  kExitBadInput = 3,       ///< invalid input value or problem file (message names the field)
  kExitNoSolution = 4,     ///< the solver finished without a usable solution (status reported)
  kExitIoError = 5,        ///< a file could not be read or written
  kExitInternalError = 6,  ///< an unexpected failure (a bug): please report
  kExitNotCertified = 7    ///< isoparallel --certify: the certificate did not close (status reported)
};

}  // namespace plateball::tools
