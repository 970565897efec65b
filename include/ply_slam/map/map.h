#pragma once

#include <memory>
#include <mutex>
#include <unordered_map>
#include <vector>

#include "ply_slam/map/key_frame.h"
#include "ply_slam/map/key_frame_packet.h"
#include "ply_slam/map/map_journal.h"
#include "ply_slam/map/map_line.h"
#include "ply_slam/map/map_point.h"

namespace ply_slam {

// The sparse map: keyframes, point and line landmarks. The containers are guarded by their own
// mutex. The keyframes and landmarks in them are guarded by updateMutex(): whoever reads or
// changes them while another thread may hold it (the tracker for one frame, the mapping side
// for each of its steps; see docs/ARCHITECTURE.md, "Threads and locks"). Ceres solves on copies without it.
class Map {
 public:
  // The one lock over keyframes' and landmarks' contents (poses, positions, links). Never taken
  // by Map's own methods, so a holder may call them.
  std::mutex& updateMutex() const { return update_mutex_; }
  std::shared_ptr<KeyFrame> addKeyFrame(std::shared_ptr<KeyFrame> keyframe);
  std::shared_ptr<MapPoint> createMapPoint(const Eigen::Vector3d& position,
                                           const cv::Mat& descriptor, long keyframe_id);
  // A line landmark with world endpoints, seen first by keyframe `keyframe_id`.
  std::shared_ptr<MapLine> createMapLine(const Eigen::Vector3d& start, const Eigen::Vector3d& end,
                                         const cv::Mat& descriptor, long keyframe_id);
  // Links keypoint `index` of `keyframe` to `point` and updates covisibility.
  void addObservation(KeyFrame& keyframe, size_t index, const std::shared_ptr<MapPoint>& point);
  // Unlinks keypoint `index` of `keyframe` from its landmark and updates covisibility.
  void removeObservation(KeyFrame& keyframe, size_t index);
  // Merges `loser` into `winner` (two landmarks found to be one): every keyframe that saw the
  // loser sees the winner instead; the loser turns bad and points to its replacement.
  void replace(const std::shared_ptr<MapPoint>& loser, const std::shared_ptr<MapPoint>& winner);
  // Drops the landmarks marked bad, points and lines, from the containers (keyframes keep
  // null-safe shared_ptrs) and notes their ids for takeRemovedPoints / takeRemovedLines.
  // Returns how many went.
  size_t removeBadLandmarks();
  // The ids of the points / lines removeBadLandmarks dropped since the last call (MapUpdate).
  std::vector<long> takeRemovedPoints();
  std::vector<long> takeRemovedLines();
  // Turns a point bad and unlinks it from every keyframe that saw it, so that covisibility
  // counts only landmarks in use.
  void erasePoint(const std::shared_ptr<MapPoint>& point);
  // Removes a keyframe (a redundant one): unlinks its point and line observations and with them
  // its covisibility links both ways, hands its spanning-tree children to new parents (see
  // reparentChildren), takes it out of the container and marks it bad; it keeps its features
  // for whoever still holds it. Points left with fewer than `min_point_observers` keyframes and
  // lines left with none turn bad. Returns the erased keyframe (the map may have held the last
  // reference: `keyframe` lives as long as what is returned), or nullptr, changing nothing, for
  // the tree's root (the first keyframe) or a keyframe not in the map.
  std::shared_ptr<KeyFrame> eraseKeyFrame(KeyFrame& keyframe, int min_point_observers);

  // Writes every addObservation, removeObservation, replace, erasePoint and eraseKeyFrame that
  // changed something into `journal` as well, until called with nullptr.
  void journalTo(MapJournal* journal);
  // Does here what `journal` says was done to another copy of this map (ids; an entry naming a
  // keyframe or point this map does not hold is left out). Not journaled again.
  void replay(const MapJournal& journal);

  // Follows what the mapping side did to its copy of this map: the links it made for the
  // keyframe it mapped taken, `update`'s journal replayed, then the poses, tree parents and
  // landmark values it carries set, then the landmarks turned bad dropped (removeBadLandmarks).
  // Ids this map does not hold are left out.
  void apply(const MapUpdate& update);

  // A keyframe or landmark made on another copy of the map (LandmarkCreator::replay), its id
  // kept; later ids continue after it.
  void adoptKeyFrame(std::shared_ptr<KeyFrame> keyframe);
  void adoptPoint(std::shared_ptr<MapPoint> point);
  void adoptLine(std::shared_ptr<MapLine> line);

  // Takes a map read from a file (MapFileReader) as it is: ids, links, covisibility and spanning
  // tree kept; the first keyframe is the tree's root. Later ids continue after the largest.
  // Throws std::logic_error when this map is not empty.
  void adopt(std::vector<std::shared_ptr<KeyFrame>> keyframes,
             std::vector<std::shared_ptr<MapPoint>> points,
             std::vector<std::shared_ptr<MapLine>> lines);

  // The ids the next keyframe, point and line get. A map that takes another's over goes on
  // after that one's (continueIdsFrom): ids of what it erased are never given again.
  struct Ids {
    long keyframe = 0, point = 0, line = 0;
  };
  Ids nextIds() const;
  void continueIdsFrom(const Ids& ids);

  std::vector<std::shared_ptr<KeyFrame>> keyFrames() const;
  // The keyframe `id`; null when the map has none (never had it, or erased it).
  std::shared_ptr<KeyFrame> keyFrame(long id) const;
  std::vector<std::shared_ptr<MapPoint>> mapPoints() const;
  size_t numKeyFrames() const;
  size_t numMapPoints() const;
  std::vector<std::shared_ptr<MapLine>> mapLines() const;
  size_t numMapLines() const;

 private:
  void addObservationLocked(KeyFrame& keyframe, size_t index,
                            const std::shared_ptr<MapPoint>& point);
  void removeObservationLocked(KeyFrame& keyframe, size_t index);
  using KeyFramesById = std::unordered_map<long, std::shared_ptr<KeyFrame>>;
  using PointsById = std::unordered_map<long, std::shared_ptr<MapPoint>>;
  using LinesById = std::unordered_map<long, std::shared_ptr<MapLine>>;
  // apply: erases what the update says left the mapping side's map and is still here.
  void eraseGone(const MapUpdate& update, const PointsById& points, const LinesById& lines);
  // replay with the maps' indexes by id made (apply makes them once for several steps).
  void replayLocked(const MapJournal& journal, const KeyFramesById& keyframes,
                    const PointsById& points);
  // apply: the keyframe's point links made exactly `links` (points this map lacks: no link).
  void relinkLocked(const MapUpdate::KeyFrameLinks& links, const KeyFramesById& keyframes,
                    const PointsById& points);
  // replay's link: as addObservationLocked, over whatever link the keyframe holds there.
  void addObservationFollowed(KeyFrame& keyframe, size_t index,
                              const std::shared_ptr<MapPoint>& point);
  void erasePointLocked(MapPoint& point);
  void unlinkLandmarksLocked(KeyFrame& keyframe, int min_point_observers);
  void reparentChildrenLocked(KeyFrame& keyframe);
  void replaceLocked(const std::shared_ptr<MapPoint>& loser,
                     const std::shared_ptr<MapPoint>& winner);
  std::shared_ptr<KeyFrame> eraseKeyFrameLocked(KeyFrame& keyframe, int min_point_observers);
  void note(const MapJournal::Entry& entry);

  mutable std::mutex mutex_;
  mutable std::mutex update_mutex_;
  std::vector<std::shared_ptr<KeyFrame>> keyframes_;
  std::vector<std::shared_ptr<MapPoint>> points_;
  std::vector<std::shared_ptr<MapLine>> lines_;
  std::vector<long> removed_points_;
  std::vector<long> removed_lines_;
  MapJournal* journal_ = nullptr;
  long next_line_id_ = 0;
  long next_point_id_ = 0;
  long next_keyframe_id_ = 0;
};

}  // namespace ply_slam
