#include "ply_slam/ros/apart_mapping_side.h"

#include <ply_slam/HandOverMap.h>
#include <ros/serialization.h>

#include <boost/algorithm/string/join.hpp>
#include <boost/make_shared.hpp>

#include "ply_slam/common/stopwatch.h"
#include "ply_slam/ros/mapping_back_end.h"
#include "ply_slam/ros/service_call.h"
#include "ply_slam/ros/split_messages.h"
#include "ply_slam/system/key_frame_packet_builder.h"

namespace ply_slam {

ApartMappingSide::ApartMappingSide(ros::NodeHandle nh, ros::NodeHandle pnh,
                                   const MappingNodeOptions& options,
                                   std::shared_ptr<const std::vector<double>> orb_scales,
                                   std::unique_ptr<MappingSide> mapping, MappedReceiver& receiver,
                                   BadInputLog& bad_input)
    : options_(options),
      config_(options.config),
      receiver_(receiver),
      bad_input_(bad_input),
      orb_scales_(std::move(orb_scales)),
      mapping_(std::move(mapping)) {
  mapping_thread_ = std::make_unique<MappingThread>(
      [this](const MappingJob& job) { return mapping_->mapKeyFrame(job); });
  update_pub_ = pnh.advertise<MapUpdateMsg>("map_update", 100);
  job_sub_ = nh.subscribe(options_.mapping_job_topic, 100, &ApartMappingSide::onMappingJob, this);
  wanted_sub_ =
      nh.subscribe(options_.updates_wanted_topic, 10, &ApartMappingSide::onUpdatesWanted, this);
  // What the mapping thread finished goes out within a hundredth of a second.
  mapped_timer_ = nh.createWallTimer(ros::WallDuration(0.01),
                                     [this](const ros::WallTimerEvent&) { takeMapped(); });
  hand_over_client_ = nh.serviceClient<HandOverMap>(options_.hand_over_service);
  map_for_tracker_srv_ =
      pnh.advertiseService("map_for_tracker", &ApartMappingSide::onMapForTracker, this);
  // A job lost last shows no gap until the next one: after kQuietJobs without jobs (the start
  // included: a restart) the tracker is asked once whether jobs went by.
  last_job_ = ros::WallTime::now();
  quiet_timer_ = nh.createWallTimer(ros::WallDuration(0.5),
                                    [this](const ros::WallTimerEvent&) { checkWhenQuiet(); });
}

void ApartMappingSide::onMappingJob(const ply_slam::MappingJobMsgConstPtr& msg) {
  const Stopwatch watch;
  const ThreadCpuStopwatch cpu;
  MappingJob job;
  try {
    adoptTracker(fromMsg(msg->camera), msg->config);
    job = fromMsg(*msg, JobReceiver{orb_scales_.get(),
                                    cv::Size(config_.camera.width, config_.camera.height)});
    mapping_->checkJob(job);
  } catch (const std::exception& e) {
    bad_input_.report("mapping_job", e.what());
    return;
  }
  mapped_any_ = true;
  const uint64_t sequence = msg->sequence;
  last_job_ = ros::WallTime::now();
  quiet_checked_ = false;
  if (awaiting_handover_) {                   // mapped after the tracker's copy, if not in it
    if (held_jobs_.size() >= kMaxHeldJobs) {  // the copy is long in coming: memory stays bounded
      bad_input_.report("mapping_job", "no handover yet: dropped held job " +
                                           std::to_string(held_jobs_.front().first));
      held_jobs_.erase(held_jobs_.begin());
    }
    held_jobs_.emplace_back(sequence, std::move(job));
    return;
  }
  const uint64_t first_missing = job_sequence_.expected();
  if (sequence > first_missing) {
    // The job's report builds on the missed ones: the tracker's copy, which holds them, comes.
    held_jobs_.emplace_back(sequence, std::move(job));
    askForHandOver("after missing " + std::to_string(sequence - first_missing) + " jobs",
                   first_missing);
    if (!awaiting_handover_) mapHeldJobs(0);  // no answer: the map goes on without them
    return;
  }
  job_sequence_.receive(sequence);
  mapping_thread_->push(std::move(job));
  receiver_.noteCallbackMs(watch.elapsedMs(), cpu.elapsedMs());
}

void ApartMappingSide::adoptTracker(const PinholeCamera& camera, const std::string& yaml) {
  const bool same_camera = sameCamera(camera, config_.camera);
  if (yaml == tracker_yaml_ && same_camera) return;
  SystemConfig tracker = loadConfigFromString(yaml, "of the tracker (in its mapping job)");
  useCamera(tracker, camera);
  const std::vector<std::string> differ = mappingSettingsThatDiffer(config_, tracker);
  if (mapped_any_ && !same_camera)
    throw std::invalid_argument("the tracker's camera (" + intrinsicsText(camera) +
                                ") is not the one this map was made with (" +
                                intrinsicsText(config_.camera) + ")");
  if (mapped_any_ && !differ.empty())
    throw std::invalid_argument("the tracker's settings are not those this map was made with: " +
                                boost::algorithm::join(differ, ", ") + " differ");
  if (same_camera && differ.empty()) {
    tracker_yaml_ = yaml;  // what differs the mapping side does not use
    return;
  }
  // Before the first job, with other settings or intrinsics: a mapping side made with them.
  if (const auto own = mappingSettingsThatDiffer(options_.config, tracker); !own.empty())
    ROS_WARN_STREAM(
        "mapping_node: maps with the tracker's settings, which differ from its own "
        "~config in: "
        << boost::algorithm::join(own, ", "));
  mapping_thread_->waitIdle();                           // nothing was pushed: no job taken yet
  auto scales = MappingBackEnd::orbScales(tracker.orb);  // the old map's, until it goes
  mapping_ = MappingBackEnd::makeMappingSide(tracker, options_.map, scales.get());
  orb_scales_ = std::move(scales);
  config_ = std::move(tracker);
  tracker_yaml_ = yaml;
  ROS_INFO_STREAM("mapping_node: maps in the tracker's intrinsics: " << intrinsicsText(camera));
}

// In the order made: each update to the tracker (whose copy follows them in turn), then to the
// receiver.
void ApartMappingSide::takeMapped() {
  // Idle, with a global bundle adjustment ended after the last keyframe: written back now.
  if (mapping_thread_->backlog() == 0 && mapping_->mapper().globalBundleAdjustmentSolved())
    mapping_thread_->push(MappingJob{});
  std::vector<MappedKeyFrame> mapped;
  try {
    mapped = mapping_thread_->takeFinished();
  } catch (const std::exception& e) {
    bad_input_.report("mapping", e.what());
    return;
  }
  for (const MappedKeyFrame& m : mapped) {
    auto update = boost::make_shared<MapUpdateMsg>(toMsg(*m.map_update, options_.world_frame));
    update->sequence = updates_sent_++;
    update_pub_.publish(update);
    keepSent(update);
    loops_closed_ += m.loop_correction != nullptr;
  }
  if (!mapped.empty()) receiver_.keepMapped(mapped);
}

// Published as a shared message, which must not change after: kept as it is, not copied.
void ApartMappingSide::keepSent(MapUpdateMsg::ConstPtr update) {
  const size_t bytes = ros::serialization::serializationLength(*update);
  sent_bytes_ += bytes;
  sent_.emplace_back(std::move(update), bytes);
  while (sent_.size() > kMaxSentUpdates || (sent_.size() > 1 && sent_bytes_ > kMaxSentBytes)) {
    sent_bytes_ -= sent_.front().second;
    sent_.pop_front();
  }
}

// The tracker missed updates (or asks after a quiet spell): those kept from `from` on go out
// again, in order; the tracker drops the ones it has.
void ApartMappingSide::onUpdatesWanted(const std_msgs::UInt64ConstPtr& msg) {
  const uint64_t from = msg->data;
  if (from >= updates_sent_) return;  // it has them all
  if (sent_.empty() || sent_.front().first->sequence > from)
    ROS_ERROR_STREAM("mapping_node: the tracker asks for map updates from "
                     << from << "; the oldest kept is "
                     << (sent_.empty() ? updates_sent_ : sent_.front().first->sequence)
                     << ": the tracker's copy goes on without those before");
  size_t resent = 0;
  for (const auto& [update, bytes] : sent_)
    if (update->sequence >= from) {
      update_pub_.publish(update);
      ++resent;
    }
  ROS_INFO_STREAM("mapping_node: sent " << resent << " map updates again from " << from);
}

void ApartMappingSide::checkWhenQuiet() {
  if (awaiting_handover_ || quiet_checked_ || ros::WallTime::now() - last_job_ < kQuietJobs) return;
  quiet_checked_ = true;
  if (hand_over_client_.exists())
    askForHandOver(std::to_string(kQuietJobs.toSec()) + " s without jobs",
                   job_sequence_.expected());
}

// Every update made so far goes out first: those the tracker has not followed when it hands
// over are dropped there (their numbers are below the one asked with).
void ApartMappingSide::askForHandOver(const std::string& when, uint64_t next_job) {
  mapping_thread_->waitIdle();
  takeMapped();
  HandOverMap ask;
  ask.request.next_job_sequence = next_job;
  ask.request.next_update_sequence = updates_sent_;
  const std::string why = callService(hand_over_client_, ask, std::chrono::seconds(30));
  if (!why.empty()) {
    ROS_ERROR_STREAM("mapping_node: asked " << when << " for the tracker's map: " << why
                                            << "; the map goes on without what it missed");
    return;
  }
  awaiting_handover_ = ask.response.handing_over;
  ROS_INFO_STREAM("mapping_node: " << when << ": " << ask.response.message);
}

// A tracker that starts (or restarts: its jobs are numbered from 0 again) gets this side's map
// once every job before is mapped and every update made has gone out.
bool ApartMappingSide::onMapForTracker(MapForTracker::Request&, MapForTracker::Response& response) {
  mapping_thread_->waitIdle();
  takeMapped();
  held_jobs_.clear();
  awaiting_handover_ = false;
  job_sequence_ = MessageSequence();
  const MapHandover handover = mapping_->handOverMap();
  response.success = true;
  handoverToFields(handover, response);
  response.next_update_sequence = updates_sent_;
  response.message =
      handover.map_file.empty()
          ? "the mapping side's map is empty"
          : "the mapping side's map: " + std::to_string(mapping_->map().numKeyFrames()) +
                " keyframes (" + std::to_string(handover.map_file.size() / 1024) + " KiB)";
  ROS_INFO_STREAM("mapping_node: map_for_tracker: " << response.message);
  return true;
}

// The jobs held while the tracker's copy was on its way, but those it holds already.
void ApartMappingSide::mapHeldJobs(uint64_t first) {
  for (auto& [sequence, job] : held_jobs_)
    if (sequence < first) imagesToDenseMaps(job);
  for (auto& [sequence, job] : held_jobs_) {
    if (sequence < first) continue;
    job_sequence_.receive(sequence);
    mapping_thread_->push(std::move(job));
  }
  held_jobs_.clear();
}

// A held job whose keyframe came in the tracker's copy: its images are still good for the dense
// maps, placed where the copy has the keyframe (unless the copy culled it).
void ApartMappingSide::imagesToDenseMaps(const MappingJob& job) {
  if (!job.keyframe) return;
  std::shared_ptr<const KeyFramePacket> packet;
  {
    std::lock_guard<std::mutex> lock(mapping_->map().updateMutex());
    if (const auto kf = mapping_->map().keyFrame(job.keyframe->id))
      packet = std::make_shared<const KeyFramePacket>(
          makeKeyFramePacket(*kf, config_.camera, job.images, job.segmentation));
  }
  if (packet) receiver_.keepDenseImages(std::move(packet));
}

// A new mapping side from the tracker's copy (the old one's map is dropped with it).
bool ApartMappingSide::takeOver(const MapSnapshot& snapshot, const MapSnapshotMsg& msg) {
  if (!awaiting_handover_ || snapshot.handover.map_file.empty()) return false;
  mapping_thread_->waitIdle();
  std::unique_ptr<MappingSide> fresh;
  try {
    adoptTracker(fromMsg(msg.camera), msg.config);  // before any job: the copy's settings
    fresh = MappingBackEnd::makeMappingSide(config_, "", orb_scales_.get());
    fresh->takeOver(snapshot.handover, orb_scales_.get());
  } catch (const std::exception& e) {
    bad_input_.report("map_snapshot", e.what());
    return false;
  }
  mapping_thread_->takeFinished();  // none: nothing was pushed while waiting
  mapping_ = std::move(fresh);
  mapped_any_ = true;  // the map is the tracker's, made with its settings
  awaiting_handover_ = false;
  const uint64_t next_job = msg.next_keyframe_sequence;
  job_sequence_.resynchronise(next_job);
  mapHeldJobs(next_job);
  ROS_INFO_STREAM("mapping_node: maps on from the tracker's copy: "
                  << mapping_->map().numKeyFrames() << " keyframes, "
                  << mapping_->map().numMapPoints() << " points; jobs from " << next_job);
  return true;
}

}  // namespace ply_slam
