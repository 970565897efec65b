#include "ply_slam/common/message_sequence.h"

#include <algorithm>

namespace ply_slam {

uint64_t MessageSequence::receive(uint64_t number) {
  if (number < next_) {
    ++repeated_;
    return 0;
  }
  const uint64_t gap = number - next_;
  missed_ += gap;
  next_ = number + 1;
  return gap;
}

void MessageSequence::resynchronise(uint64_t next) {
  next_ = std::max(next_, next);
  missed_ = 0;
}

}  // namespace ply_slam
