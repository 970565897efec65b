#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <vector>

#include "ply_slam/loop/loop_detector.h"
#include "ply_slam/loop/loop_key_frame_builder.h"
#include "ply_slam/map/map_file_contents.h"
#include "ply_slam/mapping/loop_corrector.h"
#include "ply_slam/mapping/mapper_options.h"

namespace ply_slam {

struct LoopClosureCounts {
  long queries = 0;
  long detected = 0;     // queries with a candidate consistent over loop.consistency queries
  long accepted = 0;     // of them, a candidate passed the geometric check
  long implausible = 0;  // accepted, but asking for more correction than drift explains
  long corrected = 0;    // loops closed in the map
};

// The mapping side's place recognition: every keyframe goes into the database (points, lines,
// instances), is queried for a loop, and an accepted loop is closed in the map. The database has
// a mutex of its own: the query and the geometric check read nothing of the map and run without
// the map's lock (they take tens of ms where many candidates are consistent), while the tracker
// may ask recognise() from its thread. Lock order: the map's update lock, then the database's.
class LoopCloser {
 public:
  // Of `options` it reads loop, loop_correction, lines and mask_dilation_px.
  LoopCloser(LoopDetector detector, const PinholeCamera& camera, const MapperOptions& options,
             const LandmarkFuser& fuser, Map& map);

  // What the database keeps of a keyframe, from its packet alone (its lines are described
  // here: the slow part, which needs nothing of the map).
  LoopKeyFrame describe(const KeyFramePacket& packet) const { return builder_.build(packet); }
  // After the keyframe was fused and adjusted, with the map's lock held: into the database, its
  // covisibility from the map's. Returns whether it is to be queried (not too soon after the
  // last loop closed).
  bool addKeyFrame(const KeyFrame& keyframe, LoopKeyFrame described);
  // The query and the geometric check of keyframe `id` (added before), without the map's lock.
  // Returns the accepted loop, if any.
  std::optional<LoopDetection> detect(long id);
  // With the map's lock: closes an accepted loop of `keyframe` unless the candidate has left
  // the map or the correction is more than drift explains (`pauses`: see LoopCorrector).
  // Returns the correction.
  std::optional<LoopCorrection> close(KeyFrame& keyframe, const LoopDetection& detection,
                                      CorrectionPauses* pauses = nullptr);
  // A keyframe the mapper culled leaves the database.
  void removeKeyFrame(long id);
  // Relocalisation: keyframes that look like the descriptors, most similar first.
  std::vector<long> recognise(const cv::Mat& orb_descriptors, size_t max_results) const;
  const LoopClosureCounts& counts() const { return counts_; }
  // What the database keeps of a keyframe beyond its features (null: not in the database).
  std::optional<KeyFramePlace> place(const KeyFrame& keyframe) const;
  // A keyframe of a loaded map into the database, from its features and place (keyframes in id
  // order; then syncCovisibility of each).
  void addLoadedKeyFrame(const KeyFrame& keyframe, const KeyFramePlace& place);
  // The detector's covisibility of the keyframe and its neighbours, from the map's.
  void syncCovisibility(const KeyFrame& keyframe);
  // The vocabularies, named by their files (loop.orb_vocabulary, loop.lbd_vocabulary).
  MapVocabulary orbVocabulary() const;
  MapVocabulary lbdVocabulary() const;

 private:
  KeyFrame* keyFrame(long id) const;
  // The detector's covisibility of each keyframe (by id), from the map's; database mutex held.
  void syncCovisibilityLocked(const std::map<long, const KeyFrame*>& keyframes);
  // Whether the loop's shift of the query is within the drift the tracker could have gathered
  // since the candidate (LoopCorrectionOptions).
  bool plausible(const KeyFrame& query, const KeyFrame& candidate, const LoopShift& shift) const;

  mutable std::mutex detector_mutex_;  // detector_ and counts_
  LoopDetector detector_;
  LoopKeyFrameBuilder builder_;
  LoopCorrector corrector_;
  LoopCorrectionOptions options_;
  std::string orb_file_, lbd_file_;  // the vocabularies' file names
  Map& map_;
  LoopClosureCounts counts_;
  long last_loop_keyframe_ = -1;
};

}  // namespace ply_slam
