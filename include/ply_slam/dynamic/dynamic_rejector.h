#pragma once

#include <Eigen/Geometry>
#include <deque>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include "ply_slam/common/camera_velocity.h"
#include "ply_slam/common/config.h"
#include "ply_slam/dynamic/dynamic_feature_filter.h"
#include "ply_slam/features/frame_features.h"
#include "ply_slam/features/line_feature.h"
#include "ply_slam/semantic/instance.h"

namespace ply_slam {

enum class DynamicMode { kOff, kGeometric, kSemantic, kFull };
DynamicMode parseDynamicMode(const std::string& mode);  // throws std::invalid_argument

// Why a feature was left out of tracking, or that it was kept.
enum class FeatureFate : unsigned char { kKept, kGeometric, kSemantic };

struct DynamicRejection {
  std::vector<FeatureFate> fate;     // per feature of the current frame
  std::set<int> dynamic_instances;   // measured moving, or presumed so
  std::set<int> measured_instances;  // those whose own matched features found them moving
  cv::Mat dynamic_mask;              // 8UC1 dilated union of the dynamic instances; empty: none
};

// PAPER.md §3.2 applied to one frame: matches the frame's features to an earlier frame's
// (baseline_frames back; descriptor search around where the predicted camera motion puts
// them), runs the Delaunay
// check over those with depth in both, reads the instance label under each feature, and
// decides by the configured mode which features and instances are dynamic.
class DynamicRejector {
 public:
  DynamicRejector(const DynamicParams& params, const PinholeCamera& camera);

  // velocity: the camera's, to predict where the earlier frame's features are now; may be null.
  // presumed: ids of instances to treat as dynamic whatever this frame shows (InstanceMemory)
  // if their class is an active one (a chair judged moved once stays on its evidence); only
  // full mode uses them (semantic mode takes every active instance anyway, geometric mode
  // reads no labels).
  DynamicRejection decide(const FrameFeatures& current, double stamp,
                          const std::vector<Instance>& instances, const CameraVelocity* velocity,
                          const std::set<int>& presumed = {}) const;
  // Keeps the frame's features (all of them, dynamic ones too) for the frames to come.
  void remember(const FrameFeatures& current, double stamp);

  // Lines whose start or end lies on a non-zero pixel of `mask` (PAPER.md §3.2 step 5).
  static std::vector<bool> linesTouching(const std::vector<LineFeature>& lines,
                                         const cv::Mat& mask);

 private:
  ClassMotion motionOf(const std::string& class_name) const;
  std::vector<FeatureCorrespondence> correspondences(
      const FrameFeatures& previous, const FrameFeatures& current,
      const std::optional<Eigen::Isometry3d>& T_cur_prev, std::vector<size_t>& feature_of) const;
  cv::Mat unionMask(const std::vector<Instance>& instances, const std::set<int>& ids) const;

  DynamicParams params_;
  DynamicMode mode_;
  PinholeCamera camera_;
  DynamicFeatureFilter filter_;
  std::set<std::string> active_, passive_;
  struct Earlier {
    double stamp;
    FrameFeatures features;
  };
  std::deque<Earlier> earlier_;  // the last baseline_frames frames, oldest first
};

}  // namespace ply_slam
