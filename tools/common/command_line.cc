#include "common/command_line.h"

#include <cerrno>
#include <cstdlib>
#include <iostream>
#include <stdexcept>

#include "common/exit_codes.h"
#include "common/invalid_input.h"

namespace plateball::tools {
namespace {

// A whole text as a number of the option's type ("FLOAT" or "INT"), or a message.
std::string NumberProblem(const std::string& type, const std::string& value) {
  const std::string shown = value.size() > 40 ? value.substr(0, 40) + "..." : value;
  char* end = nullptr;
  errno = 0;
  if (type == "FLOAT") {
    (void)std::strtod(value.c_str(), &end);
    if (end == value.c_str() || *end != '\0') return "value \"" + shown + "\": must be a number";
  } else if (type == "INT" || type == "UINT") {
    (void)std::strtoll(value.c_str(), &end, 10);
    if (end == value.c_str() || *end != '\0' || errno == ERANGE) return "value \"" + shown + "\": must be an integer";
  }
  return "";
}

// CLI11 converts an empty string to 0 for numbers: every value must have a non-blank text. A
// number that does not read as one is named like any other bad value ("--mu: value "abc": must be
// a number"), in every tool and with the same exit code (3).
void CheckValues(CLI::App& app) {
  for (CLI::Option* option : app.get_options()) {
    if (option->get_type_size() == 0) continue;
    const std::string type = option->get_type_name();
    option->check(CLI::Validator(
        [type](std::string& value) {
          if (value.find_first_not_of(" \t\n") == std::string::npos)
            return std::string("value \"" + value + "\": must not be empty");
          return NumberProblem(type, value);
        },
        ""));
  }
  for (CLI::App* sub : app.get_subcommands({})) CheckValues(*sub);
}

// "plateball simulate" when the error arose in a subcommand, else the program.
std::string ProgramName(const CLI::App& app, const std::string& program) {
  for (const CLI::App* sub : app.get_subcommands())
    if (sub->parsed()) return program + " " + sub->get_name();
  return program;
}

}  // namespace

std::optional<int> ParseCommandLine(CLI::App& app, int argc, char** argv, const std::string& program) {
  CheckValues(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ConversionError& e) {
    // A value of the wrong type ("--mu abc") is bad input, like a bad value in a file.
    std::cerr << ProgramName(app, program) << ": invalid input: command line: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const CLI::ValidationError& e) {
    std::cerr << ProgramName(app, program) << ": invalid input: command line: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? kExitSuccess : kExitUsage;
  }
  return std::nullopt;
}

std::uint64_t ParseSeedOption(const std::string& option, const std::string& text) {
  char* end = nullptr;
  errno = 0;
  const unsigned long long v = std::strtoull(text.c_str(), &end, 10);
  if (text.empty() || text.size() > 20 || text.find_first_not_of("0123456789") != std::string::npos ||
      errno == ERANGE || end != text.c_str() + text.size()) {
    const std::string shown = text.size() > 40 ? text.substr(0, 40) + "..." : text;
    ThrowInvalidInput(CommandLineField(option), "\"" + shown + "\"", "must be an integer in [0, 2^64 - 1]");
  }
  return static_cast<std::uint64_t>(v);
}

}  // namespace plateball::tools
