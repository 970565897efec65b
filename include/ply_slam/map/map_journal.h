#pragma once

#include <cstddef>
#include <vector>

namespace ply_slam {

// The changes to who sees what a Map went through, in order, by id (Map::journalTo): replayed
// on another copy of the map (Map::replay) they link, merge and erase there as they did here.
// Values (poses, positions, counts) are not in it: they travel as the values they ended with.
struct MapJournal {
  enum class Change { kAddObservation, kRemoveObservation, kReplace, kErasePoint, kEraseKeyFrame };
  struct Entry {
    Change change = Change::kAddObservation;
    long keyframe = -1;           // add / remove observation, erase keyframe
    long point = -1;              // add observation, erase point; replace: the loser
    long winner = -1;             // replace
    size_t index = 0;             // keypoint: add / remove observation
    int min_point_observers = 0;  // erase keyframe
  };
  std::vector<Entry> entries;
};

}  // namespace ply_slam
