// isoparallel_solve: the project's main job, the same code as `plateball isoparallel`
// (tools/common/isoparallel_command.h): the shortest path whose rolling gives a prescribed
// reorientation (section 2.2), and its impulsive approximation (Figure 7).
//
//   isoparallel_solve [PROBLEM.json|-] [problem options] [--goal X,Y] [--goal-orientation JSON]
//                     [--threads N] [--impulses N] [--out plan.json] [--svg figure.svg] [--shooting] [--exact]
//
// With no problem file it solves the built-in Figure 7 problem (problems/figure7.json).
// Exit codes (tools/common/exit_codes.h): 0 solved and planned, 2 usage, 3 bad input,
// 4 no solution (or the impulsive plan failed), 5 I/O error, 6 internal error.
#include <CLI/CLI.hpp>
#include <string>

#include "common/command_line.h"
#include "common/errors.h"
#include "common/isoparallel_command.h"
#include "common/progress.h"
#include "plateball/version.h"

int main(int argc, char** argv) {
  using namespace plateball::tools;
  CLI::App app{
      "isoparallel_solve: shortest path on the plate whose rolling gives a prescribed reorientation "
      "(section 2.2), and its impulsive approximation (Figure 7); the same as `plateball isoparallel`, "
      "with the report on standard output"};
  app.set_version_flag("--version", std::string("isoparallel_solve (plateball) ") + PLATEBALL_VERSION_STRING);
  IsoparallelCliOptions cli;
  cli.program = "isoparallel_solve";
  cli.tool = "isoparallel_solve";
  AddIsoparallelOptions(app, cli);
  AddProgressOptions(app);  // --quiet, --progress (progress.h; `plateball isoparallel` gets them in main.cc)
  if (const auto code = ParseCommandLine(app, argc, argv, "isoparallel_solve")) return *code;
  // Failures read as in the `plateball` CLI (errors.h): 3 bad input, 4 computation failed,
  // 5 unreadable/unwritable file, 6 internal error.
  return RunWithExitCodes("isoparallel_solve", [&] { return RunIsoparallel(cli); });
}
