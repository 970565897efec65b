#pragma once

#include <message_filters/subscriber.h>
#include <message_filters/sync_policies/approximate_time.h>
#include <message_filters/synchronizer.h>
#include <nav_msgs/Path.h>
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
#include <thread>

#include "ply_slam/ros/bad_input_log.h"
#include "ply_slam/ros/rgbd_message_decoder.h"
#include "ply_slam/ros/unpaired_images.h"
#include "ply_slam/semantic/live_segmenter.h"
#include "ply_slam/system/system.h"

namespace ply_slam {

// ROS glue of the tracking side (DESIGN.md, "ROS interface"): synchronised RGB + depth (+
// camera_info) -> System::process (tracking and, in line, the mapping side) -> pose, path,
// images, keyframes and what the mapping side changed (~map_update, for mapping_node). Frames are
// tracked on a worker thread in arrival order so the subscribers never block; bad input is
// counted, logged throttled and skipped. With ~map it starts in a saved map (System::loadMap);
// ~save_map writes the map file (System::saveMap).
class TrackingNode {
 public:
  TrackingNode(ros::NodeHandle nh, ros::NodeHandle pnh);
  ~TrackingNode();

 private:
  using Image = sensor_msgs::Image;
  using SyncPolicy = message_filters::sync_policies::ApproximateTime<Image, Image>;
  struct Job {
    sensor_msgs::ImageConstPtr rgb, depth;  // null: send the whole map (~resend_map)
    std::function<void()> task;             // set: run this between two frames instead
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
  void enqueue(Job job);
  void publishSnapshot();
  void publishMapped(const std::vector<MappedKeyFrame>& mapped);
  void work();
  void track(const Image& rgb, const Image& depth);
  void startSystem(const sensor_msgs::CameraInfo* info);
  // ~map: the saved map into the new system; a map that cannot be loaded stops the node.
  void loadMap();
  void publish(const Image& rgb, const RgbdImages& images, const std::vector<Instance>& instances,
               const FrameResult& result);
  void publishStats();

  ros::NodeHandle nh_, pnh_;
  SystemConfig config_;
  bool use_camera_info_ = true;
  bool publish_images_ = true;
  std::string world_frame_;
  size_t frame_queue_size_ = 100;
  std::string map_folder_;  // ~map: a saved map to localise in; "" = a new map
  bool localisation_only_ = true;
  bool mapping_thread_ = true;  // the mapping side beside tracking, not after each keyframe
  size_t mapping_backlog_ = 0;  // keyframes the mapping thread had not finished (last looked)
  // How often the idle worker looks for the mapping thread's results.
  static constexpr std::chrono::milliseconds kMappedPollPeriod{100};
  bool map_failed_ = false;  // ~map could not be loaded: no frame is tracked

  std::unique_ptr<System> system_;  // made at the first frame (intrinsics from camera_info)
  std::unique_ptr<LiveSegmenter> segmenter_;  // null: no model configured
  RgbdMessageDecoder decoder_;
  BadInputLog bad_input_;

  message_filters::Subscriber<Image> rgb_sub_, depth_sub_;
  std::unique_ptr<message_filters::Synchronizer<SyncPolicy>> sync_;
  ros::Subscriber info_sub_;
  ros::Publisher pose_pub_, path_pub_, keyframe_pub_, map_update_pub_, snapshot_pub_, stats_pub_;
  ros::ServiceServer resend_srv_, save_map_srv_;
  ros::Publisher tracking_image_pub_, segmentation_image_pub_;
  nav_msgs::Path path_;
  Eigen::Isometry3d last_path_pose_ = Eigen::Isometry3d::Identity();
  static constexpr size_t kMaxPathPoses = 20000;

  // The synchroniser emits a pair only once a later message proves no better match can come,
  // so the last pair of a stream (a bag's last frame) would wait for ever. When the stream has
  // been quiet for flush_after_s_ the newest unpaired rgb + depth are tracked as a pair.
  double sync_slop_ = 0.02, flush_after_s_ = 0.5;
  sensor_msgs::ImageConstPtr newest_rgb_, newest_depth_;
  ros::WallTime newest_arrival_;
  ros::Time last_paired_rgb_stamp_, last_paired_depth_stamp_;
  ros::WallTimer flush_timer_;
  UnpairedImages unpaired_rgb_{20}, unpaired_depth_{20};  // sized from the sync queue

  std::mutex info_mutex_;
  sensor_msgs::CameraInfoConstPtr camera_info_;

  std::mutex queue_mutex_;
  std::condition_variable queue_cv_;
  std::deque<Job> queue_;
  bool stopping_ = false;
  std::thread worker_;

  // Counters for ~stats and the shutdown report; keyframes_ and updates_ also number the
  // keyframe and map-update messages (a mapper finds what it missed from the gaps).
  std::atomic<size_t> rgb_received_{0}, depth_received_{0}, synchronised_{0};
  std::atomic<size_t> flushed_{0}, behind_dropped_{0}, tracked_{0}, lost_{0}, keyframes_{0},
      updates_{0}, loops_{0};
  std::vector<double> total_ms_;  // worker thread only
};

}  // namespace ply_slam
