#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/map/key_frame.h"
#include "ply_slam/semantic/instance_box.h"

namespace ply_slam {

// A place-recognition vocabulary a map was built with: its file name (for messages) and what
// identifies its content: the checksum its file ends with (VocabularyFile::checksum) and its
// number of words. Empty (0 words) when the map was built without place recognition.
struct MapVocabulary {
  std::string name;
  uint64_t checksum = 0;
  uint64_t words = 0;

  bool sameContent(const MapVocabulary& other) const {
    return checksum == other.checksum && words == other.words;
  }
};

// What a map's features mean, which the system loading it must share: the camera the pixels
// belong to, the ORB pyramid the levels count in, the vocabularies the place database is built
// with (a loaded map's BoW vectors are recomputed from its descriptors with them).
struct MapFileSetup {
  PinholeCamera camera;  // intrinsics and image size only
  int orb_levels = 0;
  double orb_scale_factor = 0.0;
  MapVocabulary orb_vocabulary, lbd_vocabulary;
};

// What place recognition keeps of a keyframe beyond its ORB features and depths.
struct KeyFramePlace {
  std::vector<uint8_t> used_keypoints;  // per keypoint, 1: in the database (off moving objects)
  cv::Mat lbd_descriptors;              // M x 32 CV_8U: the lines of its image; may be empty
  std::vector<InstanceBox> instances;   // its segmented objects

  // Whether keypoint i is in the database (a keyframe without a record: every one).
  bool uses(size_t i) const { return i >= used_keypoints.size() || used_keypoints[i] != 0; }
};

// A map as a map file holds it, linked as in a Map: keyframes (id order; the first is the
// spanning tree's root) with their features, poses, covisibility and parents, and the point and
// line landmarks with their observations.
struct MapFileContents {
  MapFileSetup setup;
  std::vector<std::shared_ptr<KeyFrame>> keyframes;
  std::vector<std::shared_ptr<MapPoint>> points;
  std::vector<std::shared_ptr<MapLine>> lines;
  std::map<long, KeyFramePlace> places;  // by keyframe id; empty without place recognition
  // The checksum the file ends with: names its content (two processes that each load a map must
  // have loaded the same one).
  uint64_t checksum = 0;
};

}  // namespace ply_slam
