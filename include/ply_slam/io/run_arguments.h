#pragma once

#include <string>

namespace ply_slam {

// The run a sequence tool is asked for: --sequence DIR, --config FILE and --out PATH, all three
// required. Tools' option structs derive from it.
struct RunArguments {
  std::string sequence, config, out;

  // Takes --sequence, --config and --out; returns false for any other option.
  bool take(const std::string& option, const std::string& value);
  // std::invalid_argument when one of the three is missing.
  void require() const;
};

}  // namespace ply_slam
