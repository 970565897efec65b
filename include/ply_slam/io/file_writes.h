#pragma once

#include <functional>
#include <string>
#include <vector>

namespace ply_slam {

// Several outputs written one after another: one that fails (a full disk, a folder in its
// place) does not keep the others off the disk. Each failure is kept, its message naming the
// file (AtomicFile's errors do).
class FileWrites {
 public:
  // Runs `write`; returns false and keeps the message when it throws.
  bool attempt(const std::function<void()>& write);
  const std::vector<std::string>& failures() const { return failures_; }
  // The failures as one std::runtime_error, when there are any.
  void throwFailures() const;

 private:
  std::vector<std::string> failures_;
};

}  // namespace ply_slam
