#pragma once

#include <functional>
#include <set>
#include <stdexcept>
#include <string>

namespace ply_slam {

// A command line a tool cannot run with; runTool reports it with the usage, exit code 2.
struct UsageError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// The common shape of the tools' command lines: "--option value" pairs, value-less flags and,
// for a tool that takes them, positional arguments. -h / --help prints `usage_text` and exits 0.
// Each flag goes to on_flag(flag), each pair to on_option(option, value), each argument not
// starting with '-' to on_positional(arg) when set. Anything else throws UsageError
// "unknown option ARG" (followed by unknown_hint() when set), an option without its value
// "missing value after OPTION", a flag or option given twice "OPTION is given twice"; the
// handlers throw UsageError for a value they refuse.
struct CommandLine {
  std::string usage_text;
  std::set<std::string> flags;    // take no value
  std::set<std::string> options;  // take a value
  std::function<void(const std::string& flag)> on_flag;
  std::function<void(const std::string& option, const std::string& value)> on_option;
  std::function<void(const std::string& arg)> on_positional;  // unset: none taken
  std::function<std::string()> unknown_hint;                  // unset: none

  void parse(int argc, char** argv) const;
};

// The whole number `text` gives for `option`, within [min, max]; otherwise a UsageError
// "OPTION needs REQUIREMENT, got 'TEXT'", REQUIREMENT by default "a whole number in [MIN, MAX]".
long wholeNumberArgument(const std::string& option, const std::string& text, long min, long max,
                         const std::string& requirement = "");

// A tool's main: `run` parses the command line and does the work. A UsageError is reported as
// "TOOL: what" and `usage_text` on stderr, exit code 2; any other exception as "TOOL: what",
// exit code 1.
int runTool(const std::string& tool, const std::string& usage_text,
            const std::function<int()>& run);

}  // namespace ply_slam
