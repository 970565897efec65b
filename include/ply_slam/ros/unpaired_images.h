#pragma once

#include <cstddef>
#include <deque>
#include <optional>
#include <vector>

namespace ply_slam {

// The images of one stream the synchroniser drops without a word: a colour image whose depth
// image never came within the slop (a driver that lost a frame), or the reverse. Stamps are
// noted on arrival and taken off when a pair uses them; those a pair passed over are unpaired.
class UnpairedImages {
 public:
  // More than `max_waiting` unpaired: the oldest is given up (the synchroniser's queue has
  // dropped it by then), so a dead partner stream cannot make this grow.
  explicit UnpairedImages(size_t max_waiting) : max_waiting_(max_waiting) {}

  // An image arrived; returns the stamp given up, if one was.
  std::optional<double> arrived(double stamp);
  // A pair used the image stamped `stamp`: returns the stamps of the images that arrived before
  // it, older than it and unused (the synchroniser will not pair them now).
  std::vector<double> paired(double stamp);
  size_t waiting() const { return waiting_.size(); }

 private:
  size_t max_waiting_;
  std::deque<double> waiting_;  // in order of arrival
};

}  // namespace ply_slam
