#include "ply_slam/io/file_writes.h"

#include <exception>
#include <stdexcept>

namespace ply_slam {

bool FileWrites::attempt(const std::function<void()>& write) {
  try {
    write();
    return true;
  } catch (const std::exception& e) {
    failures_.push_back(e.what());
    return false;
  }
}

void FileWrites::throwFailures() const {
  if (failures_.empty()) return;
  std::string all;
  for (const auto& failure : failures_) all += (all.empty() ? "" : "; ") + failure;
  throw std::runtime_error(all);
}

}  // namespace ply_slam
