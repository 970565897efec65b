#include "ply_slam/system/system.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <future>
#include <limits>
#include <opencv2/imgproc.hpp>
#include <optional>
#include <set>
#include <utility>

#include "ply_slam/common/stopwatch.h"
#include "ply_slam/loop/vocabulary_identity.h"
#include "ply_slam/map/map_file_reader.h"
#include "ply_slam/map/map_file_writer.h"
#include "ply_slam/mapping/carry_along.h"
#include "ply_slam/system/key_frame_packet_builder.h"

namespace ply_slam {
namespace {

// The newest keyframe whose pose the update carries (-1: none).
long newestPosed(const MapUpdate& update) {
  long newest = -1;
  for (const auto& pose : update.keyframes) newest = std::max(newest, pose.id);
  return newest;
}

}  // namespace

System::System(const SystemConfig& config, MappingMode mode)
    : config_(config),
      extractor_(config.orb),
      rejector_(config.dynamic, config.camera),
      memory_(config.dynamic.carry_frames),
      mapping_(mode == MappingMode::kApart
                   ? nullptr
                   : std::make_unique<MappingSide>(
                         config,
                         mode == MappingMode::kSplit || mode == MappingMode::kSplitOwnThread,
                         mode == MappingMode::kInline || mode == MappingMode::kSplit)),
      tracking_map_(mode == MappingMode::kInline || mode == MappingMode::kOwnThread
                        ? nullptr
                        : std::make_unique<Map>()),
      tracking_creator_(tracking_map_ ? std::make_unique<LandmarkCreator>(
                                            config.camera, config.tracking.max_point_depth,
                                            config.lines, *tracking_map_)
                                      : nullptr),
      tracker_(config.camera, config.tracking, config.orb, config.lines, trackingMap(),
               tracking_creator_ ? *tracking_creator_ : mapping_->mapper().landmarkSink()) {
  if (tracking_creator_) tracking_creator_->reportTo(&report_);
  if (config_.lines.enabled) {
    line_extractor_ = std::make_unique<LineExtractor>(config_.lines);
    line_fitter_ = std::make_unique<LineFitter>(config_.lines, config_.camera);
  }
  if (!mapping_ && config_.loop.enabled)
    places_ = std::make_unique<RelocalisationDatabase>(
        RelocalisationDatabase::fromOptions(config_.loop, config_.dynamic.mask_dilation_px));
  if (places_ || (mapping_ && mapping_->mapper().recognisesPlaces()))
    tracker_.setPlaceCandidates(
        [this](const Frame& frame) { return placeCandidates(frame.features.descriptors); });
  if (!mapping_) return;  // kApart
  Mapper& mapper = mapping_->mapper();
  // In the split modes the tracker moves when its copy follows the update that says so; else
  // the mapper tells it, holding the map's lock: the tracker is between two frames.
  if (!tracking_map_)
    mapper.setCorrectionListener(
        [this](const Eigen::Isometry3d& correction) { tracker_.applyCorrection(correction); });
  MappingSide::Hooks hooks;
  hooks.keep = [this] { return std::set<long>{reference_id_.load()}; };
  hooks.culled = [this](const std::vector<long>& culled) { reanchorTrackedFrames(culled); };
  hooks.replayed = [this] { anchorOnMappedKeyFrames(); };
  mapping_->setHooks(std::move(hooks));
  if (mode == MappingMode::kOwnThread || mode == MappingMode::kSplitOwnThread)
    mapping_thread_ = std::make_unique<MappingThread>(
        [this](const MappingJob& job) { return mapping_->mapKeyFrame(job); });
}

void System::validate(const RgbdImages& images, const std::vector<Instance>& instances) const {
  const auto& cam = config_.camera;
  if (images.rgb.empty()) throw InvalidFrame("empty RGB image");
  if (images.depth.empty()) throw InvalidFrame("empty depth image");
  if (images.rgb.type() != CV_8UC3)
    throw InvalidFrame("RGB image must be 8-bit, 3 channels (got type " +
                       cv::typeToString(images.rgb.type()) + ")");
  if (images.depth.type() != CV_32FC1)
    throw InvalidFrame("depth image must be 32FC1 in metres (got type " +
                       cv::typeToString(images.depth.type()) + ")");
  if (images.rgb.size() != images.depth.size()) throw InvalidFrame("RGB and depth sizes differ");
  if (images.rgb.cols != cam.width || images.rgb.rows != cam.height)
    throw InvalidFrame("image is " + std::to_string(images.rgb.cols) + "x" +
                       std::to_string(images.rgb.rows) + " but the camera is configured for " +
                       std::to_string(cam.width) + "x" + std::to_string(cam.height));
  if (!std::isfinite(images.stamp) || !std::isfinite(images.depth_stamp))
    throw InvalidFrame("stamp is not a finite number");
  if (images.stamp <= last_stamp_)
    throw InvalidFrame("stamp " + std::to_string(images.stamp) +
                       " does not follow the previous frame's " + std::to_string(last_stamp_));
  for (const auto& instance : instances)
    if (instance.mask.type() != CV_8UC1 || instance.mask.size() != images.rgb.size())
      throw InvalidFrame("instance mask of '" + instance.class_name +
                         "' must be 8UC1 of the image size");
}

FrameResult System::process(const RgbdImages& images, const std::vector<Instance>& instances) {
  if (!mapping_ && !job_sink_)
    throw std::logic_error("System::process: MappingMode::kApart needs a job sink");
  validate(images, instances);
  last_stamp_ = images.stamp;

  FrameResult result;
  result.frame_id = next_frame_id_++;
  result.stamp = images.stamp;
  Stopwatch total;
  cv::Mat gray;
  cv::cvtColor(images.rgb, gray, cv::COLOR_BGR2GRAY);
  std::future<DetectedLines> lines = detectLinesAside(gray);
  Frame frame = pointFrame(images, gray, instances, result);
  result.timing.features_ms = total.elapsedMs();
  if (lines.valid()) addLines(lines.get(), images, gray, frame, result);

  // Tracking reads and extends the map: under its lock, taken after the frame's features.
  Stopwatch tracking;
  std::unique_lock<std::mutex> lock(trackingMap().updateMutex());
  result.timing.map_wait_ms = tracking.elapsedMs();
  if (mapping_thread_) result.mapped = mapping_thread_->takeFinished();
  Stopwatch follow;
  if (tracking_map_)
    for (const auto& mapped : result.mapped) followMapper(*mapped.map_update);
  result.timing.follow_ms = follow.elapsedMs();
  tracker_.setUnmappedKeyFrames(mappingBacklog());
  result.tracking = tracker_.track(frame);
  if (const auto& reference = tracker_.referenceKeyFrame()) reference_id_ = reference->id;
  result.timing.tracking_ms = tracking.elapsedMs();
  result.timing.total_ms = total.elapsedMs();
  markInliers(frame, result.features);
  // Before the hand-over: mapping the frame's own keyframe in line (local BA, a loop it closes)
  // then moves the frame with it.
  rememberTracked(result);
  if (result.tracking.new_keyframe) handOverKeyFrame(images, lock, result);
  for (const auto& mapped : result.mapped) result.timing.mapping_ms += mapped.ms;
  return result;
}

std::future<System::DetectedLines> System::detectLinesAside(const cv::Mat& gray) const {
  if (!line_extractor_) return {};
  return std::async(std::launch::async, [this, &gray] {
    Stopwatch watch;
    DetectedLines detected;
    detected.lines = line_extractor_->detect(gray, config_.camera);
    detected.ms = watch.elapsedMs();
    return detected;
  });
}

Frame System::pointFrame(const RgbdImages& images, const cv::Mat& gray,
                         const std::vector<Instance>& instances, FrameResult& result) {
  FrameFeatures features =
      FrameFeatures::extract(gray, images.depth, config_.camera, extractor_, tracker_.velocity(),
                             images.depth_stamp != 0.0 ? images.depth_stamp - images.stamp : 0.0);
  // A person the segmenter missed in this frame is still where the last frames put it.
  std::vector<Instance> judged = memory_.complete(instances, gray);
  rejectDynamic(features, images.stamp, judged, result);
  memory_.remember(judged, result.measured_instances, result.dynamic_instances, gray);
  result.instances = std::move(judged);
  return Frame(result.frame_id, images.stamp, std::move(features));
}

void System::addLines(DetectedLines detected, const RgbdImages& images, const cv::Mat& gray,
                      Frame& frame, FrameResult& result) {
  FrameLines frame_lines;
  frame_lines.lines = std::move(detected.lines);
  // Described here and fitted in 3D there, side by side: neither needs the other.
  Stopwatch watch;
  std::future<void> fitted = std::async(std::launch::async, [&] {
    frame_lines.fit(images.depth, *line_fitter_, LineFitMethod::kSampled);
  });
  frame_lines.descriptors = line_extractor_->describe(gray, frame_lines.lines);
  fitted.get();
  result.timing.lines_ms = detected.ms + watch.elapsedMs();
  if (tracker_.velocity()) frame_lines.correctMotion(config_.camera, *tracker_.velocity());
  result.dynamic_lines =
      frame_lines.removeIf(DynamicRejector::linesTouching(frame_lines.lines, result.dynamic_mask));
  frame.setLines(std::move(frame_lines));
}

void System::handOverKeyFrame(const RgbdImages& images, std::unique_lock<std::mutex>& lock,
                              FrameResult& result) {
  MappingJob job;
  job.keyframe = result.tracking.new_keyframe;
  job.images = images;
  job.segmentation = segmentationOf(result.instances, result.dynamic_instances, result.dynamic_mask,
                                    images.rgb.size());
  job = job.detached();
  if (tracking_map_) {  // the mapping side gets a keyframe of its own and the report
    job.keyframe = job.keyframe->unlinkedCopy();
    job.report = std::exchange(report_, TrackerReport{});
    job.followed_updates = std::exchange(followed_at_last_keyframe_, updates_followed_);
    if (last_job_keyframe_ && !last_job_keyframe_->bad) {
      job.made_after = last_job_keyframe_->id;
      job.made_after_T_cw = last_job_keyframe_->T_cw;
    }
    last_job_keyframe_ = result.tracking.new_keyframe;
  }
  job.reference_keyframe = reference_id_.load();
  job.loaded_map = loaded_map_;
  if (!mapping_) {  // kApart
    if (places_) places_->add(*job.keyframe, job.segmentation);
    unanswered_jobs_.push_back(job.keyframe->id);
    job_sink_(std::move(job));
    return;
  }
  if (mapping_thread_) {
    mapping_thread_->push(std::move(job));
    return;
  }
  lock.unlock();
  result.mapped.push_back(mapping_->mapKeyFrame(job));
  lock.lock();
  if (tracking_map_) followMapper(*result.mapped.back().map_update);
  // The frame was tracked before its keyframe closed the loop: it moves with the map.
  if (const auto& loop = result.mapped.back().loop_correction)
    result.tracking.T_cw = result.tracking.T_cw * loop->world_correction.inverse();
}

void System::anchorOnMappedKeyFrames() {
  std::lock_guard<std::mutex> anchors_lock(anchors_mutex_);
  if (unmapped_anchors_.empty()) return;
  for (const auto& kf : mapping_->map().keyFrames())
    if (unmapped_anchors_.erase(kf->id)) anchors_[kf->id] = kf;
}

void System::followMapUpdate(const MapUpdate& update) {
  if (mapping_) throw std::logic_error("System::followMapUpdate: only with MappingMode::kApart");
  std::lock_guard<std::mutex> lock(tracking_map_->updateMutex());
  // Frames hanging from keyframes the mapping side erased move to live ones first, while the
  // poses of both still agree.
  reanchorTrackedFrames(update.erased_keyframes);
  followMapper(update);
  if (places_)
    for (long id : update.erased_keyframes) places_->remove(id);
  // Job 0's update poses nothing (no local BA yet): the replayed keyframe answers it too.
  const long newest = std::max(update.replayed.keyframe, newestPosed(update));
  while (!unanswered_jobs_.empty() && unanswered_jobs_.front() <= newest)
    unanswered_jobs_.pop_front();
}

std::vector<long> System::placeCandidates(const cv::Mat& orb_descriptors) const {
  if (places_) return places_->recognise(orb_descriptors, kRelocalisationCandidates);
  if (!mapping_) return {};
  return mapping_->mapper().recognise(orb_descriptors, kRelocalisationCandidates);
}

void System::followMapper(const MapUpdate& update) {
  const std::optional<Eigen::Isometry3d> reference_moved = followCarryingNewer(update);
  for (const auto& correction : update.world_corrections) {
    tracker_.applyCorrection(correction);
    moveTrackerReport(report_, correction);  // its line fits so far: into the world it goes on in
  }
  // The tracker's last frame and its report so far hang from its reference keyframe: when that
  // one moved as a keyframe of its own the mapping side has not seen yet, they move with it
  // (a loop's or a global BA's move came as world corrections above).
  if (reference_moved && update.world_corrections.empty()) {
    tracker_.applyCorrection(*reference_moved);
    moveTrackerReport(report_, *reference_moved);
  }
  ++updates_followed_;
  // What left the tracker's copy is the mapping side's to tell (the update says it).
  tracking_map_->takeRemovedPoints();
  tracking_map_->takeRemovedLines();
}

std::optional<Eigen::Isometry3d> System::followCarryingNewer(const MapUpdate& update) {
  Map& copy = *tracking_map_;
  // Alive through the update, which may erase some (their poses are read after).
  const std::vector<std::shared_ptr<KeyFrame>> keyframes = copy.keyFrames();
  std::vector<std::pair<KeyFrame*, Eigen::Isometry3d>> before;
  for (const auto& kf : keyframes) before.emplace_back(kf.get(), kf->T_wc());
  copy.apply(update);
  // The update accounts for every keyframe up to its newest; the tracker made the later ones.
  // One that moved no keyframe moves none of them either.
  const long newest =
      update.keyframes.empty() ? std::numeric_limits<long>::max() : newestPosed(update);
  const KeyFrame* reference = tracker_.referenceKeyFrame().get();
  std::optional<Eigen::Isometry3d> reference_before;  // when it is carried
  std::set<const KeyFrame*> seen;
  std::vector<std::pair<KeyFrame*, Eigen::Isometry3d>> kept;
  for (const auto& [kf, T_wc] : before) {
    if (kf->bad) continue;
    if (kf->id <= newest)
      seen.insert(kf);
    else if (kf == reference)
      reference_before = T_wc;
    kept.emplace_back(kf, T_wc);
  }
  carryAlong(copy, seen, kept);
  if (!reference_before) return std::nullopt;
  return reference->T_wc() * reference_before->inverse();
}

void System::rememberTracked(const FrameResult& result) {
  if (result.tracking.state != TrackingState::kOk) return;
  const auto reference = tracker_.referenceKeyFrame();
  std::lock_guard<std::mutex> lock(anchors_mutex_);
  // In the split modes the tracker's keyframe, until the mapping side has its own (same pose).
  if (anchors_.emplace(reference->id, reference).second && tracking_map_ && mapping_)
    unmapped_anchors_.insert(reference->id);
  tracked_.add(result.stamp, reference->id, reference->T_cw, result.tracking.T_cw);
}

std::vector<MappedKeyFrame> System::finishMapping() {
  if (!mapping_thread_) return {};
  mapping_thread_->waitIdle();
  // A global bundle adjustment still solving: written back by the mapping thread like one that
  // ended between frames (takeMapped).
  mapping_->mapper().waitForGlobalBundleAdjustment();
  if (mapping_->mapper().globalBundleAdjustmentSolved()) mapping_thread_->push(MappingJob{});
  mapping_thread_->waitIdle();
  return followed(mapping_thread_->takeFinished());
}

std::vector<MappedKeyFrame> System::followed(std::vector<MappedKeyFrame> mapped) {
  if (!tracking_map_) return mapped;
  std::lock_guard<std::mutex> lock(tracking_map_->updateMutex());
  for (const auto& m : mapped) followMapper(*m.map_update);
  return mapped;
}

std::vector<MappedKeyFrame> System::takeMapped() {
  if (!mapping_thread_) return {};
  // Idle, with a global bundle adjustment ended after the last keyframe: the mapping thread
  // writes it back now rather than at the next keyframe.
  if (mapping_thread_->backlog() == 0 && mapping_->mapper().globalBundleAdjustmentSolved())
    mapping_thread_->push(MappingJob{});
  return followed(mapping_thread_->takeFinished());
}

size_t System::mappingBacklog() const {
  if (mapping_thread_) return mapping_thread_->backlog();
  return mapping_ ? 0 : unanswered_jobs_.size();
}

size_t System::longestMappingQueue() const {
  return mapping_thread_ ? mapping_thread_->longestQueue() : 0;
}

void System::rejectDynamic(FrameFeatures& features, double stamp,
                           const std::vector<Instance>& instances, FrameResult& result) {
  DynamicRejection rejection =
      rejector_.decide(features, stamp, instances, tracker_.velocity(), memory_.presumed());
  // All features: one dropped now is judged again later.
  rejector_.remember(features, stamp, rejection);
  result.features.resize(features.size());
  std::vector<bool> drop(features.size());
  for (size_t i = 0; i < features.size(); ++i) {
    result.features[i] = {features.keypoints[i].pt, rejection.fate[i], false};
    drop[i] = rejection.fate[i] != FeatureFate::kKept;
  }
  result.dynamic_features = features.removeIf(drop);
  result.dynamic_instances = std::move(rejection.dynamic_instances);
  result.measured_instances = std::move(rejection.measured_instances);
  result.dynamic_mask = rejection.dynamic_mask;
}

void System::markInliers(const Frame& frame, std::vector<FeatureMark>& marks) {
  size_t k = 0;  // index among the kept features, which the frame holds in the same order
  for (auto& mark : marks) {
    if (mark.fate != FeatureFate::kKept) continue;
    mark.inlier = k < frame.map_points.size() && frame.map_points[k] && !frame.outlier[k];
    ++k;
  }
}

void System::reanchorTrackedFrames(const std::vector<long>& erased) {
  if (erased.empty()) return;
  std::lock_guard<std::mutex> lock(anchors_mutex_);
  std::map<long, std::shared_ptr<const KeyFrame>> keyframes;
  AnchoredTrajectory::KeyFramePoses live;
  const std::set<long> gone(erased.begin(), erased.end());
  for (const auto& kf : map().keyFrames()) {
    if (gone.count(kf->id)) continue;  // kApart: the copy has not followed the update yet
    keyframes.emplace(kf->id, kf);
    live.emplace(kf->id, kf->T_cw);
  }
  for (long id : erased) {
    const auto culled = anchors_.find(id);
    if (culled == anchors_.end()) continue;  // no frame hangs from it
    // The tracker's own keyframe (it took it as reference after this map had it culled): its
    // frames stay on it, the tracker's copy holds it as the mapping side last placed it.
    if (unmapped_anchors_.count(id)) continue;
    // Culled just now, so its pose still agrees with the map's.
    const long anchor = tracked_.reanchor(id, culled->second->T_cw, live);
    anchors_.erase(culled);
    anchors_.emplace(anchor, keyframes.at(anchor));
  }
}

AnchoredTrajectory::KeyFramePoses System::anchorPoses() const {
  AnchoredTrajectory::KeyFramePoses poses;
  for (const auto& [id, kf] : anchors_) poses.emplace(id, kf->T_cw);
  return poses;
}

Trajectory System::cameraTrajectory() const {
  std::lock_guard<std::mutex> lock(map().updateMutex());
  std::lock_guard<std::mutex> anchors_lock(anchors_mutex_);
  return tracked_.trajectory(anchorPoses());
}

std::vector<KeyFramePacket> System::sparseKeyFramePackets() const {
  return ply_slam::sparseKeyFramePackets(map(), config_.camera);
}

void System::saveMap(const std::string& folder) const {
  if (!mapping_) throw std::logic_error("System::saveMap: the mapping side (elsewhere) saves it");
  mapping_->saveMap((std::filesystem::path(folder) / kMapFileName).string());
}

void System::loadMap(const std::string& folder, bool localisation_only) {
  if (next_frame_id_ != 0 || trackingMap().numKeyFrames() != 0)
    throw std::logic_error("System::loadMap: a map is loaded before the first frame");
  const std::string file = (std::filesystem::path(folder) / kMapFileName).string();
  // Read and checked whole before anything changes: a bad file leaves the system as it was. The
  // tracker's copy (split modes, kApart) is a map of its own, from the same file.
  std::optional<MapFileContents> copy;
  if (tracking_map_) copy = MapFileReader::read(file, mapFileSetup(), &extractor_.scales());
  if (mapping_) mapping_->loadMap(file, &extractor_.scales());
  loaded_map_ = copy ? copy->checksum : mapping_->loadedMap();
  if (copy) adoptTrackerCopy(std::move(*copy));
  startInMap(localisation_only);
}

void System::takeOverMap(const MapHandover& handover, bool localisation_only) {
  if (mapping_) throw std::logic_error("System::takeOverMap: only with the mapping side apart");
  if (next_frame_id_ != 0 || tracking_map_->numKeyFrames() != 0)
    throw std::logic_error("System::takeOverMap: before the first frame, into an empty map");
  if (!handover.map_file.empty())
    adoptTrackerCopy(MapFileReader::decode(handover.map_file, "the mapping side's map",
                                           mapFileSetup(), &extractor_.scales()));
  tracking_map_->continueIdsFrom(handover.next_ids);
  loaded_map_ = handover.loaded_map;
  updates_followed_ = followed_at_last_keyframe_ = handover.updates_followed;
  if (!handover.map_file.empty()) startInMap(localisation_only);
}

void System::startInMap(bool localisation_only) {
  tracker_.startLost();
  tracker_.setLocalisationOnly(localisation_only);
  // Keyframes remember the frame they were made from; new frames must not repeat those ids.
  for (const auto& kf : trackingMap().keyFrames())
    next_frame_id_ = std::max(next_frame_id_, kf->frame_id + 1);
}

const MapFileSetup& System::mapFileSetup() {
  if (mapping_) return mapping_->mapFileSetup();
  if (apart_file_setup_) return *apart_file_setup_;
  // kApart: the LBD vocabulary is the mapping side's alone; the configured one is named (read
  // from its file once, when a map is first loaded or handed over), and the mapping side checks
  // it as it loads the same file.
  apart_file_setup_ =
      places_ ? MappingSide::fileSetup(
                    config_, places_->orbVocabulary(),
                    configuredVocabularyIdentity(config_.loop.lbd_vocabulary, DescriptorKind::kLbd))
              : MappingSide::fileSetup(config_, {}, {});
  return *apart_file_setup_;
}

MapHandover System::handOverMap() {
  if (mapping_) throw std::logic_error("System::handOverMap: only with the mapping side apart");
  const MapFileSetup& setup = mapFileSetup();  // before the lock: the first call reads a file
  std::lock_guard<std::mutex> lock(tracking_map_->updateMutex());
  MapHandover handover;
  handover.map_file = MapFileWriter::encode(
      setup, *tracking_map_, places_ ? places_->places() : std::map<long, KeyFramePlace>{});
  handover.updates_followed = updates_followed_;
  handover.loaded_map = loaded_map_;
  handover.next_ids = tracking_map_->nextIds();
  report_ = TrackerReport{};
  followed_at_last_keyframe_ = updates_followed_;
  unanswered_jobs_.clear();  // the copy holds every keyframe handed over
  return handover;
}

void System::adoptTrackerCopy(MapFileContents copy) {
  tracking_map_->adopt(std::move(copy.keyframes), std::move(copy.points), std::move(copy.lines));
  if (!places_) return;
  const KeyFramePlace none;  // a keyframe without a record: every keypoint
  for (const auto& kf : tracking_map_->keyFrames()) {
    const auto place = copy.places.find(kf->id);
    places_->addLoaded(*kf, place != copy.places.end() ? place->second : none);
  }
}

Trajectory System::keyFrameTrajectory() const {
  std::lock_guard<std::mutex> lock(map().updateMutex());
  Trajectory trajectory;
  for (const auto& kf : map().keyFrames()) trajectory.push_back({kf->stamp, kf->T_wc()});
  return trajectory;
}

}  // namespace ply_slam
