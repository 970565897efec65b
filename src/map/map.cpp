#include "ply_slam/map/map.h"

#include <algorithm>
#include <set>
#include <stdexcept>
#include <utility>

#include "ply_slam/map/by_id.h"
#include "ply_slam/map/landmark_values.h"

namespace ply_slam {

std::shared_ptr<KeyFrame> Map::addKeyFrame(std::shared_ptr<KeyFrame> keyframe) {
  std::lock_guard<std::mutex> lock(mutex_);
  keyframe->id = next_keyframe_id_++;
  keyframes_.push_back(keyframe);
  return keyframe;
}

void Map::adopt(std::vector<std::shared_ptr<KeyFrame>> keyframes,
                std::vector<std::shared_ptr<MapPoint>> points,
                std::vector<std::shared_ptr<MapLine>> lines) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!keyframes_.empty() || !points_.empty() || !lines_.empty())
    throw std::logic_error("Map::adopt: the map is not empty");
  for (const auto& kf : keyframes) next_keyframe_id_ = std::max(next_keyframe_id_, kf->id + 1);
  for (const auto& p : points) next_point_id_ = std::max(next_point_id_, p->id + 1);
  for (const auto& l : lines) next_line_id_ = std::max(next_line_id_, l->id + 1);
  keyframes_ = std::move(keyframes);
  points_ = std::move(points);
  lines_ = std::move(lines);
}

Map::Ids Map::nextIds() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return {next_keyframe_id_, next_point_id_, next_line_id_};
}

void Map::continueIdsFrom(const Ids& ids) {
  std::lock_guard<std::mutex> lock(mutex_);
  next_keyframe_id_ = std::max(next_keyframe_id_, ids.keyframe);
  next_point_id_ = std::max(next_point_id_, ids.point);
  next_line_id_ = std::max(next_line_id_, ids.line);
}

void Map::adoptKeyFrame(std::shared_ptr<KeyFrame> keyframe) {
  std::lock_guard<std::mutex> lock(mutex_);
  next_keyframe_id_ = std::max(next_keyframe_id_, keyframe->id + 1);
  keyframes_.push_back(std::move(keyframe));
}

void Map::adoptPoint(std::shared_ptr<MapPoint> point) {
  std::lock_guard<std::mutex> lock(mutex_);
  next_point_id_ = std::max(next_point_id_, point->id + 1);
  points_.push_back(std::move(point));
}

void Map::adoptLine(std::shared_ptr<MapLine> line) {
  std::lock_guard<std::mutex> lock(mutex_);
  next_line_id_ = std::max(next_line_id_, line->id + 1);
  lines_.push_back(std::move(line));
}

std::shared_ptr<MapPoint> Map::createMapPoint(const Eigen::Vector3d& position,
                                              const cv::Mat& descriptor, long keyframe_id) {
  auto point = std::make_shared<MapPoint>();
  point->position = position;
  point->descriptor = descriptor.clone();
  point->first_keyframe_id = keyframe_id;
  std::lock_guard<std::mutex> lock(mutex_);
  point->id = next_point_id_++;
  points_.push_back(point);
  return point;
}

void Map::addObservation(KeyFrame& keyframe, size_t index, const std::shared_ptr<MapPoint>& point) {
  std::lock_guard<std::mutex> lock(mutex_);
  addObservationLocked(keyframe, index, point);
  note({MapJournal::Change::kAddObservation, keyframe.id, point->id, -1, index});
}

void Map::addObservationLocked(KeyFrame& keyframe, size_t index,
                               const std::shared_ptr<MapPoint>& point) {
  keyframe.map_points[index] = point;
  for (const auto& o : point->observers) {
    if (o.keyframe == &keyframe) continue;
    ++keyframe.covisibility[o.keyframe];
    ++o.keyframe->covisibility[&keyframe];
  }
  point->observers.push_back({&keyframe, index});
}

void Map::removeObservation(KeyFrame& keyframe, size_t index) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!keyframe.map_points[index]) return;
  removeObservationLocked(keyframe, index);
  note({MapJournal::Change::kRemoveObservation, keyframe.id, -1, -1, index});
}

void Map::removeObservationLocked(KeyFrame& keyframe, size_t index) {
  const auto point = keyframe.map_points[index];
  if (!point) return;
  keyframe.map_points[index] = nullptr;
  auto& observers = point->observers;
  const auto entry = std::find_if(
      observers.begin(), observers.end(),
      [&](const MapPoint::Observer& o) { return o.keyframe == &keyframe && o.index == index; });
  if (entry != observers.end()) observers.erase(entry);
  for (const auto& o : observers) {
    if (o.keyframe == &keyframe) continue;
    // Covisibility counts shared landmarks; this one is no longer shared.
    if (--keyframe.covisibility[o.keyframe] <= 0) keyframe.covisibility.erase(o.keyframe);
    if (--o.keyframe->covisibility[&keyframe] <= 0) o.keyframe->covisibility.erase(&keyframe);
  }
}

void Map::replace(const std::shared_ptr<MapPoint>& loser, const std::shared_ptr<MapPoint>& winner) {
  std::lock_guard<std::mutex> lock(mutex_);
  replaceLocked(loser, winner);
  note({MapJournal::Change::kReplace, -1, loser->id, winner->id});
}

void Map::replaceLocked(const std::shared_ptr<MapPoint>& loser,
                        const std::shared_ptr<MapPoint>& winner) {
  const auto observers = loser->observers;
  for (const auto& o : observers) {
    removeObservationLocked(*o.keyframe, o.index);
    const bool seen =
        std::any_of(winner->observers.begin(), winner->observers.end(),
                    [&](const MapPoint::Observer& w) { return w.keyframe == o.keyframe; });
    if (!seen) addObservationLocked(*o.keyframe, o.index, winner);
  }
  winner->visible += loser->visible;
  winner->found += loser->found;
  winner->fuse(loser->position, loser->position_weight);
  loser->bad = true;
  loser->replaced_by = winner;
}

namespace {

// Moves the bad landmarks out of `landmarks` (order kept) and appends their ids to `removed`.
template <typename Landmark>
size_t removeBad(std::vector<std::shared_ptr<Landmark>>& landmarks, std::vector<long>& removed) {
  const auto bad = std::stable_partition(landmarks.begin(), landmarks.end(),
                                         [](const auto& l) { return !l->bad; });
  for (auto it = bad; it != landmarks.end(); ++it) removed.push_back((*it)->id);
  const size_t count = static_cast<size_t>(landmarks.end() - bad);
  landmarks.erase(bad, landmarks.end());
  return count;
}

}  // namespace

size_t Map::removeBadLandmarks() {
  std::lock_guard<std::mutex> lock(mutex_);
  return removeBad(points_, removed_points_) + removeBad(lines_, removed_lines_);
}

std::vector<long> Map::takeRemovedPoints() {
  std::lock_guard<std::mutex> lock(mutex_);
  return std::exchange(removed_points_, {});
}

std::vector<long> Map::takeRemovedLines() {
  std::lock_guard<std::mutex> lock(mutex_);
  return std::exchange(removed_lines_, {});
}

void Map::erasePoint(const std::shared_ptr<MapPoint>& point) {
  std::lock_guard<std::mutex> lock(mutex_);
  erasePointLocked(*point);
  note({MapJournal::Change::kErasePoint, -1, point->id});
}

void Map::erasePointLocked(MapPoint& point) {
  const auto observers = point.observers;
  for (const auto& o : observers)
    if (o.keyframe->map_points[o.index].get() == &point)
      removeObservationLocked(*o.keyframe, o.index);
  point.observers.clear();
  point.bad = true;
}

std::shared_ptr<KeyFrame> Map::eraseKeyFrame(KeyFrame& keyframe, int min_point_observers) {
  std::lock_guard<std::mutex> lock(mutex_);
  auto erased = eraseKeyFrameLocked(keyframe, min_point_observers);
  if (erased)
    note({MapJournal::Change::kEraseKeyFrame, keyframe.id, -1, -1, 0, min_point_observers});
  return erased;
}

std::shared_ptr<KeyFrame> Map::eraseKeyFrameLocked(KeyFrame& keyframe, int min_point_observers) {
  const auto it = std::find_if(keyframes_.begin(), keyframes_.end(),
                               [&](const auto& kf) { return kf.get() == &keyframe; });
  if (it == keyframes_.end() || it == keyframes_.begin() || !keyframe.parent) return nullptr;
  unlinkLandmarksLocked(keyframe, min_point_observers);
  reparentChildrenLocked(keyframe);
  std::shared_ptr<KeyFrame> erased = *it;  // may be the last reference: keep it past erase
  keyframes_.erase(it);
  erased->parent = nullptr;
  erased->bad = true;
  return erased;
}

void Map::journalTo(MapJournal* journal) {
  std::lock_guard<std::mutex> lock(mutex_);
  journal_ = journal;
}

void Map::note(const MapJournal::Entry& entry) {
  if (journal_) journal_->entries.push_back(entry);
}

void Map::replay(const MapJournal& journal) {
  std::lock_guard<std::mutex> lock(mutex_);
  replayLocked(journal, byId(keyframes_), byId(points_));
}

void Map::replayLocked(const MapJournal& journal, const KeyFramesById& keyframes,
                       const PointsById& points) {
  for (const auto& e : journal.entries) {
    const auto kf = keyframes.find(e.keyframe);
    const auto point = points.find(e.point);
    const bool has_kf = kf != keyframes.end(), has_point = point != points.end();
    using Change = MapJournal::Change;
    if (e.change == Change::kAddObservation && has_kf && has_point) {
      addObservationFollowed(*kf->second, e.index, point->second);
    } else if (e.change == Change::kRemoveObservation && has_kf) {
      removeObservationLocked(*kf->second, e.index);
    } else if (e.change == Change::kReplace && has_point && points.count(e.winner)) {
      replaceLocked(point->second, points.at(e.winner));
    } else if (e.change == Change::kErasePoint && has_point) {
      erasePointLocked(*point->second);
    } else if (e.change == Change::kEraseKeyFrame && has_kf) {
      eraseKeyFrameLocked(*kf->second, e.min_point_observers);
    }
  }
}

void Map::relinkLocked(const MapUpdate::KeyFrameLinks& links, const KeyFramesById& keyframes,
                       const PointsById& points) {
  const auto kf = keyframes.find(links.keyframe);
  if (kf == keyframes.end()) return;
  KeyFrame& keyframe = *kf->second;
  std::vector<std::shared_ptr<MapPoint>> wanted(keyframe.map_points.size());
  for (const auto& [index, id] : links.points)
    if (const auto p = points.find(id); p != points.end() && index < wanted.size())
      wanted[index] = p->second;
  // Unlink first: a point may move from one keypoint to another.
  for (size_t i = 0; i < wanted.size(); ++i)
    if (keyframe.map_points[i] != wanted[i]) removeObservationLocked(keyframe, i);
  for (size_t i = 0; i < wanted.size(); ++i)
    if (wanted[i] && keyframe.map_points[i] != wanted[i])
      addObservationLocked(keyframe, i, wanted[i]);
}

void Map::addObservationFollowed(KeyFrame& keyframe, size_t index,
                                 const std::shared_ptr<MapPoint>& point) {
  const auto& held = keyframe.map_points[index];
  if (held == point) return;
  // A copy ahead of the mapping side (its keyframe made before a merge it followed) may hold
  // a link there the mapping side has not got: the mapping side's wins. Never so in line.
  if (held) removeObservationLocked(keyframe, index);
  addObservationLocked(keyframe, index, point);
}

void Map::apply(const MapUpdate& update) {
  std::lock_guard<std::mutex> lock(mutex_);
  // Points stay in points_ until removeBad below (erased ones marked bad): one index serves.
  const auto points = byId(points_);
  {
    const auto followed = byId(keyframes_);
    relinkLocked(update.replayed, followed, points);
    replayLocked(update.journal, followed, points);
  }
  const auto keyframes = byId(keyframes_);  // without those the journal erased
  for (const auto& pose : update.keyframes)
    if (const auto kf = keyframes.find(pose.id); kf != keyframes.end()) {
      kf->second->T_cw = pose.T_cw;
      const auto parent = keyframes.find(pose.parent);
      kf->second->parent = parent != keyframes.end() ? parent->second.get() : nullptr;
    }
  for (const auto& values : update.points)
    if (const auto p = points.find(values.id); p != points.end()) setValues(*p->second, values);
  const auto lines = byId(lines_);
  for (const auto& values : update.lines)
    if (const auto l = lines.find(values.id); l != lines.end()) setValues(*l->second, values);
  eraseGone(update, points, lines);
  removeBad(points_, removed_points_);
  removeBad(lines_, removed_lines_);
}

void Map::eraseGone(const MapUpdate& update, const PointsById& points, const LinesById& lines) {
  // A copy ahead of the mapping side links landmarks of its own to what the mapping side
  // erased with a keyframe (it saw them from more keyframes): gone all the same. In line the
  // journal erased them already.
  for (long id : update.erased_points)
    if (const auto p = points.find(id); p != points.end() && !p->second->bad)
      erasePointLocked(*p->second);
  std::set<const MapLine*> gone;
  for (long id : update.erased_lines)
    if (const auto l = lines.find(id); l != lines.end() && !l->second->bad) {
      l->second->bad = true;
      gone.insert(l->second.get());
    }
  if (gone.empty()) return;
  for (const auto& kf : keyframes_)
    for (auto& line : kf->map_lines)
      if (line && gone.count(line.get())) line = nullptr;
}

void Map::unlinkLandmarksLocked(KeyFrame& keyframe, int min_point_observers) {
  for (size_t i = 0; i < keyframe.map_points.size(); ++i) {
    const auto point = keyframe.map_points[i];
    if (!point) continue;
    removeObservationLocked(keyframe, i);
    if (!point->bad && point->observations() < min_point_observers) erasePointLocked(*point);
  }
  for (auto& line : keyframe.map_lines) {
    if (line && --line->observations <= 0) line->bad = true;
    line = nullptr;
  }
  // Every link came from a shared point and is gone by now; this only guards the invariant.
  for (const auto& [other, shared] : keyframe.covisibility) other->covisibility.erase(&keyframe);
  keyframe.covisibility.clear();
}

// The children go to the keyframe they share the most landmarks with among the erased one's
// parent and the children already moved (ORB-SLAM's rule): the tree's edges become pose-graph
// edges and are best where many landmarks tie the two poses. None of those candidates lies
// below a child still waiting, so no cycle can form; a child sharing nothing with any of them
// goes to the erased keyframe's parent, which keeps the tree rooted at the first keyframe.
void Map::reparentChildrenLocked(KeyFrame& keyframe) {
  std::vector<KeyFrame*> children;  // in id order: keyframes_ is
  for (const auto& kf : keyframes_)
    if (kf->parent == &keyframe) children.push_back(kf.get());
  std::vector<KeyFrame*> candidates{keyframe.parent};
  while (!children.empty()) {
    int best = 0;
    size_t best_child = 0;
    KeyFrame* best_parent = nullptr;
    for (size_t c = 0; c < children.size(); ++c)
      for (KeyFrame* candidate : candidates) {
        const auto link = children[c]->covisibility.find(candidate);
        if (link == children[c]->covisibility.end() || link->second <= best) continue;
        best = link->second;
        best_child = c;
        best_parent = candidate;
      }
    if (!best_parent) break;
    children[best_child]->parent = best_parent;
    candidates.push_back(children[best_child]);
    children.erase(children.begin() + static_cast<long>(best_child));
  }
  for (KeyFrame* child : children) child->parent = keyframe.parent;
}

std::vector<std::shared_ptr<KeyFrame>> Map::keyFrames() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return keyframes_;
}

std::shared_ptr<KeyFrame> Map::keyFrame(long id) const {
  std::lock_guard<std::mutex> lock(mutex_);
  // From the newest: the one asked for is mostly among the last.
  const auto found = std::find_if(keyframes_.rbegin(), keyframes_.rend(),
                                  [id](const auto& kf) { return kf->id == id; });
  return found != keyframes_.rend() ? *found : nullptr;
}

std::vector<std::shared_ptr<MapPoint>> Map::mapPoints() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return points_;
}

size_t Map::numKeyFrames() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return keyframes_.size();
}

size_t Map::numMapPoints() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return points_.size();
}

std::shared_ptr<MapLine> Map::createMapLine(const Eigen::Vector3d& start,
                                            const Eigen::Vector3d& end, const cv::Mat& descriptor,
                                            long keyframe_id) {
  auto line = std::make_shared<MapLine>();
  line->start = start;
  line->end = end;
  line->descriptor = descriptor.clone();
  line->first_keyframe_id = keyframe_id;
  std::lock_guard<std::mutex> lock(mutex_);
  line->id = next_line_id_++;
  lines_.push_back(line);
  return line;
}

std::vector<std::shared_ptr<MapLine>> Map::mapLines() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return lines_;
}

size_t Map::numMapLines() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return lines_.size();
}

}  // namespace ply_slam
