#pragma once

#include <Eigen/Geometry>
#include <deque>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "ply_slam/map/map.h"
#include "ply_slam/map/map_file_contents.h"
#include "ply_slam/mapping/mapper.h"
#include "ply_slam/system/mapping_job.h"
#include "ply_slam/system/system_config.h"

namespace ply_slam {

// The mapping side of the system (issue 17): the map, the Mapper working on it and, for each
// keyframe the tracker hands over, what the copies of the map need to follow it
// (MappedKeyFrame: the keyframe's packet, the update, the loop correction). With
// `follows_reports` (the split modes, and a mapping process of its own) its map follows the
// tracker's copy by the reports in the jobs, and each update carries the journal of who sees
// what and the world corrections the tracker moves along with; it remembers the points it
// merged away that later reports may still name until the tracker's copy has followed the merge.
// Without, the tracker works in this map itself and is told of corrections by the Mapper.
//
// Threads: mapKeyFrame runs on one thread at a time (the mapping side's) and takes the map's
// lock itself, step by step, as the Mapper does.
class MappingSide {
 public:
  struct Hooks {
    // Keyframe ids culling must leave (the tracker's reference keyframe now); with the map's
    // lock. None: the job's reference_keyframe.
    Mapper::KeepKeyFrames keep;
    // Keyframes just culled, with the map's lock held: their poses still agree with the map's.
    std::function<void(const std::vector<long>& culled)> culled;
    // A job's report and keyframe done to the map, with the map's lock held.
    std::function<void()> replayed;
  };

  // Throws std::runtime_error naming a vocabulary that does not load (loop.enabled).
  MappingSide(const SystemConfig& config, bool follows_reports, bool wait_for_global_ba);
  MappingSide(const MappingSide&) = delete;
  MappingSide& operator=(const MappingSide&) = delete;

  // Before the first job.
  void setHooks(Hooks hooks) { hooks_ = std::move(hooks); }
  // Maps the job's keyframe: the tracker's report replayed (follows_reports), map upkeep and
  // local BA, its packet, the loop query. A job without a keyframe writes back a global bundle
  // adjustment that ended (the whole map moves). Throws what checkJob throws, the side unchanged.
  MappedKeyFrame mapKeyFrame(const MappingJob& job);
  // Throws std::invalid_argument when the job's keyframe was made in a map that started from
  // another map file than this side's (MappingJob::loaded_map): its ids would name other things.
  void checkJob(const MappingJob& job) const;

  // The camera, pyramid and vocabularies a map file of this side's map records; `fileSetup`
  // gives them for a system with these vocabularies (a tracker apart has no MappingSide).
  const MapFileSetup& mapFileSetup() const { return file_setup_; }
  static MapFileSetup fileSetup(const SystemConfig& config, MapVocabulary orb, MapVocabulary lbd);
  // Before the first job: takes the map saved in `file` with its place records (`scales`: the
  // ORB pyramid's per level, outliving the map). Throws std::runtime_error naming the file and
  // the fault, the side unchanged; std::logic_error when the map is not empty.
  void loadMap(const std::string& file, const std::vector<double>* scales);
  // Before the first job, for a mapping side that starts anew while a tracker apart goes on:
  // the map becomes the tracker's copy (System::handOverMap), and its updates count on from
  // those the copy followed. Throws std::runtime_error naming the fault (MapFileReader), the
  // side unchanged; std::logic_error when the map is not empty.
  void takeOver(const MapHandover& handover, const std::vector<double>* scales);
  // For a tracker apart that starts anew while this side goes on (tracking_node restarted): the
  // map with its place records, the updates made and the map file it started from
  // (System::takeOverMap). Between two jobs; an empty map_file when the map is empty.
  MapHandover handOverMap() const;
  // The checksum of the map file loaded (MapFileContents::checksum); 0: started empty.
  uint64_t loadedMap() const { return loaded_map_; }
  // Writes the map with its place records into `file` (MapFileWriter) under the map's lock;
  // the folder is created. Throws std::runtime_error naming the file.
  void saveMap(const std::string& file) const;

  Map& map() { return map_; }
  const Map& map() const { return map_; }
  Mapper& mapper() { return mapper_; }
  const Mapper& mapper() const { return mapper_; }

 private:
  // loadMap's and takeOver's map, read and checked, into the empty map.
  void adopt(MapFileContents contents);
  // Replays the job's report, moved to where the map has the keyframe it was made from; returns
  // the keyframe's point links it made.
  MapUpdate::KeyFrameLinks followTracker(const MappingJob& job);
  // How the keyframe of the tracker's job before (MappingJob::made_after) moved since the
  // tracker made this job's keyframe (T_wc now * T_wc then^-1); none when it has not moved (or
  // left the map).
  std::optional<Eigen::Isometry3d> moveSinceTracked(const MappingJob& job) const;
  KeyFrameInsertionStats insertKeyFrame(const MappingJob& job, MappedKeyFrame& out);
  // What it did, for the copies of the map (`mapped`: none for a global bundle adjustment
  // written back alone).
  MapUpdate updateOf(const std::optional<KeyFrameInsertionStats>& mapped, bool whole_map,
                     MapJournal journal);

  const PinholeCamera camera_;
  const bool follows_reports_;
  Map map_;
  Mapper mapper_;
  MapFileSetup file_setup_;
  uint64_t loaded_map_ = 0;
  Hooks hooks_;
  // How the Mapper moved the world while mapping a keyframe, in order, for its update.
  std::vector<Eigen::Isometry3d> corrections_;
  // The updates made, and the points merged away that reports may still name, with the update
  // that merged each (kept until a job says the tracker's copy followed it).
  long updates_made_ = 0;
  LandmarkCreator::MergedPoints merged_;
  std::deque<std::pair<long, long>> merge_log_;  // (update, loser id), oldest first
};

}  // namespace ply_slam
