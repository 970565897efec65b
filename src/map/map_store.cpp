#include "ply_slam/map/map_store.h"

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <set>
#include <stdexcept>

#include "ply_slam/io/atomic_file.h"
#include "ply_slam/io/file_writes.h"
#include "ply_slam/io/tum_trajectory_file.h"

namespace ply_slam {
namespace {

void writeVertex(std::ostream& out, const Eigen::Vector3d& p) {
  out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
}

}  // namespace

bool MapStore::insert(const KeyFramePacket& packet) {
  const auto it = keyframes_.find(packet.id);
  if (it != keyframes_.end() && it->second.stamp > packet.stamp) return false;
  KeyFramePacket kept = packet;
  kept.rgb.release();
  kept.depth.release();
  kept.label_image.release();
  kept.dynamic_mask.release();
  keyframes_[packet.id] = std::move(kept);
  for (const auto& p : packet.points) points_[p.id] = p;
  for (const auto& l : packet.lines) lines_[l.id] = l;
  return true;
}

void MapStore::apply(const MapUpdate& update) {
  for (const auto& k : update.keyframes) {
    const auto it = keyframes_.find(k.id);
    if (it != keyframes_.end()) it->second.T_wc = k.T_wc();
  }
  for (const auto& p : update.points) points_[p.id] = p;
  for (const auto& l : update.lines) lines_[l.id] = l;
  for (long id : update.erased_points) points_.erase(id);
  for (long id : update.erased_lines) lines_.erase(id);
  for (long id : update.erased_keyframes) keyframes_.erase(id);
}

std::vector<long> MapStore::restore(const std::vector<KeyFramePacket>& keyframes) {
  long newest = -1;
  std::set<long> given;
  for (const auto& k : keyframes) {
    newest = std::max(newest, k.id);
    given.insert(k.id);
  }
  std::vector<long> erased;
  for (const auto& [id, kf] : keyframes_)
    if (id <= newest && !given.count(id)) erased.push_back(id);
  for (long id : erased) keyframes_.erase(id);
  points_.clear();
  lines_.clear();
  for (const auto& [id, kf] : keyframes_) {
    if (given.count(id)) continue;
    for (const auto& p : kf.points) points_[p.id] = p;
    for (const auto& l : kf.lines) lines_[l.id] = l;
  }
  for (const auto& k : keyframes) insert(k);
  return erased;
}

Trajectory MapStore::keyFrameTrajectory() const {
  Trajectory trajectory;
  for (const auto& [id, kf] : keyframes_) trajectory.push_back({kf.stamp, kf.T_wc});
  return trajectory;
}

void MapStore::save(const std::string& folder) const {
  namespace fs = std::filesystem;
  fs::create_directories(folder);
  const fs::path dir(folder);
  // Each file on its own: one that fails does not keep the others off the disk.
  FileWrites files;
  files.attempt(
      [&] { writeTumTrajectory((dir / "KeyFrameTrajectory.txt").string(), keyFrameTrajectory()); });
  files.attempt([&] { writePoints((dir / "map_points.ply").string()); });
  files.attempt([&] { writeLines((dir / "map_lines.ply").string()); });
  files.attempt([&] { writeKeyFrameTable((dir / "keyframes.csv").string()); });
  files.throwFailures();
}

void MapStore::writePoints(const std::string& path) const {
  AtomicFile file(path);
  std::ostream& points = file.stream();
  points << std::setprecision(9) << "ply\nformat ascii 1.0\nelement vertex " << points_.size()
         << "\nproperty float x\nproperty float y\nproperty float z\nend_header\n";
  for (const auto& [id, p] : points_) writeVertex(points, p.position);
  file.commit();
}

void MapStore::writeLines(const std::string& path) const {
  AtomicFile file(path);
  std::ostream& lines = file.stream();
  lines << std::setprecision(9) << "ply\nformat ascii 1.0\nelement vertex " << 2 * lines_.size()
        << "\nproperty float x\nproperty float y\nproperty float z\nelement edge " << lines_.size()
        << "\nproperty int vertex1\nproperty int vertex2\nend_header\n";
  for (const auto& [id, l] : lines_) {
    writeVertex(lines, l.start);
    writeVertex(lines, l.end);
  }
  for (size_t i = 0; i < lines_.size(); ++i) lines << 2 * i << ' ' << 2 * i + 1 << '\n';
  file.commit();
}

void MapStore::writeKeyFrameTable(const std::string& path) const {
  AtomicFile file(path);
  std::ostream& keyframes = file.stream();
  keyframes << "id,frame,stamp,keypoints,points,lines,instances\n";
  for (const auto& [id, kf] : keyframes_) {
    std::string instances;
    for (const auto& instance : kf.instances)
      instances += (instances.empty() ? "" : " ") + instance.class_name +
                   (instance.dynamic ? "(dynamic)" : "");
    keyframes << id << ',' << kf.frame_id << ',' << std::fixed << std::setprecision(6) << kf.stamp
              << ',' << kf.keypoints.size() << ',' << kf.points.size() << ',' << kf.lines.size()
              << ',' << instances << '\n';
  }
  file.commit();
}

}  // namespace ply_slam
