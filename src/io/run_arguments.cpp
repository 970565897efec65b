#include "ply_slam/io/run_arguments.h"

#include <stdexcept>

namespace ply_slam {

bool RunArguments::take(const std::string& option, const std::string& value) {
  std::string* field = option == "--sequence" ? &sequence
                       : option == "--config" ? &config
                       : option == "--out"    ? &out
                                              : nullptr;
  if (field) *field = value;
  return field != nullptr;
}

void RunArguments::require() const {
  if (sequence.empty() || config.empty() || out.empty())
    throw std::invalid_argument("--sequence, --config and --out are required");
}

}  // namespace ply_slam
