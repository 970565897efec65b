#include "ply_slam/common/command_line.h"

#include <cstdlib>
#include <exception>
#include <iostream>

namespace ply_slam {

void CommandLine::parse(int argc, char** argv) const {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "-h" || arg == "--help") {
      std::cout << usage_text;
      std::exit(0);
    }
    if (flags.count(arg)) {
      on_flag(arg);
      continue;
    }
    if (!options.count(arg)) fail("unknown option " + arg);
    if (i + 1 >= argc) fail("missing value after " + arg);
    on_option(arg, argv[++i]);
  }
}

int runReportingErrors(const std::string& tool, const std::function<int()>& run) {
  try {
    return run();
  } catch (const std::exception& e) {
    std::cerr << tool << ": " << e.what() << "\n";
    return 1;
  }
}

}  // namespace ply_slam
