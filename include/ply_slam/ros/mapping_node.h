#pragma once

#include <geometry_msgs/PoseStamped.h>
#include <ply_slam/KeyFrameMsg.h>
#include <ply_slam/MapSnapshotMsg.h>
#include <ply_slam/MapUpdateMsg.h>
#include <ply_slam/SaveToPath.h>
#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>

#include <mutex>
#include <optional>
#include <set>
#include <string>

#include "ply_slam/common/message_sequence.h"
#include "ply_slam/common/stamped_pose.h"
#include "ply_slam/dense/dense_mapping_worker.h"
#include "ply_slam/dense/occupancy_grid.h"
#include "ply_slam/dense/occupancy_grid_builder.h"
#include "ply_slam/map/anchored_trajectory.h"
#include "ply_slam/map/map_store.h"
#include "ply_slam/ros/apart_mapping_side.h"
#include "ply_slam/ros/bad_input_log.h"
#include "ply_slam/ros/conversions.h"
#include "ply_slam/ros/mapping_back_end.h"
#include "ply_slam/ros/mapping_node_options.h"

namespace ply_slam {

// ROS glue of the mapping side (DESIGN.md, "ROS interface"): keeps a copy of the map (MapStore),
// shows it (points, lines, keyframes, path, dense cloud, semantic octree), broadcasts tf and saves
// trajectory and maps on request. With ~map_keyframes it maps the jobs of a tracker with
// ~mapping_apart (ApartMappingSide: local BA, culling, loop closure) and its copy is what the
// mapping side made; without, local BA, culling and loop closure run in the tracking process
// (System) and the copy follows the tracker's keyframes and map updates (docs/ARCHITECTURE.md, "Layout"). Its
// main reads the options and builds the back-end (dense maps, grid, the mapping side).
//
// Threads: every subscriber, timer and service runs on ros::spin's one thread; the dense maps
// build on the DenseMappingWorker's own thread behind its own lock (withMaps), the mapping side
// on ApartMappingSide's MappingThread. mutex_ guards what the callbacks share, so a
// multi-threaded spinner would stay correct too.
class MappingNode : private MappedReceiver {
 public:
  MappingNode(ros::NodeHandle nh, ros::NodeHandle pnh, MappingNodeOptions options,
              MappingBackEnd back_end);

 private:
  void keepLoadedMap();
  void onKeyFrame(const ply_slam::KeyFrameMsgConstPtr& msg);
  void onPose(const geometry_msgs::PoseStampedConstPtr& msg);
  void onMapUpdate(const ply_slam::MapUpdateMsgConstPtr& msg);
  // The store and the dense maps take a keyframe and what the mapping side changed.
  void keepKeyFrame(const std::shared_ptr<const KeyFramePacket>& packet);
  void keepMapUpdate(const MapUpdate& update);
  // MappedReceiver: what ApartMappingSide made, into the store and the dense maps.
  void keepMapped(const std::vector<MappedKeyFrame>& mapped) override;
  void keepDenseImages(std::shared_ptr<const KeyFramePacket> packet) override;
  // A gap in the tracker's numbering (`missed` > 0: say so), or the start: ask the tracker for
  // its whole map.
  void onMissed(uint64_t missed, const std::string& what);
  void onMapSnapshot(const ply_slam::MapSnapshotMsgConstPtr& msg);
  // Every frame of `trajectory` hung from the newest keyframe of the store at its stamp.
  void rebuildTrajectory(const Trajectory& trajectory);
  // Why the map or the trajectory is not whole (empty: it is); under mutex_.
  std::string partialReason(bool dense) const;
  // Keyframes of the map now whose images the dense maps never got (loaded from a file, or
  // sent while this node was down); 0 without dense maps. Under mutex_.
  size_t denseMissing() const;
  // Keyframe poses (T_cw) of the store, and kWorld (identity) for frames before any keyframe.
  AnchoredTrajectory::KeyFramePoses anchorPoses() const;
  Trajectory cameraTrajectory() const;
  // Callbacks run one at a time: the longest is how long the tracker's messages may wait.
  void noteCallbackMs(double ms, double cpu_ms) override;  // wall-clock and thread CPU
  bool saveTrajectory(SaveToPath::Request& request, SaveToPath::Response& response);
  bool saveMap(SaveToPath::Request& request, SaveToPath::Response& response);
  // Asks the tracker for the map file in `folder`; throws std::runtime_error saying why not.
  void saveTrackerMap(const std::string& folder);
  void publishMap(const ros::Time& stamp);
  void publishDense(const ros::TimerEvent& event);
  void publishGrid(const ros::TimerEvent& event);
  // The occupancy grid of `octree` (call within dense_->withMaps): built again only when the
  // octree changed since the last call (the floor fit and the cells cost 25-116 ms on an office).
  std::shared_ptr<const OccupancyGrid> gridOf(const SemanticOctree& octree,
                                              const Trajectory& trajectory);
  // The frame the grid is published and saved in (map when the map -> world placement is
  // known, else the world) and where the grid's floor frame lies in it.
  std::string gridFrame(const OccupancyGrid& grid,
                        const std::optional<Eigen::Isometry3d>& T_map_world,
                        Eigen::Isometry3d* T_frame_floor) const;
  void broadcastTf(const ros::Time& stamp, const Eigen::Isometry3d& T_world_camera);

  ros::NodeHandle nh_, pnh_;
  const MappingNodeOptions options_;  // read-only after construction

  // Guards the map's copy and what says how whole it is: store_, camera_trajectory_,
  // map_updates_, loop_updates_, the longest callback times, the two message sequences,
  // resend_requested_, dense_keyframes_ and T_map_world_.
  std::mutex mutex_;
  MapStore store_;
  // Every tracked frame from the tracker's ~pose, hung from the newest keyframe at its arrival
  // (kWorld before the first): map updates move it with the keyframes.
  AnchoredTrajectory camera_trajectory_;
  static constexpr long kWorld = -1;
  size_t map_updates_ = 0, loop_updates_ = 0;
  double longest_callback_ms_ = 0.0, longest_callback_cpu_ms_ = 0.0;
  BadInputLog bad_input_;  // locks itself

  ros::Subscriber keyframe_sub_, pose_sub_, update_sub_, snapshot_sub_;
  ros::ServiceClient resend_client_;
  // tracking_node's ~save_map: without ~map_keyframes the map file that loads again comes from
  // the tracker, which holds the whole map (descriptors, covisibility, place data); MapStore
  // holds less. With it this node owns the map and writes the file itself.
  ros::ServiceClient tracker_save_map_client_;
  ros::WallTimer startup_timer_;
  // Numbering of the tracker's keyframe and map-update messages; missed() counts what the map
  // lacks until a snapshot restores it.
  MessageSequence keyframe_sequence_, update_sequence_;
  bool resend_requested_ = false;
  // Keyframes of the map whose images the dense maps got (erased ones are dropped: denseMissing
  // counts over the store, so only the set's size depends on it).
  std::set<long> dense_keyframes_;
  ros::Publisher points_pub_, lines_pub_, keyframes_pub_, path_pub_;
  ros::ServiceServer save_trajectory_srv_, save_map_srv_;

  // Dense cloud and semantic octree, on their own thread (behind withMaps); null when disabled.
  std::unique_ptr<DenseMappingWorker> dense_;
  ros::Publisher dense_cloud_pub_, octomap_markers_pub_, octomap_cloud_pub_;
  ros::Timer dense_timer_;
  // The 2D occupancy grid from the octree (config's grid section), latched on ~grid_map.
  std::unique_ptr<OccupancyGridBuilder> grid_builder_;  // null: no grid
  // The last grid built, of octree grid_revision_: within dense_->withMaps only (gridOf).
  std::shared_ptr<const OccupancyGrid> grid_;
  std::uint64_t grid_revision_ = 0;
  ros::Publisher grid_pub_;
  ros::Timer grid_timer_;

  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  tf2_ros::StaticTransformBroadcaster static_broadcaster_;
  // Where the SLAM world lies in map: with odometry, the camera's odom pose at the first frame;
  // without, ~world_in_map when given. Under mutex_.
  std::optional<Eigen::Isometry3d> T_map_world_;
  // ~map: T_map_world_ from the saved map's WorldInMapFile, when it has one.
  void placeWorldAsSaved(const std::string& folder);

  // ~map_keyframes (null without): last, so that it stops before what it hands its results to.
  std::unique_ptr<ApartMappingSide> apart_;
};

}  // namespace ply_slam
