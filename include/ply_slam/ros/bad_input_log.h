#pragma once

#include <map>
#include <mutex>
#include <string>

namespace ply_slam {

// Input the nodes skip (wrong encoding, size, empty, stamp going backwards, ...): counted per
// kind and logged the first time a kind appears, then at most every `period_s` with the
// count since, so a stream of bad messages cannot flood the log.
class BadInputLog {
 public:
  explicit BadInputLog(double period_s = 5.0) : period_s_(period_s) {}

  void report(const std::string& kind, const std::string& what);
  size_t count(const std::string& kind) const;
  size_t total() const;
  std::string summary() const;  // "kind=count kind=count", "" when none

 private:
  struct Kind {
    size_t count = 0;
    size_t count_at_last_log = 0;
    double last_log = -1e18;
  };
  double period_s_;
  mutable std::mutex mutex_;
  std::map<std::string, Kind> kinds_;
};

}  // namespace ply_slam
