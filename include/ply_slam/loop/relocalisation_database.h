#pragma once

#include <map>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "ply_slam/loop/binary_vocabulary.h"
#include "ply_slam/loop/bow_database.h"
#include "ply_slam/loop/loop_options.h"
#include "ply_slam/map/key_frame.h"
#include "ply_slam/map/key_frame_packet.h"
#include "ply_slam/map/map_file_contents.h"

namespace ply_slam {

// The keyframes' ORB words for relocalisation alone, kept by a tracker whose mapping side (and
// its LoopDetector) runs in another process (MappingMode::kApart). It keeps of each keyframe
// what the mapping side's database keeps of its points (the features off instances of moving
// classes, LoopKeyFrameBuilder) and ranks as LoopDetector::recognise does, so both give the same
// candidates for the same keyframes.
class RelocalisationDatabase {
 public:
  RelocalisationDatabase(BinaryVocabulary orb, const LoopOptions& loop, int mask_dilation_px);
  // Loads the ORB vocabulary `loop` names (vocabularyPath); throws std::runtime_error naming a
  // missing or bad file.
  static RelocalisationDatabase fromOptions(const LoopOptions& loop, int mask_dilation_px);

  // Adds (or replaces) a keyframe with the segmentation it was handed over with.
  void add(const KeyFrame& keyframe, const KeyFrameSegmentation& segmentation);
  // Adds a keyframe of a loaded map with the features its place record keeps, as the mapping
  // side's LoopCloser::addLoadedKeyFrame does.
  void addLoaded(const KeyFrame& keyframe, const KeyFramePlace& place);
  // Forgets a keyframe (erased from the map); unknown ids are ignored.
  void remove(long id);
  // The keyframes whose ORB words an image's descriptors share, most similar first, at most
  // max_results.
  std::vector<long> recognise(const cv::Mat& orb_descriptors, size_t max_results) const;
  // Each keyframe's place record as far as this database knows it: the keypoints it keeps (no
  // lines nor instances: the mapping side's), for a map file of the tracker's copy.
  std::map<long, KeyFramePlace> places() const;
  // The ORB vocabulary as a map file records it.
  const MapVocabulary& orbVocabulary() const { return orb_identity_; }

 private:
  void add(long id, const cv::Mat& descriptors, const std::vector<bool>& kept);

  BinaryVocabulary orb_;
  MapVocabulary orb_identity_;
  BowDatabase database_;
  std::map<long, std::vector<uint8_t>> used_keypoints_;  // by keyframe id
  std::vector<std::string> mover_classes_;
  int mask_dilation_px_;
};

}  // namespace ply_slam
