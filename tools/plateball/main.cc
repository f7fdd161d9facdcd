// `plateball`: command-line front end of the library; subcommands live in cmd_*.cc.
#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>
#include <map>
#include <stdexcept>

#include "common/command_line.h"
#include "common/command_registry.h"
#include "common/errors.h"
#include "common/exit_codes.h"
#include "common/progress.h"
#include "plateball/version.h"

int main(int argc, char** argv) {
  using namespace plateball::tools;
  CLI::App app{"plateball: impulsive control of a symmetric ball rolling without sliding or spinning"};
  app.set_version_flag("--version", std::string("plateball ") + PLATEBALL_VERSION_STRING);
  app.require_subcommand(1);
  std::map<const CLI::App*, std::function<int()>> runners;
  for (const Command& c : Commands()) {
    CLI::App* sub = app.add_subcommand(c.name, c.description);
    runners[sub] = c.setup(*sub);
    AddProgressOptions(*sub);  // --quiet, --progress on every subcommand (progress.h)
  }
  if (const auto code = ParseCommandLine(app, argc, argv, "plateball")) return *code;
  for (const auto& [sub, run] : runners) {
    // Failures map to exit codes in one place (common/errors.h) for every tool.
    if (sub->parsed()) return RunWithExitCodes("plateball " + sub->get_name(), run);
  }
  return kExitUsage;
}
