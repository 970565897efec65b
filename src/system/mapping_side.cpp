#include "ply_slam/system/mapping_side.h"

#include <filesystem>
#include <set>
#include <sstream>
#include <stdexcept>

#include "ply_slam/common/stopwatch.h"
#include "ply_slam/map/map_file_reader.h"
#include "ply_slam/map/map_file_writer.h"
#include "ply_slam/system/key_frame_packet_builder.h"

namespace ply_slam {

MappingSide::MappingSide(const SystemConfig& config, bool follows_reports, bool wait_for_global_ba)
    : camera_(config.camera),
      follows_reports_(follows_reports),
      mapper_(config.camera, mapperOptions(config), map_, wait_for_global_ba),
      file_setup_(fileSetup(config, mapper_.orbVocabulary(), mapper_.lbdVocabulary())) {
  // Whoever tracks in a copy moves along when it follows the update that says so.
  if (follows_reports_)
    mapper_.setCorrectionListener(
        [this](const Eigen::Isometry3d& correction) { corrections_.push_back(correction); });
}

MapFileSetup MappingSide::fileSetup(const SystemConfig& config, MapVocabulary orb,
                                    MapVocabulary lbd) {
  MapFileSetup setup;
  setup.camera = config.camera;
  setup.orb_levels = config.orb.num_levels;
  setup.orb_scale_factor = config.orb.scale_factor;
  setup.orb_vocabulary = std::move(orb);
  setup.lbd_vocabulary = std::move(lbd);
  return setup;
}

void MappingSide::loadMap(const std::string& file, const std::vector<double>* scales) {
  if (map_.numKeyFrames() != 0)
    throw std::logic_error("MappingSide::loadMap: the map is not empty");
  MapFileContents loaded = MapFileReader::read(file, file_setup_, scales);
  loaded_map_ = loaded.checksum;
  adopt(std::move(loaded));
}

void MappingSide::takeOver(const MapHandover& handover, const std::vector<double>* scales) {
  if (map_.numKeyFrames() != 0)
    throw std::logic_error("MappingSide::takeOver: the map is not empty");
  adopt(MapFileReader::decode(handover.map_file, "the tracker's copy of the map", file_setup_,
                              scales));
  map_.continueIdsFrom(handover.next_ids);
  loaded_map_ = handover.loaded_map;
  updates_made_ = handover.updates_followed;
}

MapHandover MappingSide::handOverMap() const {
  std::lock_guard<std::mutex> lock(map_.updateMutex());
  MapHandover handover;
  if (map_.numKeyFrames() != 0)
    handover.map_file = MapFileWriter::encode(file_setup_, map_, mapper_.places());
  handover.updates_followed = updates_made_;
  handover.loaded_map = loaded_map_;
  handover.next_ids = map_.nextIds();
  return handover;
}

void MappingSide::adopt(MapFileContents contents) {
  map_.adopt(std::move(contents.keyframes), std::move(contents.points), std::move(contents.lines));
  mapper_.addLoadedKeyFrames(contents.places);
}

void MappingSide::checkJob(const MappingJob& job) const {
  if (!job.keyframe || job.loaded_map == loaded_map_) return;
  auto name = [](uint64_t checksum) {
    if (checksum == 0) return std::string("no map file (an empty map)");
    std::ostringstream text;
    text << "the map file with checksum " << std::hex << checksum;
    return text.str();
  };
  throw std::invalid_argument("keyframe " + std::to_string(job.keyframe->id) +
                              " was made by a tracker that started from " + name(job.loaded_map) +
                              ", this mapping side from " + name(loaded_map_) +
                              ": both must load the same map");
}

void MappingSide::saveMap(const std::string& file) const {
  const std::filesystem::path folder = std::filesystem::path(file).parent_path();
  if (!folder.empty()) std::filesystem::create_directories(folder);
  std::lock_guard<std::mutex> lock(map_.updateMutex());
  MapFileWriter::write(file, file_setup_, map_, mapper_.places());
}

MappedKeyFrame MappingSide::mapKeyFrame(const MappingJob& job) {
  checkJob(job);
  Stopwatch mapping;
  MappedKeyFrame out;
  MapUpdate::KeyFrameLinks replayed;
  if (follows_reports_ && job.keyframe) replayed = followTracker(job);
  // A copy following by reports follows by what this does to the map.
  MapJournal journal;
  if (follows_reports_) map_.journalTo(&journal);
  std::optional<KeyFrameInsertionStats> mapped;
  if (job.keyframe) {
    mapped = insertKeyFrame(job, out);
  } else {  // no keyframe: a global bundle adjustment that ended to write back
    mapper_.applySolvedGlobalBundleAdjustment();
  }
  if (follows_reports_) map_.journalTo(nullptr);
  const bool whole_map = !mapped || out.loop_correction || mapped->global_ba_applied;
  MapUpdate update = updateOf(mapped, whole_map, std::move(journal));
  update.replayed = std::move(replayed);
  out.map_update = std::make_shared<const MapUpdate>(std::move(update));
  out.ms = mapping.elapsedMs();
  return out;
}

MapUpdate::KeyFrameLinks MappingSide::followTracker(const MappingJob& job) {
  // Merges the tracker's copy had followed before the report began are no longer named in it.
  while (!merge_log_.empty() && merge_log_.front().first <= job.followed_updates) {
    merged_.erase(merge_log_.front().second);
    merge_log_.pop_front();
  }
  // A keyframe made before the tracker followed the updates that moved the keyframe it was made
  // from (local BA, a loop's correction) is where the tracker had that one: it moves with it. In
  // line, or when the tracker keeps up, nothing moved.
  const TrackerReport* report = &job.report;
  TrackerReport moved;
  if (const auto move = moveSinceTracked(job)) {
    job.keyframe->T_cw = job.keyframe->T_cw * move->inverse();
    moved = job.report;
    moveTrackerReport(moved, *move);
    report = &moved;
  }
  std::lock_guard<std::mutex> lock(map_.updateMutex());
  mapper_.replay(*report, job.keyframe, merged_);
  if (hooks_.replayed) hooks_.replayed();
  MapUpdate::KeyFrameLinks links{job.keyframe->id, {}};
  const auto& points = job.keyframe->map_points;
  for (size_t i = 0; i < points.size(); ++i)
    if (points[i]) links.points.emplace_back(i, points[i]->id);
  return links;
}

std::optional<Eigen::Isometry3d> MappingSide::moveSinceTracked(const MappingJob& job) const {
  if (job.made_after < 0) return std::nullopt;
  const std::shared_ptr<KeyFrame> before = map_.keyFrame(job.made_after);
  if (!before || before->bad || before->T_cw.matrix() == job.made_after_T_cw.matrix())
    return std::nullopt;
  return before->T_wc() * job.made_after_T_cw;
}

KeyFrameInsertionStats MappingSide::insertKeyFrame(const MappingJob& job, MappedKeyFrame& out) {
  KeyFrame& keyframe = *job.keyframe;
  const Mapper::KeepKeyFrames keep_reference = [&job] {
    return std::set<long>{job.reference_keyframe};
  };
  KeyFrameInsertionStats mapped =
      mapper_.insertKeyFrame(job.keyframe, hooks_.keep ? hooks_.keep : keep_reference);
  out.culled_points = mapped.culled_points;
  out.merged_points = mapped.fused.landmarks_merged;
  out.fused_observations = mapped.fused.observations_added;
  {
    std::lock_guard<std::mutex> lock(map_.updateMutex());
    if (hooks_.culled && !mapped.culled_keyframes.empty()) hooks_.culled(mapped.culled_keyframes);
    out.packet = std::make_shared<const KeyFramePacket>(
        makeKeyFramePacket(keyframe, camera_, job.images, job.segmentation));
  }
  if (auto correction = mapper_.closeLoop(keyframe, *out.packet))
    out.loop_correction = std::make_shared<const LoopCorrection>(std::move(*correction));
  return mapped;
}

MapUpdate MappingSide::updateOf(const std::optional<KeyFrameInsertionStats>& mapped, bool whole_map,
                                MapJournal journal) {
  MapUpdate update = whole_map ? mapper_.wholeMap() : mapped->adjusted;
  if (mapped) update.erased_keyframes = mapped->culled_keyframes;
  update.erased_points = map_.takeRemovedPoints();
  update.erased_lines = map_.takeRemovedLines();
  update.journal = std::move(journal);
  update.world_corrections = std::exchange(corrections_, {});
  ++updates_made_;
  for (const auto& e : update.journal.entries)
    if (e.change == MapJournal::Change::kReplace) {
      merged_[e.point] = e.winner;
      merge_log_.emplace_back(updates_made_, e.point);
    }
  return update;
}

}  // namespace ply_slam
