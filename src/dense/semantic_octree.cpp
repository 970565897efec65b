#include "ply_slam/dense/semantic_octree.h"

#include <octomap/ColorOcTree.h>
#include <octomap/OcTree.h>
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <stdexcept>
#include <unordered_map>
#include <utility>

#include "ply_slam/io/atomic_file.h"

namespace ply_slam {

// What the points that ended in one voxel said about it.
struct VoxelHistogram {
  std::uint32_t hits = 0, tagged = 0;
  std::uint32_t r = 0, g = 0, b = 0;                  // sums
  Eigen::Vector3f offsets = Eigen::Vector3f::Zero();  // sum of the hits less the voxel centre
  std::vector<std::pair<std::uint32_t, std::uint32_t>> labels;  // (label, count), few per voxel

  void add(const pcl::PointXYZRGBL& p, const Eigen::Vector3f& offset, bool tag) {
    ++hits;
    tagged += tag;
    r += p.r, g += p.g, b += p.b;
    offsets += offset;
    for (auto& [label, count] : labels)
      if (label == p.label) {
        ++count;
        return;
      }
    labels.emplace_back(p.label, 1);
  }
  std::uint32_t majority() const {
    std::pair<std::uint32_t, std::uint32_t> best{ClassPalette::kUnknown, 0};
    for (const auto& l : labels)
      if (l.second > best.second) best = l;
    return best.first;
  }
};

struct SemanticOctree::Impl {
  explicit Impl(double resolution) : tree(resolution) {}
  mutable octomap::ColorOcTree tree;
  std::unordered_map<octomap::OcTreeKey, VoxelHistogram, octomap::OcTreeKey::KeyHash> voxels;
  mutable bool stale = false;  // colours and inner nodes need a refresh
};

SemanticOctree::SemanticOctree(double resolution, ColourMode mode, ClassPalette palette,
                               double occupancy, double ray_margin)
    : palette_(std::move(palette)), mode_(mode), ray_margin_(ray_margin) {
  if (!(resolution > 0.0)) throw std::invalid_argument("SemanticOctree: resolution must be > 0");
  if (!(occupancy >= 0.5 && occupancy < 0.97))  // 0.97: OctoMap's clamping limit
    throw std::invalid_argument("SemanticOctree: occupancy must be within [0.5, 0.97)");
  if (!(ray_margin >= 0.0)) throw std::invalid_argument("SemanticOctree: ray_margin must be >= 0");
  impl_ = std::make_unique<Impl>(resolution);
  impl_->tree.setOccupancyThres(occupancy);
}

SemanticOctree::~SemanticOctree() = default;

void SemanticOctree::insert(const KeyFrameCloud& cloud) {
  if (!cloud.points) throw std::invalid_argument("SemanticOctree::insert: cloud has no points");
  if (cloud.tags && cloud.tags->size() != cloud.points->size())
    throw std::invalid_argument("SemanticOctree::insert: tags and points differ in size");
  auto& tree = impl_->tree;
  const Eigen::Isometry3f T_wc = cloud.T_wc.cast<float>();
  const Eigen::Vector3f c = T_wc.translation();
  const octomap::point3d origin(c.x(), c.y(), c.z());
  // As OcTree::insertPointCloud with discretize: one ray per end voxel, and a voxel a point
  // ends in is not also made free by another ray of the same keyframe.
  octomap::KeySet occupied, free, clearing_ends;
  octomap::KeyRay ray;
  // Casts one ray per new end voxel, `margin` short of it; false when `end` is outside the
  // octree. Without a margin, rays that end a little behind a surface (depth noise, pose
  // error: centimetres at 4 m) clear the voxels other keyframes hit, most where the surface
  // is seen at a grazing angle.
  auto castTo = [&](const octomap::point3d& end, octomap::KeySet& ends, double margin,
                    octomap::OcTreeKey& key) {
    if (!tree.coordToKeyChecked(end, key)) return false;
    if (!ends.insert(key).second) return true;
    const octomap::point3d along = end - origin;
    const double length = along.norm();
    if (length <= margin) return true;
    if (tree.computeRayKeys(origin, origin + along * static_cast<float>(1.0 - margin / length),
                            ray))
      free.insert(ray.begin(), ray.end());
    return true;
  };
  octomap::OcTreeKey key;
  for (size_t i = 0; i < cloud.points->size(); ++i) {
    const Eigen::Vector3f w = T_wc * cloud.points->points[i].getVector3fMap();
    if (castTo(octomap::point3d(w.x(), w.y(), w.z()), occupied, ray_margin_, key)) {
      const octomap::point3d centre = tree.keyToCoord(key);
      impl_->voxels[key].add(cloud.points->points[i],
                             w - Eigen::Vector3f(centre.x(), centre.y(), centre.z()),
                             cloud.tags && cloud.tags->points[i].label);
    }
  }
  for (const Eigen::Vector3f& p : cloud.clearing_rays) {
    const Eigen::Vector3f w = T_wc * p;
    castTo(octomap::point3d(w.x(), w.y(), w.z()), clearing_ends, 0.0, key);
  }
  // lazy: no pruning, so every leaf keeps its own colour.
  for (const auto& key : free)
    if (!occupied.count(key)) tree.updateNode(key, false, true);
  for (const auto& key : occupied) tree.updateNode(key, true, true);
  impl_->stale = true;
}

void SemanticOctree::clear() {
  impl_->tree.clear();
  impl_->voxels.clear();
  impl_->stale = false;
}

void SemanticOctree::refresh() const {
  if (!impl_->stale) return;
  for (const auto& [key, h] : impl_->voxels) {
    octomap::ColorOcTreeNode* node = impl_->tree.search(key);
    if (!node || !impl_->tree.isNodeOccupied(node)) continue;
    if (mode_ == ColourMode::kClass) {
      const ClassColour c = palette_.colour(h.majority());
      node->setColor(c.r, c.g, c.b);
    } else {
      node->setColor(h.r / h.hits, h.g / h.hits, h.b / h.hits);
    }
  }
  impl_->tree.updateInnerOccupancy();  // inner occupancy and mean colours for coarse views
  impl_->stale = false;
}

std::vector<SemanticOctree::Voxel> SemanticOctree::occupiedVoxels() const {
  refresh();
  std::vector<Voxel> out;
  const auto& tree = impl_->tree;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it) {
    if (!tree.isNodeOccupied(*it)) continue;
    Voxel v;
    const octomap::point3d c = it.getCoordinate();
    v.centre = {c.x(), c.y(), c.z()};
    v.surface = v.centre;
    v.size = it.getSize();
    const auto h = impl_->voxels.find(it.getKey());
    if (h != impl_->voxels.end()) {
      v.label = h->second.majority();
      v.hits = h->second.hits;
      v.tagged = h->second.tagged;
      if (v.hits > 0) v.surface += (h->second.offsets / v.hits).cast<double>();
    }
    const octomap::ColorOcTreeNode::Color colour = it->getColor();
    v.colour = {colour.r, colour.g, colour.b};
    out.push_back(v);
  }
  return out;
}

bool SemanticOctree::isOccupied(const Eigen::Vector3d& p) const {
  const octomap::ColorOcTreeNode* node = impl_->tree.search(p.x(), p.y(), p.z());
  return node && impl_->tree.isNodeOccupied(node);
}

size_t SemanticOctree::numOccupied() const {
  size_t n = 0;
  const auto& tree = impl_->tree;
  const unsigned max_depth = tree.getTreeDepth();
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it)
    if (tree.isNodeOccupied(*it)) n += size_t(1) << (3 * (max_depth - it.getDepth()));
  return n;
}

size_t SemanticOctree::memoryBytes() const {
  size_t histograms = impl_->voxels.bucket_count() * sizeof(void*) +
                      impl_->voxels.size() *
                          (sizeof(octomap::OcTreeKey) + sizeof(VoxelHistogram) + 2 * sizeof(void*));
  for (const auto& [key, h] : impl_->voxels)
    histograms += h.labels.capacity() * sizeof(h.labels[0]);
  return impl_->tree.memoryUsage() + histograms;
}

const octomap::ColorOcTree& SemanticOctree::tree() const {
  refresh();
  return impl_->tree;
}

void SemanticOctree::writeColourTree(const std::string& path) const {
  refresh();
  // Through a stream whose state is checked: OctoMap's file writers do not check the close.
  AtomicFile file(path, std::ios::binary);
  impl_->tree.write(file.stream());
  file.commit();
}

void SemanticOctree::writeBinaryTree(const std::string& path) const {
  refresh();
  octomap::OcTree binary(impl_->tree.getResolution());
  const auto& tree = impl_->tree;
  for (auto it = tree.begin_leafs(), end = tree.end_leafs(); it != end; ++it)
    binary.setNodeValue(it.getKey(), it->getLogOdds(), true);
  binary.updateInnerOccupancy();
  binary.prune();
  AtomicFile file(path, std::ios::binary);
  binary.writeBinary(file.stream());
  file.commit();
}

}  // namespace ply_slam
