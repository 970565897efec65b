#pragma once

#include <functional>
#include <set>
#include <string>

namespace ply_slam {

// The common shape of the tools' command lines: "--option value" pairs and value-less flags.
// -h / --help prints `usage_text` and exits 0. Each flag goes to on_flag(flag), each pair to
// on_option(option, value); an argument that is neither a flag nor one of `options` gets
// fail("unknown option ARG"), an option without its value fail("missing value after OPTION").
// fail must not return.
struct CommandLine {
  std::string usage_text;
  std::set<std::string> flags;    // take no value
  std::set<std::string> options;  // take a value
  std::function<void(const std::string& flag)> on_flag;
  std::function<void(const std::string& option, const std::string& value)> on_option;
  std::function<void(const std::string& error)> fail;

  void parse(int argc, char** argv) const;
};

// A tool's main after parsing: runs `run`; an exception is reported as "TOOL: what" on stderr
// and gives exit code 1.
int runReportingErrors(const std::string& tool, const std::function<int()>& run);

}  // namespace ply_slam
