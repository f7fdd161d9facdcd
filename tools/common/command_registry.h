// Subcommands of the `plateball` tool register themselves here (one file per subcommand).
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>
#include <vector>

namespace plateball::tools {

/// Configures the subcommand's options on `sub` and returns the function that runs it
/// (returning the process exit code, see exit_codes.h).
using CommandSetup = std::function<std::function<int()>(CLI::App& sub)>;

struct Command {
  std::string name;
  std::string description;
  CommandSetup setup;
};

void RegisterCommand(Command command);
const std::vector<Command>& Commands();

/// `static const CommandRegistrar kRegistrar{{"name", "description", setup}};` in a cmd_*.cc.
struct CommandRegistrar {
  explicit CommandRegistrar(Command command) { RegisterCommand(std::move(command)); }
};

}  // namespace plateball::tools
