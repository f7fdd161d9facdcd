#include "common/command_line.h"

#include <cerrno>
#include <cstdlib>
#include <iostream>
#include <stdexcept>

#include "common/exit_codes.h"

namespace plateball::tools {
namespace {

// CLI11 converts an empty string to 0 for numbers: every value must have a non-blank text.
void RejectBlankValues(CLI::App& app) {
  const CLI::Validator non_blank(
      [](std::string& value) {
        return value.find_first_not_of(" \t\n") == std::string::npos
                   ? std::string("value \"" + value + "\": must not be empty")
                   : std::string();
      },
      "");
  for (CLI::Option* option : app.get_options())
    if (option->get_type_size() != 0) option->check(non_blank);
  for (CLI::App* sub : app.get_subcommands({})) RejectBlankValues(*sub);
}

}  // namespace

std::optional<int> ParseCommandLine(CLI::App& app, int argc, char** argv, const std::string& program) {
  RejectBlankValues(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ConversionError& e) {
    // A value of the wrong type ("--mu abc") is bad input, like a bad value in a file.
    std::cerr << program << ": invalid input: command line: " << e.what() << "\n";
    return kExitBadInput;
  } catch (const CLI::ValidationError& e) {
    std::cerr << program << ": invalid input: command line: " << e.what() << "\n";
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
    throw std::invalid_argument("command line: " + option + ": value \"" + shown +
                                "\": must be an integer in [0, 2^64 - 1]");
  }
  return static_cast<std::uint64_t>(v);
}

}  // namespace plateball::tools
