#pragma once

#include <message_filters/subscriber.h>
#include <message_filters/sync_policies/approximate_time.h>
#include <message_filters/synchronizer.h>
#include <nav_msgs/Path.h>
#include <ply_slam/CameraMsg.h>
#include <ply_slam/HandOverMap.h>
#include <ply_slam/MapForTracker.h>
#include <ply_slam/MapUpdateMsg.h>
#include <ply_slam/SaveToPath.h>
#include <ros/ros.h>
#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>
#include <std_srvs/Trigger.h>
#include <chrono>

#include <atomic>
#include <condition_variable>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <thread>

#include "ply_slam/common/latency_window.h"
#include "ply_slam/ros/bad_input_log.h"
#include "ply_slam/ros/mapper_update_feed.h"
#include "ply_slam/ros/rgbd_message_decoder.h"
#include "ply_slam/ros/tracking_back_end.h"
#include "ply_slam/ros/tracking_node_options.h"
#include "ply_slam/ros/unpaired_images.h"

namespace ply_slam {

// ROS glue of the tracking side (DESIGN.md, "ROS interface"): synchronised RGB + depth (+
// camera_info) -> System::process (tracking and, in line, the mapping side) -> pose, path,
// images, keyframes and what the mapping side changed (~map_update, for mapping_node). Frames are
// tracked on a worker thread in arrival order so the subscribers never block; bad input is
// counted, logged throttled and skipped. With ~map it starts in a saved map (System::loadMap);
// ~save_map writes the map file (System::saveMap). With ~mapping_apart the mapping side runs in
// mapping_node: each keyframe goes out as a job (~mapping_job) and the tracker's copy of the map
// follows the mapping side's updates between two frames (MappingMode::kApart). Its main reads the
// options and builds the back-end (segmenter, how to make the System).
//
// Threads: the spinner (ros::spin, one thread: subscribers, the flush timer, services) and the
// worker (work(): tracking, publishing what tracking made). What both touch is guarded below,
// each by the one lock named beside it; everything else belongs to one of the two threads.
class TrackingNode {
 public:
  TrackingNode(ros::NodeHandle nh, ros::NodeHandle pnh, TrackingNodeOptions options,
               TrackingBackEnd back_end);
  ~TrackingNode();

 private:
  using Image = sensor_msgs::Image;
  using SyncPolicy = message_filters::sync_policies::ApproximateTime<Image, Image>;
  struct Job {
    sensor_msgs::ImageConstPtr rgb, depth;  // null: send the whole map (~resend_map)
    std::function<void()> task;             // set: run this between two frames instead
    ros::WallTime arrival;                  // a frame's: when the pair was complete
  };

  void onImages(const sensor_msgs::ImageConstPtr& rgb, const sensor_msgs::ImageConstPtr& depth);
  void onRgb(const sensor_msgs::ImageConstPtr& rgb);
  void onDepth(const sensor_msgs::ImageConstPtr& depth);
  void flushStalledPair();
  // An image the synchroniser dropped for want of a partner: counted and logged ("unpaired").
  void reportUnpaired(const std::string& what, double stamp);
  void onCameraInfo(const sensor_msgs::CameraInfoConstPtr& info);
  bool onResendMap(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);
  bool onSaveMap(SaveToPath::Request& request, SaveToPath::Response& response);
  // ~mapping_apart: a mapping side that starts or missed jobs asks; if it missed any, the worker
  // sends it the tracker's copy of the map (handOver) before the next frame.
  bool onHandOverMap(HandOverMap::Request& request, HandOverMap::Response& response);
  // Runs `task` on the worker between two frames; its answer, or none after `timeout`.
  using Answer = std::pair<bool, std::string>;
  std::optional<Answer> betweenFrames(std::function<Answer()> task, std::chrono::seconds timeout);
  // The worker's part: updates the mapping side sent before `next_update` are no longer
  // followed, the copy goes out with the snapshot. Answers whether it handed over, and what.
  Answer handOver(uint64_t next_job, uint64_t next_update);
  // ~mapping_apart, at construction: mapping_node's map (mapper_map_) when it is not empty.
  void askMapperForItsMap();
  void enqueue(Job job);
  // Frames that waited longer than ~frame_max_age, from the front (the oldest) of queue_ (under
  // queue_mutex_): dropped, counted and reported.
  void dropStaleFrames(ros::WallTime now);
  void publishSnapshot();
  void publishMapped(const std::vector<MappedKeyFrame>& mapped);
  void work();
  void track(const Image& rgb, const Image& depth, ros::WallTime arrival);
  // The System from the back-end, with camera_info's intrinsics when `info` is calibrated; a
  // System that cannot be made (e.g. ~map does not load) stops the node.
  void startSystem(const sensor_msgs::CameraInfo* info);
  void publish(const Image& rgb, const RgbdImages& images, const std::vector<Instance>& instances,
               const FrameResult& result, ros::WallTime arrival);
  // The segmenter the node has, said once at the start (a warning without one).
  void reportSegmenter() const;
  void publishStats();
  // ~mapping_apart: the mapping side's updates followed (true when any), the tracker's keyframes
  // sent.
  bool followMapper();
  void publishJobs(const ros::Time& stamp);
  // A warning (throttled) when keyframes have been held back for kHeldBackWarning_s.
  void warnWhileHeldBack(double stamp, bool held_back);
  // A warning when tracking is lost, a line when it is found again: never a silent gap.
  void reportTrackingChange(double stamp, bool tracked);
  void addToPath(const geometry_msgs::PoseStamped& pose, const Eigen::Isometry3d& T_wc);
  void sendPath();

  ros::NodeHandle nh_, pnh_;
  const TrackingNodeOptions options_;  // read-only after construction: any thread
  TrackingBackEnd back_end_;           // the worker uses it (segmenter, make_system)

  // Worker thread only.
  size_t mapping_backlog_ = 0;  // keyframes the mapping thread had not finished (last looked)
  // How often the idle worker looks for the mapping thread's results.
  static constexpr std::chrono::milliseconds kMappedPollPeriod{100};
  bool start_failed_ = false;           // the System could not be made: no frame is tracked
  std::vector<MappingJob> outgoing_;    // ~mapping_apart: the frame's keyframe, to send
  double longest_follow_cpu_ms_ = 0.0;  // following the mapping side's updates, between frames
  // ~mapping_apart: the map of a mapping_node that went on while this node restarted, taken over
  // at the first frame (set before the worker starts).
  std::optional<MapHandover> mapper_map_;

  std::unique_ptr<System> system_;  // made at the first frame (intrinsics from camera_info)
  CameraMsg job_camera_;            // system_'s camera; goes with each job (~mapping_apart)
  RgbdMessageDecoder decoder_;
  BadInputLog bad_input_;  // any thread: locks itself

  message_filters::Subscriber<Image> rgb_sub_, depth_sub_;
  std::unique_ptr<message_filters::Synchronizer<SyncPolicy>> sync_;
  ros::Subscriber info_sub_;
  ros::Publisher pose_pub_, path_pub_, keyframe_pub_, map_update_pub_, snapshot_pub_, stats_pub_;
  ros::Publisher job_pub_;  // ~mapping_apart
  ros::ServiceServer resend_srv_, save_map_srv_, hand_over_srv_;
  ros::Publisher tracking_image_pub_, segmentation_image_pub_;
  nav_msgs::Path path_;  // worker thread only, as last_path_pose_ and total_ms_
  Eigen::Isometry3d last_path_pose_ = Eigen::Isometry3d::Identity();
  ros::WallTime path_sent_;   // when ~path went out last; zero: never
  bool path_unsent_ = false;  // poses added since
  static constexpr size_t kMaxPathPoses = 20000;

  // Spinner thread only, down to the unpaired images. The synchroniser emits a pair only once a
  // later message proves no better match can come, so the last pair of a stream (a bag's last
  // frame) would wait for ever. When the stream has been quiet for options_.sync_flush_after the
  // newest unpaired rgb + depth are tracked as a pair.
  sensor_msgs::ImageConstPtr newest_rgb_, newest_depth_;
  ros::WallTime newest_arrival_;
  ros::Time last_paired_rgb_stamp_, last_paired_depth_stamp_;
  ros::WallTimer flush_timer_;
  UnpairedImages unpaired_rgb_, unpaired_depth_;  // sized from the sync queue

  // The newest camera_info: set by the spinner, read by the worker at each frame.
  std::mutex info_mutex_;                        // guards camera_info_
  sensor_msgs::CameraInfoConstPtr camera_info_;  // under info_mutex_

  // The jobs from the spinner to the worker (frames, ~resend_map, ~save_map) and the stop.
  std::mutex queue_mutex_;            // guards queue_ and stopping_
  std::condition_variable queue_cv_;  // queue_ grew or stopping_ was set
  std::deque<Job> queue_;             // under queue_mutex_
  bool stopping_ = false;             // under queue_mutex_
  // ~mapping_apart: the mapping side's updates in order, for the worker (locks itself). After a
  // handover those numbered before the mapping side's next are dropped (restartAt).
  std::unique_ptr<MapperUpdateFeed> mapper_updates_;
  std::thread worker_;

  // Counters for ~stats and the shutdown report (atomic: counted on one thread, read on both);
  // keyframes_ and updates_ also number the keyframe and map-update messages (a mapper finds
  // what it missed from the gaps).
  std::atomic<size_t> rgb_received_{0}, depth_received_{0}, synchronised_{0};
  std::atomic<size_t> flushed_{0}, behind_dropped_{0}, tracked_{0}, lost_{0}, keyframes_{0},
      updates_{0}, loops_{0}, updates_followed_{0}, keyframes_held_back_{0};
  std::vector<double> total_ms_;  // worker thread only
  // Worker thread only: each posed frame's arrival -> ~pose (wall clock) and image stamp ->
  // ~pose (ROS clock: a live camera's, or a bag's with use_sim_time).
  LatencyWindow lag_from_arrival_, lag_from_stamp_;
  std::optional<double> held_back_since_;  // worker thread only: frame stamp (s)
  std::optional<double> lost_since_;       // worker thread only: stamp of the first lost frame
  long lost_in_a_row_ = 0;                 // worker thread only
  static constexpr double kHeldBackWarning_s = 3.0;
};

}  // namespace ply_slam
