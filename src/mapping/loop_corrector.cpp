#include "ply_slam/mapping/loop_corrector.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "ply_slam/common/angles.h"
#include "ply_slam/common/stopwatch.h"
#include "ply_slam/mapping/carry_along.h"

namespace ply_slam {
namespace {

using KeyFrameIndex = std::unordered_map<long, KeyFrame*>;

KeyFrameIndex indexById(const std::vector<std::shared_ptr<KeyFrame>>& keyframes) {
  KeyFrameIndex index;
  for (const auto& kf : keyframes) index[kf->id] = kf.get();
  return index;
}

// The keyframe a landmark moves with: the one that created it, else its first observer still
// in the map (the creator was culled).
const KeyFrame* referenceOf(const MapPoint& point, const KeyFrameIndex& index) {
  const auto it = index.find(point.first_keyframe_id);
  if (it != index.end()) return it->second;
  for (const auto& o : point.observers)
    if (index.count(o.keyframe->id)) return o.keyframe;
  return nullptr;
}

// Covisibility is keyed by address: walked in id order, so that a run repeats itself whatever the
// heap's layout.
std::vector<std::pair<KeyFrame*, int>> byId(const std::map<KeyFrame*, int>& covisibility) {
  std::vector<std::pair<KeyFrame*, int>> links(covisibility.begin(), covisibility.end());
  std::sort(links.begin(), links.end(),
            [](const auto& a, const auto& b) { return a.first->id < b.first->id; });
  return links;
}

Eigen::Isometry3d relative(const Eigen::Isometry3d& T_w_from, const Eigen::Isometry3d& T_w_to) {
  return T_w_from.inverse() * T_w_to;
}

}  // namespace

LoopShift loopShift(const KeyFrame& query, const KeyFrame& candidate,
                    const Eigen::Isometry3d& T_query_candidate) {
  LoopShift shift;
  shift.query_T_wc = candidate.T_wc() * T_query_candidate.inverse();
  shift.moved_m = (shift.query_T_wc.translation() - query.T_wc().translation()).norm();
  shift.turned_deg = rotationAngleDeg(shift.query_T_wc.linear() * query.T_cw.linear());
  return shift;
}

LoopCorrection LoopCorrector::correct(KeyFrame& query, KeyFrame& candidate,
                                      const Eigen::Isometry3d& T_query_candidate,
                                      CorrectionPauses* pauses) {
  Stopwatch watch;
  LoopCorrection correction;
  correction.loop = {query.id, candidate.id, T_query_candidate};
  const auto keyframes = map_.keyFrames();
  const Poses before = posesOf(keyframes);
  correction.shift = loopShift(query, candidate, T_query_candidate);
  const Eigen::Isometry3d rigid = correction.shift.query_T_wc * query.T_wc().inverse();

  const std::vector<KeyFrame*> current_side = moveCurrentSide(query, rigid);
  correction.connected_keyframes = static_cast<int>(current_side.size());
  moveLandmarks(keyframes, before);
  if (pauses) pauses->movedRigidly(rigid);
  const auto links = fuseAcrossLoop(current_side, candidate, &correction.fused, pauses);

  loops_.push_back(correction.loop);
  PoseGraph graph = essentialGraph(keyframes, before, candidate, links);
  correction.loop_links = static_cast<int>(links.size());
  const auto optimise = [&] { correction.pose_graph = graph.optimise(options_.pose_graph); };
  pauses ? pauses->unlocked(optimise) : optimise();
  applyPoses(keyframes, graph);
  correction.world_correction = query.T_wc() * before.at(&query).inverse();
  correction.ms = watch.elapsedMs();
  return correction;
}

LoopCorrector::Poses LoopCorrector::posesOf(
    const std::vector<std::shared_ptr<KeyFrame>>& keyframes) {
  Poses poses;
  for (const auto& kf : keyframes) poses[kf.get()] = kf->T_wc();
  return poses;
}

std::vector<KeyFrame*> LoopCorrector::moveCurrentSide(KeyFrame& query,
                                                      const Eigen::Isometry3d& correction) {
  std::vector<KeyFrame*> side{&query};
  for (const auto& [kf, shared] : byId(query.covisibility)) side.push_back(kf);
  for (KeyFrame* kf : side) kf->T_cw = (correction * kf->T_wc()).inverse();
  return side;
}

std::vector<std::pair<KeyFrame*, KeyFrame*>> LoopCorrector::fuseAcrossLoop(
    const std::vector<KeyFrame*>& current_side, KeyFrame& candidate, int* fused,
    CorrectionPauses* pauses) {
  const std::set<KeyFrame*> current(current_side.begin(), current_side.end());
  std::vector<KeyFrame*> old_side{&candidate};
  for (KeyFrame* kf : candidate.bestCovisible(options_.loop_side_keyframes))
    if (!current.count(kf)) old_side.push_back(kf);
  const std::set<KeyFrame*> old(old_side.begin(), old_side.end());

  std::map<KeyFrame*, std::set<KeyFrame*>> linked_before;
  for (KeyFrame* kf : current_side)
    for (const auto& [other, shared] : kf->covisibility) linked_before[kf].insert(other);
  *fused = 0;
  for (KeyFrame* kf : current_side) {
    if (pauses) pauses->pause();
    const FusionCounts counts = fuser_.fuse(map_, *kf, old_side);
    *fused += counts.observations_added + counts.landmarks_merged;
  }

  // Links the fusion created between the two sides: the loop's own pose-graph edges.
  std::vector<std::pair<KeyFrame*, KeyFrame*>> links;
  for (KeyFrame* kf : current_side)
    for (const auto& [other, shared] : byId(kf->covisibility))
      if (old.count(other) && !linked_before[kf].count(other)) links.emplace_back(kf, other);
  return links;
}

PoseGraph LoopCorrector::essentialGraph(
    const std::vector<std::shared_ptr<KeyFrame>>& keyframes, const Poses& before,
    KeyFrame& candidate, const std::vector<std::pair<KeyFrame*, KeyFrame*>>& loop_links) const {
  PoseGraph graph;
  for (const auto& kf : keyframes)
    graph.addPose(kf->id, kf->T_wc(), kf.get() == &candidate || kf == keyframes.front());
  std::set<std::pair<long, long>> done;  // (smaller id, larger id)
  auto add = [&](const KeyFrame* from, const KeyFrame* to, const Eigen::Isometry3d& T_from_to) {
    if (!done.insert(std::minmax(from->id, to->id)).second) return;
    graph.addEdge(from->id, to->id, T_from_to);
  };
  const KeyFrameIndex index = indexById(keyframes);
  // Every loop so far (this one included), as its check measured it.
  for (const LoopEdge& loop : loops_) {
    const auto q = index.find(loop.query_id), c = index.find(loop.candidate_id);
    if (q != index.end() && c != index.end())
      add(c->second, q->second, loop.T_query_candidate.inverse());
  }
  // The strong links this loop's fusion created, measured from where the correction put the
  // current side.
  for (const auto& [current, old] : loop_links)
    if (current->covisibility.at(old) >= options_.strong_covisibility)
      add(old, current, relative(old->T_wc(), current->T_wc()));
  // The spanning tree and strong covisibility, as they were before the loop moved anything
  // (a link the fusion created is already in, measured across the loop).
  for (const auto& kf : keyframes) {
    if (kf->parent && index.count(kf->parent->id))
      add(kf->parent, kf.get(), relative(before.at(kf->parent), before.at(kf.get())));
    for (const auto& [other, shared] : byId(kf->covisibility)) {
      if (shared < options_.strong_covisibility || !before.count(other)) continue;
      add(other, kf.get(), relative(before.at(other), before.at(kf.get())));
    }
  }
  return graph;
}

void LoopCorrector::applyPoses(const std::vector<std::shared_ptr<KeyFrame>>& keyframes,
                               const PoseGraph& graph) {
  const Poses from = posesOf(keyframes);
  std::vector<std::pair<KeyFrame*, Eigen::Isometry3d>> all_before;  // T_wc, in id order
  for (const auto& kf : map_.keyFrames()) all_before.emplace_back(kf.get(), kf->T_wc());
  for (const auto& kf : keyframes) kf->T_cw = graph.pose(kf->id).inverse();
  moveLandmarks(keyframes, from);
  std::set<const KeyFrame*> solved;
  for (const auto& kf : keyframes) solved.insert(kf.get());
  carryAlong(map_, solved, all_before);
}

void LoopCorrector::moveLandmarks(const std::vector<std::shared_ptr<KeyFrame>>& keyframes,
                                  const Poses& from) {
  const KeyFrameIndex index = indexById(keyframes);
  auto moveOf = [&](const KeyFrame* reference) {
    return reference->T_wc() * from.at(reference).inverse();
  };
  for (const auto& point : map_.mapPoints()) {
    if (point->bad) continue;
    const KeyFrame* reference = referenceOf(*point, index);
    if (!reference) continue;
    point->moveBy(moveOf(reference));
  }
  for (const auto& line : map_.mapLines()) {
    if (line->bad) continue;
    const auto it = index.find(line->first_keyframe_id);
    if (it == index.end()) continue;
    line->moveBy(moveOf(it->second));
  }
}

}  // namespace ply_slam
