// The isoparallel command (section 2.2 and Figure 7): one implementation behind two entry points,
// `isoparallel_solve` (the tool name users were promised: a report on standard output, the JSON
// with --out) and `plateball isoparallel` (JSON on standard output or --out, the report on
// standard error). Both take the same options: the problem options of problem_options.h, the
// isoparallel overrides (--start, --goal, --start-orientation, --goal-orientation, --starts,
// --threads), --impulses, --out, --svg, --shooting, --exact, --certify (with --certify-cap or
// --certify-length, and --certify-budget).
#pragma once

#include <CLI/CLI.hpp>
#include <string>

#include "common/actuator_json.h"
#include "common/problem_options.h"

namespace plateball::tools {

struct IsoparallelCliOptions {
  std::string program;          ///< message prefix: "isoparallel_solve" or "plateball isoparallel"
  std::string tool;             ///< the output header's tool: "isoparallel_solve" or "plateball"
  bool json_to_stdout = false;  ///< plateball isoparallel: the JSON on standard output unless --out
  ProblemOptions problem;       ///< without a file: the built-in Figure 7 problem
  long long impulses = 0;
  CLI::Option* impulses_opt = nullptr;
  std::string out, svg;
  bool shooting = false;
  bool exact = false;    ///< exact arrival along the optimal path (exact_arrival.h)
  bool certify = false;  ///< certify the solution list up to certify_cap (isoparallel_certificate.h)
  double certify_cap = 1.0;
  double certify_length = 0.0;  ///< with certify_length_given: this length cap instead of certify_cap x the shortest
  bool certify_length_given = false;  ///< --certify-length was given (any value, 0 included, is then checked)
  long long certify_budget = 250000000;
  ActuatorOptions actuator;  ///< the actuator's records of the plan's and exact arrival's impulses (JSON only)
};

/// Adds the options above to `app` (set program, tool and json_to_stdout first).
void AddIsoparallelOptions(CLI::App& app, IsoparallelCliOptions& cli);

/// Solves, plans, writes; returns the exit code (0 solved and planned, 4 no solution or the plan
/// failed, 7 a requested certificate did not close). Throws as every subcommand does (errors.h maps the exceptions to
/// exit codes).
int RunIsoparallel(const IsoparallelCliOptions& cli);

}  // namespace plateball::tools
