#pragma once

#include <memory>
#include <vector>

#include "ply_slam/map/key_frame.h"
#include "ply_slam/map/map_point.h"
#include "ply_slam/tracking/frame.h"

namespace ply_slam {

// The mapping side as the tracker sees it. The tracker reads the map and never writes to a
// keyframe or a landmark: what it measured goes here, and the mapping side (LandmarkCreator)
// creates, fuses and counts. Called on the tracker's thread with the map's lock held.
class LandmarkSink {
 public:
  virtual ~LandmarkSink() = default;

  // Every frame, tracked or not: the landmarks that were in its view, once per projection pass
  // that found them unoccluded in the frustum (MapPoint::visible).
  virtual void countVisible(const std::vector<MapPoint*>& in_view) = 0;
  // A tracked frame whose outliers are unlinked: its landmarks were found (MapPoint::found,
  // MapLine::found); with `fuse_lines`, its accepted 3D line fits refine the lines they matched.
  virtual void recordTracked(const Frame& frame, bool fuse_lines) = 0;
  // The frame becomes a keyframe: its landmarks gain an observation (and its depths), its other
  // features with depth and its other line fits become landmarks. Afterwards the frame's
  // map_points / map_lines hold them all.
  virtual std::shared_ptr<KeyFrame> addKeyFrame(Frame& frame) = 0;
};

}  // namespace ply_slam
