#include "ply_slam/dense/dense_map.h"

#include <pcl/common/transforms.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <stdexcept>

#include "ply_slam/dense/semantic_octree.h"
#include "ply_slam/dense/voxel_filter.h"

namespace ply_slam {
namespace {

DenseCloudPtr placed(const DenseCloudPtr& cloud, const Eigen::Isometry3d& T_wc) {
  if (!cloud) return nullptr;
  auto out = std::make_shared<DenseCloud>();
  pcl::transformPointCloud(*cloud, *out, T_wc.matrix().cast<float>());
  return out;
}

bool poseChanged(const Eigen::Isometry3d& a, const Eigen::Isometry3d& b) {
  const Eigen::Isometry3d d = a.inverse() * b;
  return d.translation().norm() > 1e-6 || Eigen::AngleAxisd(d.rotation()).angle() > 1e-6;
}

long countTagged(const DenseCloudPtr& tags) {
  if (!tags) return -1;
  long count = 0;
  for (const auto& p : tags->points) count += p.label == 1;
  return count;
}

size_t bytes(const DenseCloudPtr& cloud) {
  return cloud ? cloud->size() * sizeof(pcl::PointXYZRGBL) : 0;
}

}  // namespace

DenseMap::DenseMap(double voxel_size) : voxel_size_(voxel_size) {
  if (!(voxel_size > 0.0)) throw std::invalid_argument("DenseMap: voxel_size must be > 0");
}

void DenseMap::keepOnlyOccupied(const SemanticOctree* octree) {
  octree_ = octree;
  dirty_ = true;
}

void DenseMap::insert(KeyFrameCloud cloud) {
  if (!cloud.points) throw std::invalid_argument("DenseMap::insert: keyframe cloud has no points");
  if (cloud.tags && cloud.tags->size() != cloud.points->size())
    throw std::invalid_argument("DenseMap::insert: tags and points differ in size");
  keyframes_[cloud.id] = std::move(cloud);
  dirty_ = true;
}

size_t DenseMap::erase(const std::vector<long>& ids) {
  size_t erased = 0;
  for (long id : ids) erased += keyframes_.erase(id);
  dirty_ |= erased > 0;
  return erased;
}

std::vector<long> DenseMap::applyUpdate(const MapUpdate& update) {
  std::vector<long> changed;
  for (const auto& pose : update.keyframes) {
    const auto it = keyframes_.find(pose.id);
    if (it == keyframes_.end()) continue;
    const Eigen::Isometry3d T_wc = pose.T_wc();
    if (!poseChanged(it->second.T_wc, T_wc)) continue;
    it->second.T_wc = T_wc;
    changed.push_back(pose.id);
  }
  if (!changed.empty()) dirty_ = true;
  return changed;
}

void DenseMap::rebuild() {
  DenseCloud all, all_tags;
  bool have_tags = !keyframes_.empty();
  for (const auto& [id, k] : keyframes_) have_tags = have_tags && k.tags;
  for (const auto& [id, k] : keyframes_) {
    all += *placed(k.points, k.T_wc);
    if (have_tags) all_tags += *placed(k.tags, k.T_wc);
  }
  global_ = voxelFilter(all, voxel_size_);
  global_tags_ = have_tags ? voxelFilter(all_tags, voxel_size_) : nullptr;
  unfiltered_points_ = global_->size();
  unfiltered_tagged_ = countTagged(global_tags_);
  if (octree_) {
    auto kept = std::make_shared<DenseCloud>();
    auto kept_tags = global_tags_ ? std::make_shared<DenseCloud>() : nullptr;
    for (size_t i = 0; i < global_->size(); ++i) {
      if (!octree_->isOccupied(global_->points[i].getVector3fMap().cast<double>())) continue;
      kept->push_back(global_->points[i]);
      if (kept_tags) kept_tags->push_back(global_tags_->points[i]);
    }
    global_ = kept;
    global_tags_ = kept_tags;
  }
  dirty_ = false;
}

DenseCloudPtr DenseMap::globalCloud() {
  if (dirty_) rebuild();
  return global_;
}

size_t DenseMap::numGlobalPoints() { return globalCloud()->size(); }

size_t DenseMap::numUnfilteredPoints() {
  if (dirty_) rebuild();
  return unfiltered_points_;
}

long DenseMap::taggedPoints(bool unfiltered) {
  if (dirty_) rebuild();
  return unfiltered ? unfiltered_tagged_ : countTagged(global_tags_);
}

size_t DenseMap::memoryBytes() const {
  size_t total = bytes(global_) + bytes(global_tags_);
  for (const auto& [id, k] : keyframes_) total += bytes(k.points) + bytes(k.tags);
  return total;
}

}  // namespace ply_slam
