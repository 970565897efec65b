#pragma once

#include <functional>
#include <memory>

#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/ros/tracking_node_options.h"
#include "ply_slam/semantic/live_segmenter.h"
#include "ply_slam/system/system.h"

namespace ply_slam {

// What tracking_node runs, built by its main from the options and handed to the node, which only
// feeds it frames and publishes what comes out. The System is made at the first frame (the
// intrinsics may come from camera_info), so the node gets how to make it.
struct TrackingBackEnd {
  // The System for `camera`, already in the map of ~map when one is given and `load_map` (not
  // when it takes over a live mapping side's map instead); throws when it cannot be made (e.g.
  // the map does not load).
  using SystemFactory =
      std::function<std::unique_ptr<System>(const PinholeCamera& camera, bool load_map)>;

  std::unique_ptr<LiveSegmenter> segmenter;  // null: the config names no model
  SystemFactory make_system;

  // Live segmentation when the config names a model (the network beside tracking on the newest
  // frame, DESIGN.md); the System as the options say: mapping thread or in line, without a
  // segmenter the dynamic mode that needs none (modeWithoutSegmenter).
  static TrackingBackEnd fromOptions(const TrackingNodeOptions& options);
};

}  // namespace ply_slam
