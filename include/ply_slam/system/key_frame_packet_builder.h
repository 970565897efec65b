#pragma once

#include <set>
#include <vector>

#include "ply_slam/io/rgbd_images.h"
#include "ply_slam/map/key_frame.h"
#include "ply_slam/map/key_frame_packet.h"
#include "ply_slam/map/map.h"
#include "ply_slam/semantic/instance.h"

namespace ply_slam {

// The keyframe's pose, features and landmarks as they are now, without images (what a mapper
// that missed the keyframe can still be given).
KeyFramePacket makeSparseKeyFramePacket(const KeyFrame& keyframe, const PinholeCamera& camera);
// So, every keyframe of the map (its lock taken here).
std::vector<KeyFramePacket> sparseKeyFramePackets(const Map& map, const PinholeCamera& camera);

// The instances of an image of `size` as one label image, larger ones drawn first so that a
// smaller one in front keeps its pixels (those in `dynamic_ids` marked dynamic), and the
// dynamic mask (may be empty; shared, not copied).
KeyFrameSegmentation segmentationOf(const std::vector<Instance>& instances,
                                    const std::set<int>& dynamic_ids, const cv::Mat& dynamic_mask,
                                    const cv::Size& size);

// Packs a new keyframe for the mapping side: pose, features, landmarks, the images and the
// segmentation. The packet shares the images and the segmentation's images: pass copies
// nobody else changes (MappingJob's).
KeyFramePacket makeKeyFramePacket(const KeyFrame& keyframe, const PinholeCamera& camera,
                                  const RgbdImages& images,
                                  const KeyFrameSegmentation& segmentation);

}  // namespace ply_slam
