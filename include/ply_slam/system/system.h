#pragma once

#include <atomic>
#include <deque>
#include <functional>
#include <future>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <stdexcept>

#include "ply_slam/common/stamped_pose.h"
#include "ply_slam/dynamic/dynamic_rejector.h"
#include "ply_slam/dynamic/feature_mark.h"
#include "ply_slam/features/line_extractor.h"
#include "ply_slam/features/line_fitter.h"
#include "ply_slam/features/orb_extractor.h"
#include "ply_slam/io/rgbd_images.h"
#include "ply_slam/loop/relocalisation_database.h"
#include "ply_slam/map/anchored_trajectory.h"
#include "ply_slam/map/key_frame_packet.h"
#include "ply_slam/map/map.h"
#include "ply_slam/semantic/instance.h"
#include "ply_slam/semantic/instance_memory.h"
#include "ply_slam/system/mapping_job.h"
#include "ply_slam/system/mapping_side.h"
#include "ply_slam/system/mapping_thread.h"
#include "ply_slam/system/system_config.h"
#include "ply_slam/tracking/tracker.h"

namespace ply_slam {

// Milliseconds spent on one frame, per stage.
struct FrameTiming {
  double features_ms = 0.0;  // grey conversion, ORB, undistortion, depth lookup
  double lines_ms = 0.0;     // line detection (beside ORB on a second thread), then LBD and 3D
                             // fitting side by side (0 when disabled); not a share of total_ms
  double tracking_ms = 0.0;  // matching, pose optimisation, keyframe insertion
  double map_wait_ms = 0.0;  // of tracking_ms, waiting for the map's lock (the mapping thread)
  double follow_ms = 0.0;    // of tracking_ms, the tracker's copy following the mapping side's
                             // updates that came since the last frame (kSplitOwnThread)
  double total_ms = 0.0;     // features + lines + tracking: what the frame costs the tracking side
  double mapping_ms = 0.0;   // the mapping side's work delivered with this frame (on its own
                             // thread with MappingMode::kOwnThread: not a share of total_ms)
};

struct FrameResult {
  long frame_id = 0;
  double stamp = 0.0;
  TrackingResult tracking;
  FrameTiming timing;
  size_t dynamic_features = 0;  // dropped because they lay on a moving object
  size_t dynamic_lines = 0;     // lines dropped: an endpoint on a dynamic instance
  std::vector<FeatureMark> features;
  std::vector<Instance> instances;   // as judged: the segmenter's and those carried on for it
  std::set<int> dynamic_instances;   // ids of the instances judged moving
  std::set<int> measured_instances;  // those of them this frame's own evidence found moving
  cv::Mat dynamic_mask;              // their dilated union (8UC1), empty when none
  // The mapping side's work finished since the previous frame, in keyframe order: with
  // MappingMode::kInline this frame's keyframe, if it made one; with kOwnThread whatever the
  // mapping thread finished meanwhile (System::finishMapping returns the rest).
  std::vector<MappedKeyFrame> mapped;
};

// A frame the system cannot use (empty, wrong encoding or size, stamp not increasing).
// The system's state is unchanged when this is thrown.
class InvalidFrame : public std::invalid_argument {
 public:
  using std::invalid_argument::invalid_argument;
};

// Where the mapping side runs. kInline: after each keyframe, before process() returns, so that
// runs repeat bit for bit. kOwnThread: on a thread of its own, while tracking goes on (the two
// share the map under Map::updateMutex()); results come with later frames. kSplit: in line as
// kInline, but the tracker tracks in a copy of the map of its own, as the tracking process of
// a two-process split would: the mapping side's map follows the tracker's reports
// (TrackerReport), the tracker's copy follows the mapping side's updates (MapUpdate with its
// journal); runs repeat kInline's bit for bit. kSplitOwnThread: so, with the mapping side on a
// thread of its own; the tracker's copy follows each update at the first frame after it.
// kApart: the tracking side alone, as tracking_node runs it beside a mapping_node: each new
// keyframe's job goes to the job sink (setJobSink), the copy follows the updates given to
// followMapUpdate, nothing is mapped here; relocalisation goes through a place database of its
// own (loop.enabled); a loaded map is loaded by the mapping side too, from the same file.
enum class MappingMode { kInline, kOwnThread, kSplit, kSplitOwnThread, kApart };

// The whole pipeline in one process, frame by frame: the tracking side in process(), the
// mapping side as MappingMode says.
class System {
 public:
  explicit System(const SystemConfig& config, MappingMode mode = MappingMode::kInline);

  // kApart: where each new keyframe's job goes (called from process(), with the tracker's map
  // locked: queue it, do not call back into the system).
  using JobSink = std::function<void(MappingJob job)>;
  void setJobSink(JobSink sink) { job_sink_ = std::move(sink); }
  // kApart: what the mapping side changed, its updates in the order it made them, done to the
  // tracker's copy; between two frames, on the thread that calls process().
  void followMapUpdate(const MapUpdate& update);

  // kApart, between two frames: the tracker's copy of the map for a mapping side that starts
  // anew from it (MappingSide::takeOver); what the tracker did since the last keyframe is in it,
  // so the next job's report starts from here. std::logic_error in the other modes.
  MapHandover handOverMap();
  // kApart, before the first frame: the tracker restarted while the mapping side went on; its
  // copy becomes the mapping side's map (MappingSide::handOverMap), in which it relocalises as
  // in a loaded map (loadMap). Throws std::runtime_error naming the fault, the system unchanged;
  // std::logic_error after the first frame, with a map, or in the other modes.
  void takeOverMap(const MapHandover& handover, bool localisation_only);

  // rgb: 8UC3 BGR; depth: 32FC1 metres (0 or NaN = invalid); both of the configured size.
  // Dynamic features are left out as config.dynamic.mode says (PAPER.md §3.2).
  FrameResult process(const RgbdImages& images, const std::vector<Instance>& instances = {});
  // Waits for the mapping side to finish the keyframes it was given and returns what it made
  // of those not delivered with a frame yet (nothing with kInline). Call it after the last
  // frame, before reading the trajectories or saving the map.
  std::vector<MappedKeyFrame> finishMapping();
  // What the mapping thread finished since the last frame, for a caller with no frame coming
  // (a node between frames: loop closures must not wait for the next frame); the next frame's
  // result then holds only what finished after. Nothing with kInline.
  std::vector<MappedKeyFrame> takeMapped();
  // The most keyframes that waited for the mapping thread at once (0 with kInline).
  size_t longestMappingQueue() const;
  // Keyframes handed to the mapping side that it has not finished: the mapping thread's jobs
  // waiting or running, with kApart the jobs no update has answered yet (0 in line). The
  // tracker makes no keyframe while there are more than tracking.keyframe_max_unmapped.
  size_t mappingBacklog() const;
  // kApart: no mapping side took the jobs handed over so far (nobody listens): the tracker
  // waits for no answer to them.
  void forgetUnansweredJobs() { unanswered_jobs_.clear(); }

  // Tracked frames, each placed relative to its reference keyframe as the map has that keyframe
  // now: bundle adjustment and loop closure move the past with the map.
  Trajectory cameraTrajectory() const;
  Trajectory keyFrameTrajectory() const;
  // Every keyframe of the map as it is now, without images (for a mapper that restarted).
  std::vector<KeyFramePacket> sparseKeyFramePackets() const;
  // Keyframes to relocalise an image with these ORB descriptors against, most similar first, at
  // most kRelocalisationCandidates (loop.enabled: the mapping side's place database; kApart a
  // database of the tracker's own that keeps the same words); empty without place recognition.
  static constexpr size_t kRelocalisationCandidates = 10;
  std::vector<long> placeCandidates(const cv::Mat& orb_descriptors) const;
  // Loop closure's counts; null without loop.enabled.
  const LoopClosureCounts* loopCounts() const {
    return mapping_ ? mapping_->mapper().loopCounts() : nullptr;
  }
  GlobalBundleAdjustmentCounts globalBundleAdjustmentCounts() const {
    return mapping_ ? mapping_->mapper().globalBundleAdjustmentCounts()
                    : GlobalBundleAdjustmentCounts{};
  }
  // The mapping side's map (kApart: the tracker's copy), and the one the tracker tracks in (its
  // own copy in the split modes; both still while the mapping side works on another thread only).
  const Map& map() const { return mapping_ ? mapping_->map() : *tracking_map_; }
  const Map& trackerMap() const { return tracking_map_ ? *tracking_map_ : mapping_->map(); }

  // The map file a saved map is in, inside the folder saveMap and loadMap take.
  static constexpr const char* kMapFileName = "map.plymap";
  // Writes the map (keyframes with features, poses, landmarks, covisibility, spanning tree,
  // place-recognition data) into folder/map.plymap (MapFileWriter); the folder is created.
  // Throws std::runtime_error naming the file; std::logic_error with kApart.
  void saveMap(const std::string& folder) const;
  // Before the first frame: takes the map saved in `folder`. Tracking starts lost and
  // relocalises in it (place-recognition candidates and PnP), so no pose is reported before;
  // frame and keyframe ids continue after the map's. `localisation_only`: no keyframes nor
  // landmarks are added; false: the map is extended. With kApart the tracker's copy loads it
  // and the mapping side elsewhere must load the same file (MappingSide::loadMap): each job
  // names the file (MappingJob::loaded_map). Throws std::runtime_error naming the file and the
  // fault (missing, truncated, corrupted, another version, camera, pyramid or vocabulary), the
  // system unchanged; std::logic_error after the first frame.
  void loadMap(const std::string& folder, bool localisation_only = true);
  const SystemConfig& config() const { return config_; }

 private:
  // Lines detected on a second thread beside ORB (PAPER.md §3.1), and the time it took.
  struct DetectedLines {
    std::vector<LineFeature> lines;
    double ms = 0.0;
  };

  // Throws InvalidFrame for images or instance masks the system cannot use.
  void validate(const RgbdImages& images, const std::vector<Instance>& instances) const;
  // Starts the line detection on its own thread (gray must outlive the future); an empty future
  // when lines are disabled.
  std::future<DetectedLines> detectLinesAside(const cv::Mat& gray) const;
  // The frame's ORB points without the dynamic ones; the instances as judged into result.
  Frame pointFrame(const RgbdImages& images, const cv::Mat& gray,
                   const std::vector<Instance>& instances, FrameResult& result);
  // Describes and fits the detected lines, drops those touching a dynamic instance and gives
  // the rest to the frame.
  void addLines(DetectedLines detected, const RgbdImages& images, const cv::Mat& gray, Frame& frame,
                FrameResult& result);
  // The frame's new keyframe to the mapping side: queued for its thread, or mapped in line with
  // the map's lock released meanwhile (then a loop it closed moves the frame's pose too).
  void handOverKeyFrame(const RgbdImages& images, std::unique_lock<std::mutex>& lock,
                        FrameResult& result);
  // Judges the frame's features (PAPER.md §3.2), drops the dynamic ones, records the fates.
  void rejectDynamic(FrameFeatures& features, double stamp, const std::vector<Instance>& instances,
                     FrameResult& result);
  static void markInliers(const Frame& frame, std::vector<FeatureMark>& marks);
  // The frame's pose as tracked, hung from the tracker's reference keyframe as it is then (with
  // the map's lock held).
  void rememberTracked(const FrameResult& result);
  // Split modes, after the mapping side did a job's report (its map's lock held): anchors on the
  // tracker's keyframes move to the map's.
  void anchorOnMappedKeyFrames();
  // Split modes, tracking side (its copy locked): what the mapping side changed, done to the
  // copy; after a whole-map update the keyframes the mapping side has not seen yet move as the
  // one before them moved, and the tracker as the mapping side told.
  void followMapper(const MapUpdate& update);
  // The camera, pyramid and vocabularies a map file must have been made with to load here.
  const MapFileSetup& mapFileSetup();
  // loadMap's read map into the tracker's copy (and its keyframes into the place database).
  void adoptTrackerCopy(MapFileContents copy);
  // After a map was taken: tracking starts lost, frame ids go on after the map's.
  void startInMap(bool localisation_only);
  // followMapper's update into the copy: the keyframes the tracker made after the update's newest
  // (the mapping side has not seen them yet) move as the one before them moved (carryAlong), and
  // the landmarks they made with them. Returns how the tracker's reference keyframe moved so
  // (T_wc after * T_wc before^-1); none when it is not one of them.
  std::optional<Eigen::Isometry3d> followCarryingNewer(const MapUpdate& update);
  // The mapping thread's results, followed by the tracker's copy (split modes).
  std::vector<MappedKeyFrame> followed(std::vector<MappedKeyFrame> mapped);
  // The map the tracker tracks in: its own copy in the split modes, else the one map.
  Map& trackingMap() { return tracking_map_ ? *tracking_map_ : mapping_->map(); }
  // Frames anchored on keyframes the mapping side erased move to live ones, where they are.
  void reanchorTrackedFrames(const std::vector<long>& erased);
  AnchoredTrajectory::KeyFramePoses anchorPoses() const;

  SystemConfig config_;
  OrbExtractor extractor_;
  std::unique_ptr<LineExtractor> line_extractor_;  // null when lines are disabled
  std::unique_ptr<LineFitter> line_fitter_;
  DynamicRejector rejector_;
  InstanceMemory memory_;
  // Before the tracker, which sends it what it measured (unless in a copy); null with kApart.
  std::unique_ptr<MappingSide> mapping_;
  // Split modes (null otherwise): the tracker's copy of the map, the creator writing into it
  // what the tracker measured, and its report of that since the last keyframe (under the
  // copy's lock).
  std::unique_ptr<Map> tracking_map_;
  std::unique_ptr<LandmarkCreator> tracking_creator_;
  TrackerReport report_;
  // Split modes: the updates the tracker's copy followed, and their count when the last
  // keyframe went.
  long updates_followed_ = 0, followed_at_last_keyframe_ = 0;
  // Split modes: the keyframe of the last job, in the copy (MappingJob::made_after).
  std::shared_ptr<const KeyFrame> last_job_keyframe_;
  // The tracker's reference keyframe after the last frame (-1: none), for keyframe culling on
  // whichever thread maps.
  std::atomic<long> reference_id_{-1};
  Tracker tracker_;
  long next_frame_id_ = 0;
  double last_stamp_ = -1.0;
  // Tracked frames, each relative to the tracker's reference keyframe of its time; the
  // mapping side's keyframes they hang from (culled ones are replaced at once, see
  // reanchorTrackedFrames), in the split modes the tracker's until the mapping side has them
  // (`unmapped_anchors_`). Guarded by anchors_mutex_, taken after either map's lock.
  mutable std::mutex anchors_mutex_;
  AnchoredTrajectory tracked_;
  std::map<long, std::shared_ptr<const KeyFrame>> anchors_;
  std::set<long> unmapped_anchors_;
  JobSink job_sink_;  // kApart
  // kApart: the keyframe ids of the jobs handed over that no update has answered yet, oldest
  // first (an update answers every job up to the newest keyframe it names).
  std::deque<long> unanswered_jobs_;
  uint64_t loaded_map_ = 0;  // the checksum of the map file loaded (0: none), for the jobs
  std::optional<MapFileSetup> apart_file_setup_;  // kApart: mapFileSetup's, once made
  // kApart with loop.enabled: the keyframes' ORB words, for relocalisation (the mapping side's
  // database is in another process).
  std::unique_ptr<RelocalisationDatabase> places_;
  // Last: joined before anything it uses goes. Null with kInline.
  std::unique_ptr<MappingThread> mapping_thread_;
};

}  // namespace ply_slam
