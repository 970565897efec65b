#pragma once

#include <map>
#include <string>
#include <vector>

#include "ply_slam/common/stamped_pose.h"
#include "ply_slam/map/key_frame_packet.h"

namespace ply_slam {

// The map as the mapping side holds it (mapping_node): keyframes and landmarks from the
// KeyFramePackets the tracker sends, corrected by MapUpdates. A landmark's position is the
// newest one reported. Keyframes are kept without their images (the dense map takes those).
class MapStore {
 public:
  // Adds the keyframe, or replaces one of the same id; returns false for an out-of-date
  // packet (an id already stored with a newer stamp).
  bool insert(const KeyFramePacket& packet);
  void apply(const MapUpdate& update);
  // The tracker's whole map as it is now (after messages were missed): keyframes up to the
  // newest of `keyframes` are exactly those, later ones stay; landmarks are taken again from
  // the keyframes held, the given ones last. Returns the ids erased.
  std::vector<long> restore(const std::vector<KeyFramePacket>& keyframes);

  const std::map<long, KeyFramePacket>& keyFrames() const { return keyframes_; }
  const std::map<long, LandmarkPoint>& points() const { return points_; }
  const std::map<long, LandmarkLine>& lines() const { return lines_; }
  Trajectory keyFrameTrajectory() const;

  // Writes everything it holds into `folder` (created): KeyFrameTrajectory.txt (TUM),
  // map_points.ply, map_lines.ply (segments as edges) and keyframes.csv (id, frame, stamp,
  // features, landmarks, instances). Each file is whole or not there (AtomicFile); every file
  // is tried, then std::runtime_error names each that could not be written.
  void save(const std::string& folder) const;

 private:
  void writePoints(const std::string& path) const;
  void writeLines(const std::string& path) const;
  void writeKeyFrameTable(const std::string& path) const;

  std::map<long, KeyFramePacket> keyframes_;
  std::map<long, LandmarkPoint> points_;
  std::map<long, LandmarkLine> lines_;
};

}  // namespace ply_slam
