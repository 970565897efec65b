#pragma once

#include <stdexcept>

namespace ply_slam {

// A config file that cannot be used: names the file, the key and the fault.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace ply_slam
