#pragma once

#include <opencv2/core.hpp>
#include <set>
#include <vector>

#include "ply_slam/semantic/instance.h"
#include "ply_slam/semantic/mask_carrier.h"

namespace ply_slam {

// A walking person does not stop between two frames, but the evidence does come and go:
// segmenters miss a person now and then (blur, a partial view), and the Delaunay check has
// frames where a walker's few matched features look still (turning, moving along the ray).
// This remembers the instances judged dynamic and follows them for up to `max_frames` frames
// after they were last measured moving:
// - one the segmenter misses is carried to the frame (MaskCarrier), for at most max_frames
//   frames since the segmenter last saw it;
// - one measured moving in at least two frames in a row is presumed dynamic (`presumed()`)
//   in the frames that follow, carried or seen again, until max_frames frames pass without a
//   measurement: a person who stops is judged on their own evidence again after that.
class InstanceMemory {
 public:
  explicit InstanceMemory(int max_frames) : max_frames_(max_frames) {}

  // The frame's instances plus the remembered dynamic ones it lacks (carried to `gray`).
  std::vector<Instance> complete(const std::vector<Instance>& instances, const cv::Mat& gray);
  // Ids, among those complete() returned, of instances to presume dynamic in this frame.
  const std::set<int>& presumed() const { return presumed_ids_; }
  // After the frame was judged: `measured` are the ids the frame's own evidence found moving,
  // `dynamic` those treated as moving (measured or presumed).
  void remember(const std::vector<Instance>& instances, const std::set<int>& measured,
                const std::set<int>& dynamic, const cv::Mat& gray);

 private:
  struct Remembered {
    Instance instance;
    int unseen = 0;      // frames since the segmenter last saw it
    int unmeasured = 0;  // frames since it was last measured moving
    int run = 0;         // frames in a row it was measured moving, up to the last one
  };
  int max_frames_;
  int next_id_ = kFirstCarriedId;
  std::vector<Remembered> remembered_;
  std::vector<Remembered> followed_;  // remembered ones in the frame being judged, by its ids
  std::set<int> presumed_ids_;
  static constexpr int kMinRun = 2;
  cv::Mat gray_;
  MaskCarrier carrier_;
  static constexpr int kFirstCarriedId = 60000;  // above any segmenter's ids
};

}  // namespace ply_slam
