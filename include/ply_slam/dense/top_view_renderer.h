#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "ply_slam/common/stamped_pose.h"
#include "ply_slam/dense/class_palette.h"
#include "ply_slam/dense/semantic_octree.h"

namespace ply_slam {

// map_top.png: an orthographic view of the occupied voxels looking down the world's up axis,
// each column showing its highest voxel (shaded darker the lower it is), the trajectory on
// top, a legend of the classes shown and a 1 m scale bar.
class TopViewRenderer {
 public:
  // `max_height_above_camera` (m): voxels higher than the highest camera centre plus this are
  // left out, so a ceiling does not hide the room.
  explicit TopViewRenderer(double max_height_above_camera = 0.5, int max_map_px = 900);

  // The up direction of a hand-held or robot camera (x right, y down, z forward): the mean of
  // the cameras' -y axes. Unit (0, 0, 1) when the trajectory is empty.
  static Eigen::Vector3d upFromTrajectory(const Trajectory& trajectory);

  cv::Mat render(const std::vector<SemanticOctree::Voxel>& voxels, const Trajectory& trajectory,
                 const Eigen::Vector3d& up, const ClassPalette& palette,
                 const std::string& title) const;
  // render() into a PNG; throws std::runtime_error when it cannot be written.
  void write(const std::string& png_path, const std::vector<SemanticOctree::Voxel>& voxels,
             const Trajectory& trajectory, const Eigen::Vector3d& up, const ClassPalette& palette,
             const std::string& title) const;

 private:
  double max_height_above_camera_;
  int max_map_px_;
};

}  // namespace ply_slam
