#pragma once

#include <Eigen/Geometry>
#include <functional>
#include <unordered_map>
#include <vector>

#include "ply_slam/map/key_frame_packet.h"
#include "ply_slam/map/map.h"
#include "ply_slam/mapping/landmark_fuser.h"
#include "ply_slam/mapping/loop_correction_options.h"
#include "ply_slam/mapping/pose_graph.h"

namespace ply_slam {

// A verified loop: p_query = T_query_candidate * p_candidate (camera frames).
struct LoopEdge {
  long query_id = 0;
  long candidate_id = 0;
  Eigen::Isometry3d T_query_candidate = Eigen::Isometry3d::Identity();
};

// Where a verified loop puts the query keyframe (T_wc), and how far that is from where tracking
// had it: camera centre shift and rotation.
struct LoopShift {
  Eigen::Isometry3d query_T_wc = Eigen::Isometry3d::Identity();
  double moved_m = 0.0, turned_deg = 0.0;
};
LoopShift loopShift(const KeyFrame& query, const KeyFrame& candidate,
                    const Eigen::Isometry3d& T_query_candidate);

struct LoopCorrection {
  LoopEdge loop;
  // How the current keyframe moved: T_wc(after) = world_correction * T_wc(before). The tracker
  // moves its own pose by the same.
  Eigen::Isometry3d world_correction = Eigen::Isometry3d::Identity();
  LoopShift shift;              // of the current keyframe, before the pose graph spreads it
  int connected_keyframes = 0;  // the current side, moved rigidly before the pose graph
  int fused = 0;                // observations added and landmarks merged across the loop
  int loop_links = 0;           // pose-graph edges across the loop
  PoseGraphSummary pose_graph;
  double global_ba_ms = 0.0;  // the bundle adjustment of the whole map after the pose graph
  double ms = 0.0;            // the whole correction, global bundle adjustment included
};

// How a loop correction lets the tracker at the map between its steps (on the mapping thread;
// without it, the correction holds the map's lock from start to end, as in line).
class CorrectionPauses {
 public:
  virtual ~CorrectionPauses() = default;
  // The current side moved rigidly: T_wc(after) = world_correction * T_wc(before). Whoever
  // tracks in the map must move along before it tracks again. Map's lock held.
  virtual void movedRigidly(const Eigen::Isometry3d& world_correction) = 0;
  // Between two steps: lets go of the map's lock and takes it again.
  virtual void pause() = 0;
  // Runs `work`, which reads nothing of the map, without the map's lock.
  virtual void unlocked(const std::function<void()>& work) = 0;
};

// Closes a verified loop in the map (ORB-SLAM's loop correction, SE(3) for RGB-D):
// 1. the current keyframe and its covisible keyframes move rigidly to where the loop puts the
//    current keyframe, their landmarks with them;
// 2. the old side's landmarks are fused into the current side (one landmark per corner again);
// 3. a pose graph over the essential graph (spanning tree, strong covisibility, this and earlier
//    loops) spreads the remaining error over the keyframes between the two visits;
// 4. every landmark follows its reference keyframe (the one that created it); keyframes the
//    tracker made during the correction (with `pauses`) follow the keyframe made before them.
// With `pauses`, the tracker tracks between the steps: after the rigid move, between the fusion
// of one current-side keyframe and the next, and while the pose graph is solved.
class LoopCorrector {
 public:
  LoopCorrector(const LoopCorrectionOptions& options, const LandmarkFuser& fuser, Map& map)
      : options_(options), fuser_(fuser), map_(map) {}

  LoopCorrection correct(KeyFrame& query, KeyFrame& candidate,
                         const Eigen::Isometry3d& T_query_candidate,
                         CorrectionPauses* pauses = nullptr);
  const std::vector<LoopEdge>& loops() const { return loops_; }

 private:
  using Poses = std::unordered_map<const KeyFrame*, Eigen::Isometry3d>;  // T_wc

  static Poses posesOf(const std::vector<std::shared_ptr<KeyFrame>>& keyframes);
  // Moves the current side rigidly; returns its keyframes.
  std::vector<KeyFrame*> moveCurrentSide(KeyFrame& query, const Eigen::Isometry3d& correction);
  // Fuses the old side's landmarks into the current side; returns the new links between them.
  std::vector<std::pair<KeyFrame*, KeyFrame*>> fuseAcrossLoop(
      const std::vector<KeyFrame*>& current_side, KeyFrame& candidate, int* fused,
      CorrectionPauses* pauses);
  PoseGraph essentialGraph(const std::vector<std::shared_ptr<KeyFrame>>& keyframes,
                           const Poses& before, KeyFrame& candidate,
                           const std::vector<std::pair<KeyFrame*, KeyFrame*>>& loop_links) const;
  // Keyframes to the graph's poses; each landmark follows its reference keyframe's move, and
  // keyframes made since `keyframes` was taken follow along (carryAlong).
  void applyPoses(const std::vector<std::shared_ptr<KeyFrame>>& keyframes, const PoseGraph& graph);
  void moveLandmarks(const std::vector<std::shared_ptr<KeyFrame>>& keyframes, const Poses& from);

  LoopCorrectionOptions options_;
  const LandmarkFuser& fuser_;
  Map& map_;
  std::vector<LoopEdge> loops_;  // every loop closed so far: edges of each later pose graph
};

}  // namespace ply_slam
