#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "ply_slam/dense/class_palette.h"
#include "ply_slam/dense/key_frame_cloud.h"
#include "ply_slam/dense/octree_colour_mode.h"

namespace octomap {
class ColorOcTree;
}

namespace ply_slam {

// OctoMap ColorOcTree built by ray casting keyframe clouds from their camera centres: the
// voxels a ray passes are made more free, its end voxel more occupied, so something that
// moved away is cleared once the space behind it has been seen (also through the keyframe's
// clearing rays, which end beyond the mapped range and mark nothing occupied). Beside the tree, a
// class histogram per hit voxel; voxels are coloured by their majority class (palette) or mean RGB.
class SemanticOctree {
 public:
  using ColourMode = OctreeColourMode;

  // One occupied leaf of the tree.
  struct Voxel {
    Eigen::Vector3d centre;
    // Where in the voxel the surface lies: the mean of the points that ended in it (the centre
    // when none did). A 5 cm voxel's centre is up to 4.3 cm off the surface.
    Eigen::Vector3d surface = Eigen::Vector3d::Zero();
    double size = 0.0;                             // m, edge
    std::uint32_t label = ClassPalette::kUnknown;  // majority class of its hits
    ClassColour colour;
    std::uint32_t hits = 0;    // cloud points that ended in it
    std::uint32_t tagged = 0;  // of those, from tagged pixels (evaluation)
  };

  // `occupancy`: the probability from which a voxel counts as occupied (OctoMap default 0.5).
  // `ray_margin` (m): a ray to a point frees the voxels it passes only up to this short of
  // the point (0: up to the point's voxel, as OctoMap).
  SemanticOctree(double resolution, ColourMode mode, ClassPalette palette, double occupancy = 0.5,
                 double ray_margin = 0.0);
  ~SemanticOctree();
  SemanticOctree(const SemanticOctree&) = delete;
  SemanticOctree& operator=(const SemanticOctree&) = delete;

  // Ray-casts the keyframe's points and clearing rays (placed by cloud.T_wc) from its camera
  // centre. One update per voxel and keyframe: occupied if a point ends in it, else free if a
  // ray passes it (rays to points stop ray_margin short of them).
  void insert(const KeyFrameCloud& cloud);
  void clear();  // empty tree and histograms (before re-inserting after a pose correction)

  std::vector<Voxel> occupiedVoxels() const;
  bool isOccupied(const Eigen::Vector3d& p) const;  // false for free and unknown space
  size_t numOccupied() const;
  size_t memoryBytes() const;  // tree (OcTree::memoryUsage) + histograms
  const ClassPalette& palette() const { return palette_; }

  // The tree with inner nodes and colours up to date.
  const octomap::ColorOcTree& tree() const;
  void writeColourTree(const std::string& path) const;  // .ot (octovis)
  void writeBinaryTree(const std::string& path) const;  // .bt: occupancy only

 private:
  struct Impl;
  void refresh() const;

  std::unique_ptr<Impl> impl_;
  ClassPalette palette_;
  ColourMode mode_;
  double ray_margin_;
};

}  // namespace ply_slam
