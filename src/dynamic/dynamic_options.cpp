#include "ply_slam/dynamic/dynamic_options.h"

#include <stdexcept>

namespace ply_slam {

DynamicMode parseDynamicMode(const std::string& mode) {
  DynamicMode value = DynamicMode::kFull;
  if (!valueOf(kDynamicModeWords, mode, value))
    throw std::invalid_argument("dynamic mode '" + mode + "' (off, geometric, semantic or full)");
  return value;
}

}  // namespace ply_slam
