// `plateball`: command-line front end of the library; subcommands live in cmd_*.cc.
#include <CLI/CLI.hpp>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string>

#include "common/command_line.h"
#include "common/command_registry.h"
#include "common/errors.h"
#include "common/exit_codes.h"
#include "common/progress.h"
#include "plateball/version.h"

namespace {

// This process's rank when an MPI starter (mpirun, srun) launched it, from the starter's
// environment; 0 otherwise. Only montecarlo splits its work over ranks: every other subcommand
// runs on rank 0 alone, so that its document is printed and its files written once.
int LauncherRank() {
  for (const char* v : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"})
    if (const char* rank = std::getenv(v)) return std::atoi(rank);
  return 0;
}

}  // namespace

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
  // A first word that names no subcommand is reported as such (CLI11 would say only that a
  // subcommand is required).
  std::string names;
  bool known = false;
  for (const Command& c : Commands()) {
    names += (names.empty() ? "" : ", ") + c.name;
    known = known || (argc >= 2 && c.name == argv[1]);
  }
  if (argc >= 2 && argv[1][0] != '-' && !known) {
    std::cerr << "plateball: command line: SUBCOMMAND: value \"" << TerminalSafe(argv[1])
              << "\": unknown subcommand; one of " << names << "\nRun with --help for more information.\n";
    return kExitUsage;
  }
  // The same for a group's second word (plateball rig export|replay).
  if (argc >= 2 && known) {
    const std::vector<CLI::App*> members = app.get_subcommand(argv[1])->get_subcommands([](CLI::App*) { return true; });
    std::string member_names;
    bool member = false;
    for (const CLI::App* m : members) {
      member_names += (member_names.empty() ? "" : ", ") + m->get_name();
      member = member || (argc >= 3 && m->get_name() == argv[2]);
    }
    if (!members.empty() && !member && (argc < 3 || argv[2][0] != '-')) {
      std::cerr << "plateball " << argv[1] << ": command line: SUBCOMMAND: value \""
                << (argc >= 3 ? TerminalSafe(argv[2]) : std::string()) << "\": unknown subcommand; one of "
                << member_names << "\nRun with --help for more information.\n";
      return kExitUsage;
    }
  }
  if (const auto code = ParseCommandLine(app, argc, argv, "plateball")) return *code;
  for (const auto& [sub, run] : runners) {
    if (sub->parsed() && sub->get_name() != "montecarlo" && LauncherRank() > 0) return kExitSuccess;
    // Failures map to exit codes in one place (common/errors.h) for every tool.
    if (sub->parsed()) return RunWithExitCodes("plateball " + sub->get_name(), run);
  }
  return kExitUsage;
}
