#include "ply_slam/common/command_line.h"

#include <cstdlib>
#include <exception>
#include <iostream>
#include <optional>

#include "ply_slam/common/number_text.h"

namespace ply_slam {

void CommandLine::parse(int argc, char** argv) const {
  std::set<std::string> given;  // a second value would silently replace the first
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "-h" || arg == "--help") {
      std::cout << usage_text;
      std::exit(0);
    }
    if ((flags.count(arg) || options.count(arg)) && !given.insert(arg).second)
      throw UsageError(arg + " is given twice");
    if (flags.count(arg)) {
      on_flag(arg);
    } else if (options.count(arg)) {
      if (i + 1 >= argc) throw UsageError("missing value after " + arg);
      on_option(arg, argv[++i]);
    } else if (on_positional && (arg.size() < 2 || arg[0] != '-')) {
      on_positional(arg);
    } else {
      throw UsageError("unknown option " + arg + (unknown_hint ? unknown_hint() : ""));
    }
  }
}

long wholeNumberArgument(const std::string& option, const std::string& text, long min, long max,
                         const std::string& requirement) {
  const std::optional<long> value = parseWholeNumber(text, min, max);
  if (value) return *value;
  throw UsageError(option + " needs " +
                   (requirement.empty() ? "a whole number in [" + std::to_string(min) + ", " +
                                              std::to_string(max) + "]"
                                        : requirement) +
                   ", got '" + text + "'");
}

int runTool(const std::string& tool, const std::string& usage_text,
            const std::function<int()>& run) {
  try {
    return run();
  } catch (const UsageError& e) {
    std::cerr << tool << ": " << e.what() << "\n" << usage_text;
    return 2;
  } catch (const std::exception& e) {
    std::cerr << tool << ": " << e.what() << "\n";
    return 1;
  }
}

}  // namespace ply_slam
