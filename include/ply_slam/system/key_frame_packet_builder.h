#pragma once

#include <set>
#include <vector>

#include "ply_slam/io/tum_sequence.h"
#include "ply_slam/map/key_frame.h"
#include "ply_slam/map/key_frame_packet.h"
#include "ply_slam/semantic/instance.h"

namespace ply_slam {

// The keyframe's pose, features and landmarks as they are now, without images (what a mapper
// that missed the keyframe can still be given).
KeyFramePacket makeSparseKeyFramePacket(const KeyFrame& keyframe, const PinholeCamera& camera);

// Packs a new keyframe for the mapping side: pose, features, landmarks, the images and the
// segmentation (instances in `dynamic_ids` are marked dynamic; `dynamic_mask` may be empty).
// The packet shares the images and the mask: pass copies nobody else changes (MappingJob's).
KeyFramePacket makeKeyFramePacket(const KeyFrame& keyframe, const PinholeCamera& camera,
                                  const RgbdImages& images, const std::vector<Instance>& instances,
                                  const std::set<int>& dynamic_ids, const cv::Mat& dynamic_mask);

}  // namespace ply_slam
