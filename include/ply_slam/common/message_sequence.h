#pragma once

#include <cstdint>

namespace ply_slam {

// Sequence numbers of one stream of messages (0, 1, 2, ...): tells a receiver what it missed.
class MessageSequence {
 public:
  // Takes message `number`; returns how many were missed just before it (a receiver that starts
  // late misses 0..number-1). A number already seen (a repeat, or out of order) returns 0 and is
  // counted in repeated().
  uint64_t receive(uint64_t number);
  // After the sender has filled the gaps another way: `next` is the number its next message gets
  // (a later one already received keeps its place). Forgets what was missed.
  void resynchronise(uint64_t next);

  uint64_t missed() const { return missed_; }  // since construction or the last resynchronise
  uint64_t repeated() const { return repeated_; }
  uint64_t expected() const { return next_; }

 private:
  uint64_t next_ = 0;
  uint64_t missed_ = 0;
  uint64_t repeated_ = 0;
};

}  // namespace ply_slam
