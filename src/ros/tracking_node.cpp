#include "ply_slam/ros/tracking_node.h"

#include <cv_bridge/cv_bridge.h>
#include <geometry_msgs/PoseStamped.h>
#include <ply_slam/KeyFrameMsg.h>
#include <ply_slam/MapSnapshotMsg.h>
#include <std_msgs/String.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <future>
#include <iomanip>
#include <sstream>

#include "ply_slam/common/angles.h"
#include "ply_slam/common/statistics.h"
#include "ply_slam/common/stopwatch.h"
#include "ply_slam/ros/conversions.h"
#include "ply_slam/ros/service_call.h"
#include "ply_slam/ros/split_messages.h"
#include "ply_slam/semantic/segmentation_image.h"
#include "ply_slam/system/tracking_image.h"

namespace ply_slam {
namespace {

// A camera_info whose K is all zero says the camera is not calibrated: the config's
// intrinsics are used.
bool calibrated(const sensor_msgs::CameraInfo& info) { return info.K[0] != 0.0; }

// What cameraFromInfo reads: a camera sends the same with every frame.
bool sameCalibration(const sensor_msgs::CameraInfo& a, const sensor_msgs::CameraInfo& b) {
  return a.K == b.K && a.D == b.D && a.width == b.width && a.height == b.height;
}

}  // namespace

TrackingNode::TrackingNode(ros::NodeHandle nh, ros::NodeHandle pnh, TrackingNodeOptions options,
                           TrackingBackEnd back_end)
    : nh_(nh),
      pnh_(pnh),
      options_(std::move(options)),
      back_end_(std::move(back_end)),
      decoder_(options_.depth_16u_scale),
      unpaired_rgb_(2 * static_cast<size_t>(options_.sync_queue_size)),
      unpaired_depth_(2 * static_cast<size_t>(options_.sync_queue_size)) {
  reportSegmenter();

  pose_pub_ = pnh_.advertise<geometry_msgs::PoseStamped>("pose", 10);
  path_pub_ = pnh_.advertise<nav_msgs::Path>("path", 1, true);
  keyframe_pub_ = pnh_.advertise<KeyFrameMsg>("keyframe", 100);
  map_update_pub_ = pnh_.advertise<MapUpdateMsg>("map_update", 100);
  snapshot_pub_ = pnh_.advertise<MapSnapshotMsg>("map_snapshot", 2);
  resend_srv_ = pnh_.advertiseService("resend_map", &TrackingNode::onResendMap, this);
  save_map_srv_ = pnh_.advertiseService("save_map", &TrackingNode::onSaveMap, this);
  stats_pub_ = pnh_.advertise<std_msgs::String>("stats", 1, true);
  tracking_image_pub_ = pnh_.advertise<sensor_msgs::Image>("tracking_image", 1);
  if (options_.mapping_apart) {
    job_pub_ = pnh_.advertise<MappingJobMsg>("mapping_job", 100);
    // The lock taken before the worker is woken: it cannot be between its check and its wait.
    mapper_updates_ = std::make_unique<MapperUpdateFeed>(
        nh_, pnh_, options_.mapper_update_topic, bad_input_, [this] {
          { std::lock_guard<std::mutex> lock(queue_mutex_); }
          queue_cv_.notify_one();
        });
    // Before hand_over_map is offered: mapping_node cannot be asking it meanwhile (each would
    // wait for the other's single spinner).
    askMapperForItsMap();
    hand_over_srv_ = pnh_.advertiseService("hand_over_map", &TrackingNode::onHandOverMap, this);
  }
  segmentation_image_pub_ = pnh_.advertise<sensor_msgs::Image>("segmentation_image", 1);

  const int sync_queue = options_.sync_queue_size;
  rgb_sub_.subscribe(nh_, options_.rgb_topic, sync_queue);
  depth_sub_.subscribe(nh_, options_.depth_topic, sync_queue);
  rgb_sub_.registerCallback(&TrackingNode::onRgb, this);
  depth_sub_.registerCallback(&TrackingNode::onDepth, this);
  sync_ = std::make_unique<message_filters::Synchronizer<SyncPolicy>>(SyncPolicy(sync_queue),
                                                                      rgb_sub_, depth_sub_);
  sync_->setMaxIntervalDuration(ros::Duration(options_.sync_slop));
  // Without the shortest period the synchroniser waits for the next frame to emit a pair (the
  // last frame of a bag would never be emitted).
  const double min_period = options_.sync_min_period;
  if (min_period > 0) {
    sync_->setInterMessageLowerBound(0, ros::Duration(min_period));
    sync_->setInterMessageLowerBound(1, ros::Duration(min_period));
  }
  sync_->registerCallback(&TrackingNode::onImages, this);
  info_sub_ = nh_.subscribe(options_.camera_info_topic, 1, &TrackingNode::onCameraInfo, this);
  if (options_.sync_flush_after > 0)
    flush_timer_ = nh_.createWallTimer(ros::WallDuration(options_.sync_flush_after / 2),
                                       [this](const ros::WallTimerEvent&) { flushStalledPair(); });
  worker_ = std::thread(&TrackingNode::work, this);
  ROS_INFO_STREAM("tracking_node: config "
                  << options_.config.source_path << ", rgb " << rgb_sub_.getTopic() << ", depth "
                  << depth_sub_.getTopic() << ", camera_info " << info_sub_.getTopic()
                  << (options_.use_camera_info ? "" : " (ignored)") << ", sync queue " << sync_queue
                  << " slop " << options_.sync_slop << " s"
                  << (options_.map.empty()
                          ? std::string()
                          : ", map " + options_.map +
                                (options_.localisation_only ? " (localisation only)"
                                                            : " (extended)")));
}

TrackingNode::~TrackingNode() {
  {
    std::lock_guard<std::mutex> lock(queue_mutex_);
    stopping_ = true;
  }
  queue_cv_.notify_all();
  if (worker_.joinable()) worker_.join();
  const size_t paired = synchronised_;
  ROS_INFO_STREAM("tracking_node: rgb "
                  << rgb_received_ << ", depth " << depth_received_ << ", synchronised " << paired
                  << " (unpaired rgb " << rgb_received_ - std::min<size_t>(rgb_received_, paired)
                  << ", depth " << depth_received_ - std::min<size_t>(depth_received_, paired)
                  << "), tracked " << tracked_ << ", lost " << lost_ << ", dropped while behind "
                  << behind_dropped_ << ", skipped bad " << bad_input_.total() << " ("
                  << bad_input_.summary() << "), median " << median(total_ms_, 0.0)
                  << " ms per frame");
}

void TrackingNode::onRgb(const sensor_msgs::ImageConstPtr& rgb) {
  ++rgb_received_;
  if (const auto given_up = unpaired_rgb_.arrived(rgb->header.stamp.toSec()))
    reportUnpaired("colour", *given_up);
  newest_rgb_ = rgb;
  newest_arrival_ = ros::WallTime::now();
}

void TrackingNode::onDepth(const sensor_msgs::ImageConstPtr& depth) {
  ++depth_received_;
  if (const auto given_up = unpaired_depth_.arrived(depth->header.stamp.toSec()))
    reportUnpaired("depth", *given_up);
  newest_depth_ = depth;
  newest_arrival_ = ros::WallTime::now();
}

void TrackingNode::onImages(const sensor_msgs::ImageConstPtr& rgb,
                            const sensor_msgs::ImageConstPtr& depth) {
  if (!last_paired_rgb_stamp_.isZero() && rgb->header.stamp <= last_paired_rgb_stamp_ &&
      flushed_ > 0)
    return;  // already tracked by flushStalledPair
  for (double stamp : unpaired_rgb_.paired(rgb->header.stamp.toSec()))
    reportUnpaired("colour", stamp);
  for (double stamp : unpaired_depth_.paired(depth->header.stamp.toSec()))
    reportUnpaired("depth", stamp);
  last_paired_rgb_stamp_ = std::max(last_paired_rgb_stamp_, rgb->header.stamp);
  last_paired_depth_stamp_ = std::max(last_paired_depth_stamp_, depth->header.stamp);
  ++synchronised_;
  enqueue({rgb, depth, nullptr, ros::WallTime::now()});
}

void TrackingNode::reportUnpaired(const std::string& what, double stamp) {
  std::ostringstream s;
  s << std::fixed << std::setprecision(6) << what << " image stamped " << stamp << " had no "
    << (what == "colour" ? "depth" : "colour") << " image within " << options_.sync_slop
    << " s; the synchroniser dropped it";
  bad_input_.report("unpaired", s.str());
}

// Runs on the spinner thread like the subscriber callbacks, so it needs no lock of its own.
void TrackingNode::flushStalledPair() {
  if (!newest_rgb_ || !newest_depth_) return;
  if ((ros::WallTime::now() - newest_arrival_).toSec() < options_.sync_flush_after) return;
  if (newest_rgb_->header.stamp <= last_paired_rgb_stamp_ ||
      newest_depth_->header.stamp <= last_paired_depth_stamp_)
    return;
  if (std::abs((newest_rgb_->header.stamp - newest_depth_->header.stamp).toSec()) >
      options_.sync_slop)
    return;
  ++flushed_;
  onImages(newest_rgb_, newest_depth_);
}

// Checked on arrival: a NaN or absurd number in K or D is logged and the camera_info left
// out (the last good one, or the config, stays), never handed to the tracker.
void TrackingNode::onCameraInfo(const sensor_msgs::CameraInfoConstPtr& info) {
  {
    std::lock_guard<std::mutex> lock(info_mutex_);
    if (camera_info_ && sameCalibration(*camera_info_, *info)) {  // checked when it came first
      camera_info_ = info;
      return;
    }
  }
  if (calibrated(*info)) try {
      cameraFromInfo(*info, options_.config.camera);
    } catch (const std::invalid_argument& e) {
      bad_input_.report("camera_info", std::string(e.what()) + "; camera_info ignored");
      return;
    }
  std::lock_guard<std::mutex> lock(info_mutex_);
  camera_info_ = info;
}

// A mapper that missed messages asks for the whole map; the worker sends it between two frames.
bool TrackingNode::onResendMap(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  {
    std::lock_guard<std::mutex> lock(queue_mutex_);
    queue_.push_front({nullptr, nullptr, nullptr, {}});
  }
  queue_cv_.notify_one();
  response.success = true;
  response.message = "the map goes out on " + snapshot_pub_.getTopic() + " before the next frame";
  ROS_INFO_STREAM("resend_map: " << response.message);
  return true;
}

// The map file into request.path (a folder), written by the worker between two frames.
bool TrackingNode::onSaveMap(SaveToPath::Request& request, SaveToPath::Response& response) {
  const std::string folder = request.path;
  const std::optional<Answer> answer = betweenFrames(
      [this, folder]() -> Answer {
        if (!system_) throw std::runtime_error("no map yet: no frame has arrived");
        system_->saveMap(folder);
        return {true, std::to_string(system_->map().numKeyFrames()) + " keyframes, " +
                          std::to_string(system_->map().numMapPoints()) + " points to " +
                          (std::filesystem::path(folder) / System::kMapFileName).string()};
      },
      std::chrono::seconds(60));
  std::tie(response.success, response.message) =
      answer.value_or(Answer{false, "the tracker did not save the map within 60 s"});
  if (response.success)
    ROS_INFO_STREAM("save_map: " << response.message);
  else
    ROS_WARN_STREAM("save_map: " << response.message);
  return true;
}

bool TrackingNode::onHandOverMap(HandOverMap::Request& request, HandOverMap::Response& response) {
  const uint64_t next_job = request.next_job_sequence, next_update = request.next_update_sequence;
  const std::optional<Answer> answer =
      betweenFrames([this, next_job, next_update] { return handOver(next_job, next_update); },
                    std::chrono::seconds(60));
  response.success = answer.has_value();
  response.handing_over = answer && answer->first;
  response.message = answer ? answer->second : "the tracker did not answer within 60 s";
  ROS_INFO_STREAM("hand_over_map: " << response.message);
  return true;
}

TrackingNode::Answer TrackingNode::handOver(uint64_t next_job, uint64_t next_update) {
  if (next_job == keyframes_)
    return {false, "nothing to hand over: every job went to the mapping side (" +
                       std::to_string(next_job) + ")"};
  if (!system_) return {false, "nothing to hand over: no frame has arrived"};
  mapper_updates_->restartAt(next_update);
  MapSnapshot map{system_->sparseKeyFramePackets(), system_->cameraTrajectory(),
                  system_->handOverMap()};
  MapSnapshotMsg snapshot = toMsg(map, options_.world_frame);
  snapshot.header.stamp = ros::Time::now();
  snapshot.next_keyframe_sequence = keyframes_;
  snapshot.next_update_sequence = updates_;
  snapshot.camera = job_camera_;  // the mapping side maps on in them, as with the jobs
  snapshot.config = options_.config.yaml;
  snapshot_pub_.publish(snapshot);
  return {true, "the mapping side expected job " + std::to_string(next_job) + " of " +
                    std::to_string(keyframes_) + ": handed over " +
                    std::to_string(map.keyframes.size()) + " keyframes (" +
                    std::to_string(map.handover.map_file.size() / 1024) + " KiB) on " +
                    snapshot_pub_.getTopic()};
}

std::optional<TrackingNode::Answer> TrackingNode::betweenFrames(std::function<Answer()> task,
                                                                std::chrono::seconds timeout) {
  auto answer = std::make_shared<std::promise<Answer>>();
  std::future<Answer> answered = answer->get_future();
  auto run = [task = std::move(task), answer] {
    try {
      answer->set_value(task());
    } catch (const std::exception& e) {
      answer->set_value({false, e.what()});
    }
  };
  {
    std::lock_guard<std::mutex> lock(queue_mutex_);
    queue_.push_front({nullptr, nullptr, run, {}});
  }
  queue_cv_.notify_one();
  if (answered.wait_for(timeout) != std::future_status::ready) return std::nullopt;
  return answered.get();
}

// Frames wait here for the worker, at most ~frame_max_age: when it falls behind, the oldest go
// (a live camera cannot wait, and a pose that late is of no use to the robot).
void TrackingNode::enqueue(Job job) {
  {
    std::lock_guard<std::mutex> lock(queue_mutex_);
    queue_.push_back(std::move(job));
    dropStaleFrames(ros::WallTime::now());
  }
  queue_cv_.notify_one();
}

void TrackingNode::dropStaleFrames(ros::WallTime now) {
  if (options_.frame_max_age <= 0) return;
  for (auto job = queue_.begin(); job != queue_.end();) {
    if (!job->rgb || (now - job->arrival).toSec() <= options_.frame_max_age) {
      ++job;
      continue;
    }
    job = queue_.erase(job);
    ++behind_dropped_;
    bad_input_.report("behind",
                      "tracking is behind; dropped the oldest waiting frame (older "
                      "than ~frame_max_age " +
                          std::to_string(options_.frame_max_age) + " s)");
  }
}

void TrackingNode::work() {
  while (true) {
    Job job;
    bool idle = false;
    {
      std::unique_lock<std::mutex> lock(queue_mutex_);
      // Between frames the mapping thread's results go out too: a loop closed after the last
      // frame must not wait for the next one.
      idle = !queue_cv_.wait_for(lock, kMappedPollPeriod, [this] {
        return stopping_ || !queue_.empty() ||
               (system_ && mapper_updates_ && mapper_updates_->ready());
      });
      if (stopping_) return;  // shutting down: frames still waiting are not tracked
      dropStaleFrames(ros::WallTime::now());
      idle = idle || queue_.empty();
      if (!idle) {
        job = std::move(queue_.front());
        queue_.pop_front();
      }
    }
    try {
      const bool followed = followMapper();
      if (idle) {
        sendPath();  // the last poses of a stream that stopped
        if (!system_) continue;
        const std::vector<MappedKeyFrame> mapped = system_->takeMapped();
        if (mapped.empty() && system_->mappingBacklog() == mapping_backlog_ && !followed) continue;
        publishMapped(mapped);
      } else if (job.task)
        job.task();
      else if (job.rgb)
        track(*job.rgb, *job.depth, job.arrival);
      else
        publishSnapshot();
    } catch (const BadRgbdMessage& e) {
      bad_input_.report(e.kind(), e.what());
    } catch (const InvalidFrame& e) {
      bad_input_.report("invalid_frame", e.what());
    } catch (const std::exception& e) {  // a segmenter failure
      bad_input_.report("error", e.what());
    }
    publishStats();
  }
}

void TrackingNode::startSystem(const sensor_msgs::CameraInfo* info) {
  PinholeCamera camera = options_.config.camera;
  if (info && calibrated(*info)) {
    camera = cameraFromInfo(*info, camera);
    ROS_INFO_STREAM("intrinsics from camera_info: " << intrinsicsText(camera));
  } else {
    ROS_INFO_STREAM("intrinsics from the config: " << intrinsicsText(camera));
  }
  try {
    system_ = back_end_.make_system(camera, !mapper_map_);
    job_camera_ = toMsg(camera);
    if (options_.mapping_apart)
      system_->setJobSink([this](MappingJob job) { outgoing_.push_back(std::move(job)); });
    if (mapper_map_) {  // a restart: the mapping side's live map, not ~map's file
      system_->takeOverMap(*mapper_map_, !options_.map.empty() && options_.localisation_only);
      mapper_map_.reset();
      ROS_INFO_STREAM("tracking_node: in the mapping side's map: "
                      << system_->map().numKeyFrames() << " keyframes, "
                      << system_->map().numMapPoints() << " points; relocalising");
      return;
    }
  } catch (const std::exception& e) {
    start_failed_ = true;
    ROS_FATAL_STREAM("tracking_node: " << e.what());
    ros::shutdown();
    return;
  }
  if (options_.map.empty()) return;
  ROS_INFO_STREAM("tracking_node: map "
                  << options_.map << " loaded: " << system_->map().numKeyFrames() << " keyframes, "
                  << system_->map().numMapPoints() << " points; relocalising (no pose until then)");
  publishSnapshot();  // mapping_node shows and keeps the loaded map
}

void TrackingNode::track(const Image& rgb, const Image& depth, ros::WallTime arrival) {
  sensor_msgs::CameraInfoConstPtr info;
  if (options_.use_camera_info) {
    std::lock_guard<std::mutex> lock(info_mutex_);
    info = camera_info_;
  }
  const RgbdImages images = decoder_.decode(rgb, depth, info.get());
  if (start_failed_) return;
  if (!system_) startSystem(info.get());
  if (start_failed_) return;
  std::vector<Instance> instances;
  if (back_end_.segmenter) {
    back_end_.segmenter->submit(images);
    instances = back_end_.segmenter->instancesFor(images);
  }
  const FrameResult result = system_->process(images, instances);
  if (total_ms_.size() >= 2000)  // the median is over recent frames; a live run has no end
    total_ms_.erase(total_ms_.begin(), total_ms_.begin() + 1000);
  total_ms_.push_back(result.timing.total_ms);
  reportTrackingChange(images.stamp, result.tracking.state == TrackingState::kOk);
  if (result.tracking.state == TrackingState::kOk)
    ++tracked_;
  else
    ++lost_;
  keyframes_held_back_ += result.tracking.keyframe_held_back;
  warnWhileHeldBack(images.stamp, result.tracking.keyframe_held_back);
  publish(rgb, images, instances, result, arrival);
  publishJobs(rgb.header.stamp);
}

// Holding keyframes back for a moment is how the tracker waits for a busy mapping side; for
// seconds on end, the mapping side is far behind or refuses the jobs, and the map stops growing.
void TrackingNode::warnWhileHeldBack(double stamp, bool held_back) {
  if (!held_back) {
    held_back_since_.reset();
    return;
  }
  if (!held_back_since_) held_back_since_ = stamp;
  if (stamp - *held_back_since_ >= kHeldBackWarning_s)
    ROS_WARN_STREAM_THROTTLE(10, "tracking_node: no new keyframe for "
                                     << stamp - *held_back_since_
                                     << " s: " << system_->mappingBacklog()
                                     << " keyframes wait for mapping_node's answer (is it far "
                                        "behind, or refusing the jobs? see its log)");
}

void TrackingNode::reportTrackingChange(double stamp, bool tracked) {
  if (tracked_ == 0) return;  // before the first pose (relocalising in a loaded map) none was lost
  if (!tracked) {
    if (!lost_since_) {
      ROS_WARN_STREAM("tracking_node: lost at stamp "
                      << std::fixed << std::setprecision(3) << stamp
                      << "; relocalising against the map's keyframes"
                      << (options_.localisation_only && !options_.map.empty()
                              ? " (localisation only: a view the map does not hold stays lost)"
                              : ""));
      lost_since_ = stamp;
      lost_in_a_row_ = 0;
    }
    ++lost_in_a_row_;
    return;
  }
  if (!lost_since_) return;
  ROS_INFO_STREAM("tracking_node: tracking again after " << lost_in_a_row_ << " frame(s), "
                                                         << std::fixed << std::setprecision(2)
                                                         << stamp - *lost_since_ << " s lost");
  lost_since_.reset();
}

// Updates wait for the System (made at the first frame, in the map they build on).
bool TrackingNode::followMapper() {
  if (!system_ || !mapper_updates_) return false;
  const std::vector<MapUpdate> updates = mapper_updates_->takeReady();
  if (updates.empty()) return false;
  const ThreadCpuStopwatch cpu;
  for (const MapUpdate& update : updates) system_->followMapUpdate(update);
  updates_followed_ += updates.size();
  longest_follow_cpu_ms_ = std::max(longest_follow_cpu_ms_, cpu.elapsedMs());
  return true;
}

// A tracker that restarts while mapping_node maps on takes over its map at the first frame; the
// updates it sent before are not followed.
void TrackingNode::askMapperForItsMap() {
  ros::ServiceClient client = nh_.serviceClient<MapForTracker>(options_.mapper_map_service);
  if (!client.exists()) {
    ROS_INFO_STREAM("tracking_node: " << client.getService() << " is not up: a map of its own");
    return;
  }
  MapForTracker ask;
  const std::string why = callService(client, ask, std::chrono::seconds(30));
  if (!why.empty()) {
    ROS_ERROR_STREAM("tracking_node: " << why << "; a map of its own");
    return;
  }
  const MapForTracker::Response& r = ask.response;
  mapper_updates_->restartAt(r.next_update_sequence);
  ROS_INFO_STREAM("tracking_node: " << client.getService() << ": " << r.message);
  if (r.map_file.empty()) return;
  try {
    mapper_map_ = handoverFromFields(r);
  } catch (const std::invalid_argument& e) {
    bad_input_.report("map_for_tracker", std::string(e.what()) + "; a map of its own");
  }
}

void TrackingNode::publishJobs(const ros::Time& stamp) {
  // A mapping_node that starts later takes the tracker's copy over (hand_over_map).
  if (!outgoing_.empty() && job_pub_.getNumSubscribers() == 0) {
    ROS_WARN_STREAM_THROTTLE(10, "tracking_node: no mapping_node takes the keyframes on "
                                     << job_pub_.getTopic()
                                     << ": no local BA, culling or loop closure until one does "
                                        "(mapping.launch; or mapping_apart:=false)");
    system_->forgetUnansweredJobs();  // no answer comes: keyframes are not held back for them
  }
  for (const MappingJob& job : outgoing_) {
    MappingJobMsg msg = toMsg(job, options_.world_frame);
    msg.camera = job_camera_;
    msg.config = options_.config.yaml;  // the mapping side maps with the tracker's settings
    msg.header.stamp = stamp;
    msg.sequence = keyframes_++;
    job_pub_.publish(msg);
  }
  outgoing_.clear();
}

void TrackingNode::publish(const Image& rgb, const RgbdImages& images,
                           const std::vector<Instance>& instances, const FrameResult& result,
                           ros::WallTime arrival) {
  std_msgs::Header header;
  header.stamp = rgb.header.stamp;
  header.frame_id = options_.world_frame;
  if (result.tracking.state == TrackingState::kOk) {
    geometry_msgs::PoseStamped pose;
    pose.header = header;
    pose.pose = toPoseMsg(result.tracking.T_cw.inverse());
    pose_pub_.publish(pose);
    lag_from_arrival_.add((ros::WallTime::now() - arrival).toSec());
    lag_from_stamp_.add((ros::Time::now() - rgb.header.stamp).toSec());
    addToPath(pose, result.tracking.T_cw.inverse());
  }
  sendPath();
  publishMapped(result.mapped);
  if (!options_.publish_images) return;
  std_msgs::Header image_header = rgb.header;
  if (tracking_image_pub_.getNumSubscribers() > 0)
    tracking_image_pub_.publish(
        cv_bridge::CvImage(image_header, "bgr8", drawTrackingImage(images.rgb, result, instances))
            .toImageMsg());
  if (segmentation_image_pub_.getNumSubscribers() > 0)
    segmentation_image_pub_.publish(
        cv_bridge::CvImage(image_header, "bgr8",
                           drawSegmentationImage(images.rgb, instances, result.dynamic_instances))
            .toImageMsg());
}

// The path is for looking at: a pose every few cm or degrees, the most recent kMaxPathPoses of
// them, so that hours of tracking stay a message rviz can draw.
void TrackingNode::addToPath(const geometry_msgs::PoseStamped& pose,
                             const Eigen::Isometry3d& T_wc) {
  const bool moved =
      path_.poses.empty() || (T_wc.translation() - last_path_pose_.translation()).norm() > 0.01 ||
      Eigen::AngleAxisd(T_wc.linear() * last_path_pose_.linear().transpose()).angle() >
          radians(1.0);
  if (!moved) return;
  if (path_.poses.size() >= kMaxPathPoses)
    path_.poses.erase(path_.poses.begin(), path_.poses.begin() + kMaxPathPoses / 2);
  path_.header = pose.header;
  path_.poses.push_back(pose);
  last_path_pose_ = T_wc;
  path_unsent_ = true;
}

// The whole path, at most once per ~path_period: the first poses at once, later ones with the
// first frame (or idle wake-up of the worker) after the period, so the last are not held back.
void TrackingNode::sendPath() {
  const ros::WallTime now = ros::WallTime::now();
  if (!path_unsent_ || (!path_sent_.isZero() && (now - path_sent_).toSec() < options_.path_period))
    return;
  path_pub_.publish(path_);
  path_sent_ = now;
  path_unsent_ = false;
}

// The mapping side's keyframes and map updates, in order (the worker's thread only: it numbers
// them).
void TrackingNode::publishMapped(const std::vector<MappedKeyFrame>& mapped) {
  for (const MappedKeyFrame& m : mapped) {
    if (m.packet) {
      KeyFrameMsg keyframe = toMsg(*m.packet, options_.world_frame);
      keyframe.sequence = keyframes_++;
      keyframe_pub_.publish(keyframe);
    }
    MapUpdateMsg update = toMsg(*m.map_update, options_.world_frame);
    update.sequence = updates_++;
    map_update_pub_.publish(update);
    loops_ += m.loop_correction != nullptr;
  }
}

void TrackingNode::publishSnapshot() {
  MapSnapshot map;
  if (system_) map = {system_->sparseKeyFramePackets(), system_->cameraTrajectory(), {}};
  MapSnapshotMsg snapshot = toMsg(map, options_.world_frame);
  snapshot.header.stamp = ros::Time::now();
  snapshot.next_keyframe_sequence = keyframes_;
  snapshot.next_update_sequence = updates_;
  snapshot_pub_.publish(snapshot);
  ROS_INFO_STREAM("resend_map: sent " << snapshot.keyframes.size() << " keyframes and "
                                      << snapshot.trajectory.size() << " poses");
}

void TrackingNode::reportSegmenter() const {
  if (back_end_.segmenter)
    ROS_INFO_STREAM("segmentation: " << back_end_.segmenter->description());
  else
    ROS_WARN(
        "segmentation: none (config segmentation.model is empty; model:=ONNX on the launch "
        "files): moving people are told from the scene by geometry alone");
}

void TrackingNode::publishStats() {
  mapping_backlog_ = system_ ? system_->mappingBacklog() : 0;
  std::ostringstream s;
  s << "rgb_received=" << rgb_received_ << " depth_received=" << depth_received_
    << " synchronised=" << synchronised_ << " flushed=" << flushed_ << " tracked=" << tracked_
    << " lost=" << lost_ << " keyframes=" << keyframes_ << " map_updates=" << updates_
    << " loops=" << loops_ << " mapping_backlog=" << mapping_backlog_
    << " keyframes_held_back=" << keyframes_held_back_ << " updates_followed=" << updates_followed_
    << " updates_asked=" << (mapper_updates_ ? mapper_updates_->asked() : 0)
    << " updates_lost=" << (mapper_updates_ ? mapper_updates_->lost() : 0)
    << " follow_cpu_ms_max=" << longest_follow_cpu_ms_ << " dropped_behind=" << behind_dropped_
    << " skipped_bad=" << bad_input_.total() << " median_ms=" << median(total_ms_, 0.0);
  // Latencies of the posed frames, ms: from the pair's arrival, and from the image stamp.
  for (const auto& [name, lag] :
       {std::pair<const char*, const LatencyWindow*>{"lag_arrival", &lag_from_arrival_},
        {"lag_stamp", &lag_from_stamp_}}) {
    const std::vector<double> p = lag->percentiles({0.5, 0.95});
    s << " " << name << "_ms_p50=" << 1e3 * p[0] << " " << name << "_ms_p95=" << 1e3 * p[1] << " "
      << name << "_ms_max=" << 1e3 * lag->max();
  }
  if (back_end_.segmenter)
    s << " segmented=" << back_end_.segmenter->segmentedFrames()
      << " segment_ms_mean=" << back_end_.segmenter->meanSegmentMs()
      << " mask_age_ms_mean=" << 1e3 * back_end_.segmenter->meanAgeSeconds();
  const std::string kinds = bad_input_.summary();
  if (!kinds.empty()) s << " " << kinds;
  std_msgs::String msg;
  msg.data = s.str();
  stats_pub_.publish(msg);
}

}  // namespace ply_slam
