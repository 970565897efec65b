#include "ply_slam/ros/mapping_node.h"

#include <geometry_msgs/PoseArray.h>
#include <nav_msgs/Path.h>
#include <ply_slam/MapUpdateMsg.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_srvs/Trigger.h>
#include <visualization_msgs/MarkerArray.h>

#include <algorithm>
#include <filesystem>

#include "ply_slam/common/stopwatch.h"
#include "ply_slam/dense/grid_map_files.h"
#include "ply_slam/dense/grid_renderer.h"
#include "ply_slam/dense/map_export.h"
#include "ply_slam/dense/occupancy_grid_builder.h"
#include "ply_slam/io/file_writes.h"
#include "ply_slam/io/tum_trajectory_file.h"
#include "ply_slam/map/world_in_map_file.h"
#include "ply_slam/ros/conversions.h"
#include "ply_slam/ros/dense_map_messages.h"
#include "ply_slam/ros/grid_map_message.h"
#include "ply_slam/ros/service_call.h"
#include "ply_slam/ros/sparse_map_messages.h"
#include "ply_slam/ros/split_messages.h"
#include "ply_slam/system/key_frame_packet_builder.h"
#include "ply_slam/system/system.h"

namespace ply_slam {

MappingNode::MappingNode(ros::NodeHandle nh, ros::NodeHandle pnh, MappingNodeOptions options,
                         MappingBackEnd back_end)
    : nh_(nh),
      pnh_(pnh),
      options_(std::move(options)),
      dense_(std::move(back_end.dense)),
      grid_builder_(std::move(back_end.grid_builder)),
      tf_listener_(tf_buffer_) {
  if (options_.world_in_map) {
    T_map_world_ = options_.world_in_map;
    static_broadcaster_.sendTransform(
        toTransformMsg(*T_map_world_, ros::Time::now(), options_.map_frame, options_.world_frame));
  }
  // A saved map to localise in: its map frame is the one it was saved in, not where odometry
  // starts today. Until the tracker has relocalised no pose arrives, so no map -> odom either.
  if (!options_.map.empty()) placeWorldAsSaved(options_.map);

  points_pub_ = pnh_.advertise<sensor_msgs::PointCloud2>("map_points", 1, true);
  lines_pub_ = pnh_.advertise<visualization_msgs::MarkerArray>("map_lines", 1, true);
  keyframes_pub_ = pnh_.advertise<geometry_msgs::PoseArray>("keyframes", 1, true);
  path_pub_ = pnh_.advertise<nav_msgs::Path>("path", 1, true);
  // Dense cloud and octree: built on the worker's thread from the keyframes' images, published
  // every ~dense_publish_period seconds.
  if (dense_) {
    dense_cloud_pub_ = pnh_.advertise<sensor_msgs::PointCloud2>("dense_cloud", 1, true);
    octomap_markers_pub_ =
        pnh_.advertise<visualization_msgs::MarkerArray>("octomap_markers", 1, true);
    octomap_cloud_pub_ = pnh_.advertise<sensor_msgs::PointCloud2>("octomap_cloud", 1, true);
    dense_timer_ = nh_.createTimer(ros::Duration(options_.dense_publish_period),
                                   &MappingNode::publishDense, this);
  }
  if (grid_builder_) {
    grid_pub_ = pnh_.advertise<nav_msgs::OccupancyGrid>("grid_map", 1, true);
    grid_timer_ = nh_.createTimer(ros::Duration(options_.grid_publish_period),
                                  &MappingNode::publishGrid, this);
  }

  pose_sub_ = nh_.subscribe(options_.pose_topic, 100, &MappingNode::onPose, this);
  if (back_end.mapping) {
    apart_ = std::make_unique<ApartMappingSide>(nh_, pnh_, options_, std::move(back_end.orb_scales),
                                                std::move(back_end.mapping),
                                                static_cast<MappedReceiver&>(*this), bad_input_);
    if (apart_->mapping().loadedMap() != 0) keepLoadedMap();
    snapshot_sub_ =
        nh_.subscribe(options_.map_snapshot_topic, 2, &MappingNode::onMapSnapshot, this);
  } else {
    keyframe_sub_ = nh_.subscribe(options_.keyframe_topic, 100, &MappingNode::onKeyFrame, this);
    update_sub_ = nh_.subscribe(options_.map_update_topic, 100, &MappingNode::onMapUpdate, this);
    snapshot_sub_ =
        nh_.subscribe(options_.map_snapshot_topic, 2, &MappingNode::onMapSnapshot, this);
    resend_client_ = nh_.serviceClient<std_srvs::Trigger>(options_.resend_service);
    // Started after the tracker (a restart): what went by is not known from a gap until the
    // next keyframe, so the map is asked for once at the start (an empty one from a fresh
    // tracker).
    startup_timer_ = nh_.createWallTimer(
        ros::WallDuration(1.0),
        [this](const ros::WallTimerEvent&) {
          if (resend_client_.exists()) onMissed(0, "messages before the start");
        },
        true);
  }
  save_trajectory_srv_ =
      pnh_.advertiseService("save_trajectory", &MappingNode::saveTrajectory, this);
  save_map_srv_ = pnh_.advertiseService("save_map", &MappingNode::saveMap, this);
  tracker_save_map_client_ = nh_.serviceClient<SaveToPath>(options_.tracker_save_map_service);
  ROS_INFO_STREAM("mapping_node: " << (apart_ ? "maps the jobs from " + apart_->jobTopic() +
                                                    ", updates to " + apart_->updateTopic()
                                              : "keyframes from " + keyframe_sub_.getTopic() +
                                                    ", map updates from " + update_sub_.getTopic())
                                   << ", poses from " << pose_sub_.getTopic() << "; tf "
                                   << (options_.odom_frame.empty()
                                           ? options_.world_frame + " -> " + options_.camera_frame
                                           : options_.map_frame + " -> " + options_.odom_frame));
}

// The map the mapping side loaded is this node's copy from the start; the dense maps lack its
// keyframes (a map file holds no images).
void MappingNode::keepLoadedMap() {
  const std::vector<KeyFramePacket> loaded =
      sparseKeyFramePackets(apart_->mapping().map(), options_.config.camera);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    store_.restore(loaded);
  }
  ROS_INFO_STREAM("mapping_node: maps on from " << options_.map << ": " << loaded.size()
                                                << " keyframes");
}

void MappingNode::onKeyFrame(const ply_slam::KeyFrameMsgConstPtr& msg) {
  const Stopwatch watch;
  const ThreadCpuStopwatch cpu;
  KeyFramePacket packet;
  try {
    packet = fromMsg(*msg);
  } catch (const std::exception& e) {
    bad_input_.report("keyframe", e.what());
    return;
  }
  uint64_t missed = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    missed = keyframe_sequence_.receive(msg->sequence);
  }
  keepKeyFrame(std::make_shared<const KeyFramePacket>(std::move(packet)));
  if (missed > 0) onMissed(missed, "keyframe messages");
  publishMap(msg->header.stamp);
  noteCallbackMs(watch.elapsedMs(), cpu.elapsedMs());
}

// The dense maps take the packet's images (the store keeps none); push only queues.
void MappingNode::keepKeyFrame(const std::shared_ptr<const KeyFramePacket>& packet) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!store_.insert(*packet)) {
      bad_input_.report("keyframe", "keyframe " + std::to_string(packet->id) + " is out of date");
      return;
    }
    if (dense_) dense_keyframes_.insert(packet->id);
  }
  if (dense_) dense_->push(packet);
}

void MappingNode::onMapUpdate(const ply_slam::MapUpdateMsgConstPtr& msg) {
  const Stopwatch watch;
  const ThreadCpuStopwatch cpu;
  MapUpdate update;
  try {
    update = fromMsg(*msg);
  } catch (const std::exception& e) {
    bad_input_.report("map_update", e.what());
    return;
  }
  uint64_t missed = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    missed = update_sequence_.receive(msg->sequence);
  }
  keepMapUpdate(update);
  if (missed > 0) onMissed(missed, "map updates");
  publishMap(msg->header.stamp);
  noteCallbackMs(watch.elapsedMs(), cpu.elapsedMs());
}

// What the mapping side changed: frames hanging from erased keyframes move to live ones, then the
// store takes the new poses and landmarks. The dense maps drop the erased keyframes and re-place
// theirs only after a loop closure (a rebuild of the octree is heavy; local BA moves keyframes by
// millimetres).
void MappingNode::keepMapUpdate(const MapUpdate& update) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    AnchoredTrajectory::KeyFramePoses live;
    if (!update.erased_keyframes.empty()) live = anchorPoses();
    for (long id : update.erased_keyframes) {
      live.erase(id);
      dense_keyframes_.erase(id);  // the set stays as large as the map
    }
    for (long id : update.erased_keyframes) {
      const auto erased = store_.keyFrames().find(id);
      if (erased != store_.keyFrames().end())
        camera_trajectory_.reanchor(id, erased->second.T_wc.inverse(), live);
    }
    store_.apply(update);
    ++map_updates_;
    loop_updates_ += update.whole_map;
  }
  if (dense_) dense_->follow(update);
}

// In the order made: what the mapping side made, into the store and the dense maps.
void MappingNode::keepMapped(const std::vector<MappedKeyFrame>& mapped) {
  for (const MappedKeyFrame& m : mapped) {
    if (m.packet) keepKeyFrame(m.packet);
    keepMapUpdate(*m.map_update);
  }
  publishMap(ros::Time::now());
}

void MappingNode::keepDenseImages(std::shared_ptr<const KeyFramePacket> packet) {
  if (!dense_) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    dense_keyframes_.insert(packet->id);
  }
  dense_->push(std::move(packet));
}

void MappingNode::onMissed(uint64_t missed, const std::string& what) {
  if (missed > 0)
    ROS_WARN_STREAM("mapping_node: missed " << missed << " " << what << " from the tracker "
                                            << "(started late or restarted?); asking for its map");
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (resend_requested_) return;
    resend_requested_ = true;
  }
  std_srvs::Trigger trigger;
  const std::string why = callService(resend_client_, trigger, std::chrono::seconds(10));
  if (why.empty()) return;
  ROS_ERROR_STREAM("mapping_node: " << why << ": the map stays partial");
  std::lock_guard<std::mutex> lock(mutex_);
  resend_requested_ = false;
}

// The tracker's whole map: the store and the trajectory become it (what arrived after it was made
// stays); the dense maps drop what the map culled meanwhile and re-place the rest.
void MappingNode::onMapSnapshot(const ply_slam::MapSnapshotMsgConstPtr& msg) {
  MapSnapshot snapshot;
  try {
    snapshot = fromMsg(*msg);
  } catch (const std::exception& e) {
    bad_input_.report("map_snapshot", e.what());
    return;
  }
  // Apart, only a handover asked for counts.
  if (apart_ && !apart_->takeOver(snapshot, *msg)) return;
  const std::vector<KeyFramePacket>& keyframes = snapshot.keyframes;
  Trajectory& poses = snapshot.trajectory;
  MapUpdate placed;
  placed.whole_map = true;
  size_t without_images = 0;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const double last = poses.empty() ? -1.0 : poses.back().stamp;
    for (const StampedPose& later : cameraTrajectory())
      if (later.stamp > last) poses.push_back(later);
    placed.erased_keyframes = store_.restore(keyframes);
    rebuildTrajectory(poses);
    keyframe_sequence_.resynchronise(msg->next_keyframe_sequence);
    update_sequence_.resynchronise(msg->next_update_sequence);
    resend_requested_ = false;
    for (const auto& k : keyframes) placed.keyframes.push_back({k.id, k.T_wc.inverse()});
    for (long id : placed.erased_keyframes) dense_keyframes_.erase(id);
    without_images = denseMissing();
  }
  if (dense_) dense_->follow(placed);
  ROS_INFO_STREAM("mapping_node: map restored from the tracker: "
                  << keyframes.size() << " keyframes, " << poses.size() << " poses"
                  << (without_images ? ", " + std::to_string(without_images) +
                                           " keyframes without images for the dense maps"
                                     : std::string()));
  publishMap(msg->header.stamp);
}

void MappingNode::rebuildTrajectory(const Trajectory& trajectory) {
  camera_trajectory_ = AnchoredTrajectory();
  const auto& keyframes = store_.keyFrames();
  auto next = keyframes.begin();
  long anchor = kWorld;
  Eigen::Isometry3d T_anchor_world = Eigen::Isometry3d::Identity();
  for (const StampedPose& pose : trajectory) {
    for (; next != keyframes.end() && next->second.stamp <= pose.stamp; ++next) {
      anchor = next->first;
      T_anchor_world = next->second.T_wc.inverse();
    }
    camera_trajectory_.add(pose.stamp, anchor, T_anchor_world, pose.T_wc.inverse());
  }
}

std::string MappingNode::partialReason(bool dense) const {
  std::string reason;
  auto add = [&reason](const std::string& part) { reason += (reason.empty() ? "" : "; ") + part; };
  if (keyframe_sequence_.missed() > 0)
    add("missed " + std::to_string(keyframe_sequence_.missed()) + " keyframe messages");
  if (update_sequence_.missed() > 0)
    add("missed " + std::to_string(update_sequence_.missed()) + " map updates");
  const size_t missing = dense ? denseMissing() : 0;
  if (missing > 0)
    add("the dense maps lack " + std::to_string(missing) +
        " keyframes without images (loaded from a map file, or sent while mapping_node was not "
        "running)");
  return reason;
}

size_t MappingNode::denseMissing() const {
  if (!dense_) return 0;
  size_t missing = 0;
  for (const auto& [id, keyframe] : store_.keyFrames()) missing += !dense_keyframes_.count(id);
  return missing;
}

void MappingNode::noteCallbackMs(double ms, double cpu_ms) {
  std::lock_guard<std::mutex> lock(mutex_);
  longest_callback_ms_ = std::max(longest_callback_ms_, ms);
  longest_callback_cpu_ms_ = std::max(longest_callback_cpu_ms_, cpu_ms);
}

AnchoredTrajectory::KeyFramePoses MappingNode::anchorPoses() const {
  AnchoredTrajectory::KeyFramePoses poses{{kWorld, Eigen::Isometry3d::Identity()}};
  for (const auto& [id, kf] : store_.keyFrames()) poses.emplace(id, kf.T_wc.inverse());
  return poses;
}

Trajectory MappingNode::cameraTrajectory() const {
  return camera_trajectory_.trajectory(anchorPoses());
}

void MappingNode::onPose(const geometry_msgs::PoseStampedConstPtr& msg) {
  Eigen::Isometry3d T_world_camera;
  try {
    T_world_camera = fromPoseMsg(msg->pose);
  } catch (const std::exception& e) {
    bad_input_.report("pose", e.what());
    return;
  }
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto& keyframes = store_.keyFrames();
    const long anchor = keyframes.empty() ? kWorld : keyframes.rbegin()->first;
    const Eigen::Isometry3d T_anchor_world = keyframes.empty()
                                                 ? Eigen::Isometry3d::Identity()
                                                 : keyframes.rbegin()->second.T_wc.inverse();
    camera_trajectory_.add(msg->header.stamp.toSec(), anchor, T_anchor_world,
                           T_world_camera.inverse());
  }
  broadcastTf(msg->header.stamp, T_world_camera);
}

void MappingNode::placeWorldAsSaved(const std::string& folder) {
  const std::string path = (std::filesystem::path(folder) / WorldInMapFile::kName).string();
  const std::optional<Eigen::Isometry3d> saved = WorldInMapFile::read(path);
  if (!saved) {
    ROS_INFO_STREAM(path << " does not exist (a map saved offline): its world is placed as "
                            "without a map");
    return;
  }
  T_map_world_ = *saved;
  if (options_.world_frame != options_.map_frame)
    static_broadcaster_.sendTransform(
        toTransformMsg(*T_map_world_, ros::Time::now(), options_.map_frame, options_.world_frame));
  ROS_INFO_STREAM("the map's world placed in " << options_.map_frame << " as saved in " << path);
}

// Without odometry the camera hangs from the world frame. With it (a robot), `map` starts where
// odometry starts: T_map_world is the camera's pose in odom at the first tracked frame (the
// robot's camera mounting comes in through its tf tree), and map -> odom absorbs the drift.
void MappingNode::broadcastTf(const ros::Time& stamp, const Eigen::Isometry3d& T_world_camera) {
  const MappingNodeOptions& o = options_;
  if (o.odom_frame.empty()) {
    tf_broadcaster_.sendTransform(
        toTransformMsg(T_world_camera, stamp, o.world_frame, o.camera_frame));
    return;
  }
  Eigen::Isometry3d T_odom_camera;
  try {
    T_odom_camera =
        fromTransformMsg(tf_buffer_.lookupTransform(o.odom_frame, o.camera_frame, stamp).transform);
  } catch (const tf2::TransformException& e) {
    bad_input_.report("tf", std::string("no odom -> camera transform: ") + e.what());
    return;
  }
  Eigen::Isometry3d T_map_world;
  bool placed_now = false;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    if (!T_map_world_) {
      T_map_world_ = T_odom_camera * T_world_camera.inverse();
      placed_now = true;
    }
    T_map_world = *T_map_world_;
  }
  if (placed_now && o.world_frame != o.map_frame)
    static_broadcaster_.sendTransform(
        toTransformMsg(T_map_world, stamp, o.map_frame, o.world_frame));
  const Eigen::Isometry3d T_map_odom = T_map_world * T_world_camera * T_odom_camera.inverse();
  tf_broadcaster_.sendTransform(toTransformMsg(T_map_odom, stamp, o.map_frame, o.odom_frame));
}

void MappingNode::publishMap(const ros::Time& stamp) {
  std_msgs::Header header;
  header.stamp = stamp;
  header.frame_id = options_.world_frame;
  std::lock_guard<std::mutex> lock(mutex_);
  points_pub_.publish(toMapPointsMsg(store_.points(), header));
  lines_pub_.publish(toMapLinesMsg(store_.lines(), header));
  keyframes_pub_.publish(toKeyFramePosesMsg(store_.keyFrames(), header));
  path_pub_.publish(toKeyFramePathMsg(store_.keyFrames(), header));
}

bool MappingNode::saveTrajectory(SaveToPath::Request& request, SaveToPath::Response& response) {
  std::lock_guard<std::mutex> lock(mutex_);
  try {
    if (camera_trajectory_.size() == 0) throw std::runtime_error("no tracked frame yet");
    writeTumTrajectory(request.path, cameraTrajectory());
    const std::string partial = partialReason(false);
    response.success = partial.empty();
    response.message = (partial.empty() ? "" : "PARTIAL (" + partial + "): ") +
                       std::to_string(camera_trajectory_.size()) + " poses to " + request.path +
                       " (" + std::to_string(map_updates_) + " map updates applied, " +
                       std::to_string(loop_updates_) + " after a loop closure" +
                       (apart_ ? ", " + std::to_string(apart_->loopsClosed()) + " loops closed here"
                               : std::string()) +
                       "; longest keyframe " + "or map-update callback " +
                       std::to_string(longest_callback_ms_) + " ms, " +
                       std::to_string(longest_callback_cpu_ms_) + " ms of CPU)";
  } catch (const std::exception& e) {
    response.success = false;
    response.message = e.what();
  }
  if (response.success)
    ROS_INFO_STREAM("save_trajectory: " << response.message);
  else
    ROS_WARN_STREAM("save_trajectory: " << response.message);
  return true;
}

void MappingNode::publishDense(const ros::TimerEvent&) {
  if (dense_cloud_pub_.getNumSubscribers() + octomap_markers_pub_.getNumSubscribers() +
          octomap_cloud_pub_.getNumSubscribers() ==
      0)
    return;
  std_msgs::Header header;
  header.stamp = ros::Time::now();
  header.frame_id = options_.world_frame;
  // Only the snapshot under the maps' lock (a rebuild replaces the global cloud, never changes
  // it): the worker need not wait while the messages are built.
  const bool want_cloud = dense_cloud_pub_.getNumSubscribers() > 0;
  DenseCloudPtr cloud;
  std::vector<SemanticOctree::Voxel> voxels;
  dense_->withMaps([&](DenseMap& map, const SemanticOctree& octree) {
    if (want_cloud) cloud = map.globalCloud();
    voxels = octree.occupiedVoxels();
  });
  if (cloud) dense_cloud_pub_.publish(toDenseCloudMsg(*cloud, header));
  octomap_markers_pub_.publish(toVoxelMarkers(voxels, header));
  octomap_cloud_pub_.publish(toVoxelCloudMsg(voxels, header));
}

std::shared_ptr<const OccupancyGrid> MappingNode::gridOf(const SemanticOctree& octree,
                                                         const Trajectory& trajectory) {
  if (!grid_ || grid_revision_ != dense_->octreeRevision()) {
    grid_ = std::make_shared<const OccupancyGrid>(grid_builder_->build(octree, trajectory));
    grid_revision_ = dense_->octreeRevision();
  }
  return grid_;
}

std::string MappingNode::gridFrame(const OccupancyGrid& grid,
                                   const std::optional<Eigen::Isometry3d>& T_map_world,
                                   Eigen::Isometry3d* T_frame_floor) const {
  *T_frame_floor = T_map_world ? Eigen::Isometry3d(*T_map_world * grid.floor().T_world_floor)
                               : grid.floor().T_world_floor;
  return T_map_world ? options_.map_frame : options_.world_frame;
}

void MappingNode::publishGrid(const ros::TimerEvent&) {
  Trajectory trajectory;
  std::optional<Eigen::Isometry3d> T_map_world;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    trajectory = cameraTrajectory();
    T_map_world = T_map_world_;
  }
  std::shared_ptr<const OccupancyGrid> grid;
  dense_->withMaps(
      [&](DenseMap&, const SemanticOctree& octree) { grid = gridOf(octree, trajectory); });
  Eigen::Isometry3d T_frame_floor;
  std_msgs::Header header;
  header.stamp = ros::Time::now();
  header.frame_id = gridFrame(*grid, T_map_world, &T_frame_floor);
  grid_pub_.publish(toGridMsg(*grid, T_frame_floor, header));
}

void MappingNode::saveTrackerMap(const std::string& folder) {
  SaveToPath save;
  save.request.path = folder;
  const std::string map_file = (std::filesystem::path(folder) / System::kMapFileName).string();
  // The tracker gives itself 60 s to write the map between two frames, and says so.
  const std::string why = callService(tracker_save_map_client_, save, std::chrono::seconds(90));
  if (!why.empty()) throw FileWriteError(map_file, why);
}

bool MappingNode::saveMap(SaveToPath::Request& request, SaveToPath::Response& response) {
  std::lock_guard<std::mutex> lock(mutex_);
  // Every part is tried; the answer names each file that could not be written.
  FileWrites files;
  files.attempt([&] { store_.save(request.path); });
  // The map file is written by whoever owns the map: this node with ~map_keyframes, else the
  // tracker.
  files.attempt([&] {
    if (apart_)
      apart_->mapping().saveMap(
          (std::filesystem::path(request.path) / System::kMapFileName).string());
    else
      saveTrackerMap(request.path);
  });
  if (T_map_world_)
    files.attempt([&] {
      WorldInMapFile::write((std::filesystem::path(request.path) / WorldInMapFile::kName).string(),
                            *T_map_world_);
    });
  const Trajectory trajectory = cameraTrajectory();
  const std::filesystem::path folder(request.path);
  files.attempt(
      [&] { writeTumTrajectory((folder / "CameraTrajectory.txt").string(), trajectory); });
  // The dense maps and the grid from one state of the octree.
  if (dense_)
    dense_->withMaps([&](DenseMap& map, const SemanticOctree& octree) {
      files.attempt([&] { writeDenseMaps(request.path, map, octree); });
      if (!grid_builder_) return;
      // map.pgm + map.yaml in the frame ~grid_map is published in, grid.png
      const std::shared_ptr<const OccupancyGrid> grid = gridOf(octree, trajectory);
      Eigen::Isometry3d T_frame_floor;
      const std::string frame = gridFrame(*grid, T_map_world_, &T_frame_floor);
      files.attempt([&] { writeGridMap(request.path, *grid, T_frame_floor); });
      files.attempt([&] {
        GridRenderer().write((folder / "grid.png").string(), *grid, trajectory,
                             "occupancy grid (" + frame + ")");
      });
    });
  if (!files.failures().empty()) {
    response.success = false;
    response.message = files.summaryText() + " (" + files.reasonsText() + ")";
  } else {
    const std::string partial = partialReason(true);
    response.success = partial.empty();
    response.message = (partial.empty() ? "" : "PARTIAL (" + partial + "): ") +
                       std::to_string(store_.keyFrames().size()) + " keyframes, " +
                       std::to_string(store_.points().size()) + " points, " +
                       std::to_string(store_.lines().size()) + " lines to " + request.path;
  }
  if (response.success)
    ROS_INFO_STREAM("save_map: " << response.message);
  else
    ROS_WARN_STREAM("save_map: " << response.message);
  return true;
}

}  // namespace ply_slam
