#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <utility>
#include <vector>

namespace ply_slam {

// Messages numbered 0, 1, 2, ... by their sender, given out strictly in that order: one that
// comes before those numbered below it waits for them. A receiver asks the sender again from
// firstMissing() and, when they never come, gives them up (skipMissing). Each message builds on
// the one before (the mapping side's map updates), so none may be followed out of turn.
template <typename T>
class InOrderQueue {
 public:
  // The sender started anew at `next`: what is numbered below it, waiting or still to come, is
  // dropped. A `next` below the present one is a new sender numbering from there (a restarted
  // one): everything waiting was the old one's.
  void restartAt(uint64_t next) {
    if (next < next_)
      waiting_.clear();
    else
      waiting_.erase(waiting_.begin(), waiting_.lower_bound(next));
    next_ = next;
  }

  // False, and nothing kept: the number was given out or is waiting already (a repeat), or lies
  // below restartAt's.
  bool push(uint64_t number, T value) {
    if (number < next_) return false;
    return waiting_.emplace(number, std::move(value)).second;
  }

  // The run of consecutive numbers from the next one on, in order.
  std::vector<T> takeReady() {
    std::vector<T> ready;
    for (auto it = waiting_.begin(); it != waiting_.end() && it->first == next_;
         it = waiting_.erase(it), ++next_)
      ready.push_back(std::move(it->second));
    return ready;
  }

  // takeReady would give out one at least.
  bool ready() const { return !waiting_.empty() && waiting_.begin()->first == next_; }

  // The next number to give out when a later one waits for it; none when nothing is missing
  // (empty, or the next one is here).
  std::optional<uint64_t> firstMissing() const {
    if (waiting_.empty() || ready()) return std::nullopt;
    return next_;
  }

  // Gives up the numbers missing before the first one waiting; returns how many.
  uint64_t skipMissing() {
    if (waiting_.empty()) return 0;
    const uint64_t skipped = waiting_.begin()->first - next_;
    next_ = waiting_.begin()->first;
    return skipped;
  }

  uint64_t next() const { return next_; }  // the number given out next
  size_t waiting() const { return waiting_.size(); }

 private:
  uint64_t next_ = 0;
  std::map<uint64_t, T> waiting_;
};

}  // namespace ply_slam
