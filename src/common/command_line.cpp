#include "ply_slam/common/command_line.h"

#include <cstdlib>
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

}  // namespace ply_slam
