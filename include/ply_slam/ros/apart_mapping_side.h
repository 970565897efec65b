#pragma once

#include <ply_slam/MapForTracker.h>
#include <ply_slam/MapSnapshotMsg.h>
#include <ply_slam/MapUpdateMsg.h>
#include <ply_slam/MappingJobMsg.h>
#include <ros/ros.h>
#include <std_msgs/UInt64.h>

#include <deque>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "ply_slam/common/message_sequence.h"
#include "ply_slam/ros/bad_input_log.h"
#include "ply_slam/ros/conversions.h"
#include "ply_slam/ros/mapping_node_options.h"
#include "ply_slam/system/mapping_side.h"
#include "ply_slam/system/mapping_thread.h"

namespace ply_slam {

// What mapping_node does with what the mapping side made: its copy of the map (shown, saved)
// and the dense maps.
class MappedReceiver {
 public:
  virtual ~MappedReceiver() = default;
  virtual void keepMapped(const std::vector<MappedKeyFrame>& mapped) = 0;  // in the order made
  // A keyframe whose images came with a job the map already held (a handover's).
  virtual void keepDenseImages(std::shared_ptr<const KeyFramePacket> packet) = 0;
  virtual void noteCallbackMs(double ms, double cpu_ms) = 0;  // wall-clock and thread CPU
};

// mapping_node's mapping side for a tracker apart (~map_keyframes, tracking_node ~mapping_apart):
// the tracker's jobs in (numbered), mapped on a MappingThread, each update out to the tracker
// (numbered too) and to the receiver. A job missed, or 2 s without jobs, asks the tracker to hand
// over its copy of the map (~hand_over_service), from which a fresh mapping side goes on; jobs
// coming meanwhile are held. A tracker that starts gets this side's map (~map_for_tracker); one
// that missed updates asks for them again (~updates_wanted_topic), sent from the updates kept.
//
// Threads: everything here runs on mapping_node's spinner; the mapping side on the MappingThread.
class ApartMappingSide {
 public:
  ApartMappingSide(ros::NodeHandle nh, ros::NodeHandle pnh, const MappingNodeOptions& options,
                   std::shared_ptr<const std::vector<double>> orb_scales,
                   std::unique_ptr<MappingSide> mapping, MappedReceiver& receiver,
                   BadInputLog& bad_input);

  const MappingSide& mapping() const { return *mapping_; }
  // A map snapshot from the tracker: taken over (true) when it is the handover asked for.
  bool takeOver(const MapSnapshot& snapshot, const MapSnapshotMsg& msg);
  size_t loopsClosed() const { return loops_closed_; }
  std::string jobTopic() const { return job_sub_.getTopic(); }
  std::string updateTopic() const { return update_pub_.getTopic(); }

 private:
  void onMappingJob(const ply_slam::MappingJobMsgConstPtr& msg);
  // Each update the mapping thread finished, to the tracker and the receiver.
  void takeMapped();
  // Asks the tracker whether jobs went by from `next_job` on (a restart, a gap); if so its copy
  // comes on the snapshot topic and jobs wait (held_jobs_) until takeOver.
  void askForHandOver(const std::string& when, uint64_t next_job);
  void mapHeldJobs(uint64_t first);
  void imagesToDenseMaps(const MappingJob& job);
  void checkWhenQuiet();  // askForHandOver once after kQuietJobs without a job
  bool onMapForTracker(MapForTracker::Request& request, MapForTracker::Response& response);
  void onUpdatesWanted(const std_msgs::UInt64ConstPtr& msg);
  void keepSent(MapUpdateMsg::ConstPtr update);
  // The mapping side maps in the tracker's intrinsics (camera_info's, or its config's) and with
  // its settings (ORB pyramid, BA, culling, loop closure), which each job carries: made anew
  // with them before the first job; after it, a job with others is refused
  // (std::invalid_argument naming what differs).
  void adoptTracker(const PinholeCamera& camera, const std::string& yaml);

  const MappingNodeOptions& options_;
  SystemConfig config_;       // the tracker's config and camera (options_.config until a job)
  std::string tracker_yaml_;  // the tracker's config document, as its last job had it
  bool mapped_any_ = false;   // a job was taken since the start
  MappedReceiver& receiver_;
  BadInputLog& bad_input_;
  // The ORB scales first: the map's keyframes point to them.
  std::shared_ptr<const std::vector<double>> orb_scales_;
  std::unique_ptr<MappingSide> mapping_;
  std::unique_ptr<MappingThread> mapping_thread_;

  ros::Subscriber job_sub_, wanted_sub_;
  ros::Publisher update_pub_;
  ros::ServiceClient hand_over_client_;
  ros::ServiceServer map_for_tracker_srv_;
  ros::WallTimer mapped_timer_, quiet_timer_;
  MessageSequence job_sequence_;
  bool awaiting_handover_ = false;
  std::vector<std::pair<uint64_t, MappingJob>> held_jobs_;  // by sequence, while awaiting
  static constexpr size_t kMaxHeldJobs = 30;                // ~2.5 MB each at 640x480
  inline static const ros::WallDuration kQuietJobs{2.0};
  ros::WallTime last_job_;
  bool quiet_checked_ = false;
  uint64_t updates_sent_ = 0;
  size_t loops_closed_ = 0;
  // The newest updates sent (the messages published, shared), with their serialised sizes, for a
  // tracker that missed some: at most kMaxSentUpdates and kMaxSentBytes (a loop's whole-map
  // update is the largest).
  std::deque<std::pair<MapUpdateMsg::ConstPtr, size_t>> sent_;
  size_t sent_bytes_ = 0;
  static constexpr size_t kMaxSentUpdates = 300, kMaxSentBytes = size_t{64} << 20;
};

}  // namespace ply_slam
