#include "ply_slam/io/earlier_outputs.h"

#include <stdexcept>
#include <system_error>

namespace ply_slam {

std::vector<std::string> removeEarlierOutputs(const std::filesystem::path& folder,
                                              const std::vector<std::string>& names) {
  namespace fs = std::filesystem;
  std::vector<std::string> removed;
  for (const std::string& name : names) {
    const fs::path path = folder / name;
    std::error_code error;
    if (!fs::is_regular_file(fs::symlink_status(path, error))) continue;
    if (!fs::remove(path, error) || error)
      throw std::runtime_error("cannot remove " + path.string() +
                               ", an output of an earlier run: " + error.message());
    removed.push_back(name);
  }
  return removed;
}

}  // namespace ply_slam
