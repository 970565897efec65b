#pragma once

#include <Eigen/Geometry>
#include <deque>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include "ply_slam/common/camera_velocity.h"
#include "ply_slam/dynamic/depth_surfaces.h"
#include "ply_slam/dynamic/dynamic_feature_filter.h"
#include "ply_slam/dynamic/dynamic_options.h"
#include "ply_slam/dynamic/feature_mark.h"
#include "ply_slam/features/frame_features.h"
#include "ply_slam/features/line_feature.h"
#include "ply_slam/semantic/instance.h"

namespace ply_slam {

struct DynamicRejection {
  std::vector<FeatureFate> fate;     // per feature of the current frame
  std::set<int> dynamic_instances;   // measured moving, or presumed so
  std::set<int> measured_instances;  // those whose own matched features found them moving
  cv::Mat dynamic_mask;              // 8UC1 dilated union of the dynamic instances; empty: none
  // Per pixel of the depth image: frames since its depth surface was measured moving (0: this
  // frame), kNoMotion where none is; empty when no surface moved.
  cv::Mat surface_age;
  // Frames since the surfaces seen moving once were seen so (kNoMotion elsewhere; empty:
  // none): moving if seen so again within carry_frames.
  cv::Mat surface_candidates;
  static constexpr unsigned char kNoMotion = 255;
};

// PAPER.md §3.2 applied to one frame: matches the frame's features to an earlier frame's
// (baseline_frames back; descriptor search around where the predicted camera motion puts
// them), runs the Delaunay
// check over those with depth in both, reads the instance label under each feature, and
// decides by the configured mode which features and instances are dynamic.
class DynamicRejector {
 public:
  DynamicRejector(const DynamicOptions& params, const PinholeCamera& camera);

  // velocity: the camera's, to predict where the earlier frame's features are now; may be null.
  // presumed: ids of instances to treat as dynamic whatever this frame shows (InstanceMemory)
  // if their class is an active one (a chair judged moved once stays on its evidence); only
  // full mode uses them (semantic mode takes every active instance anyway, geometric mode
  // reads no labels).
  DynamicRejection decide(const FrameFeatures& current, double stamp,
                          const std::vector<Instance>& instances, const CameraVelocity* velocity,
                          const std::set<int>& presumed = {}) const;
  // Keeps the frame's features (all of them, dynamic ones too) and the surfaces judged moving
  // for the frames to come.
  void remember(const FrameFeatures& current, double stamp, const DynamicRejection& rejection);

  // Lines whose start or end lies on a non-zero pixel of `mask` (PAPER.md §3.2 step 5).
  static std::vector<bool> linesTouching(const std::vector<LineFeature>& lines,
                                         const cv::Mat& mask);

 private:
  ClassMotion motionOf(const std::string& class_name) const;
  // Geometric and full mode: the Delaunay check over the features matched to the earlier
  // frame, with the instances' or the surfaces' labels.
  void judgeByMotion(const FrameFeatures& current, double stamp,
                     const std::vector<Instance>& instances, const CameraVelocity* velocity,
                     const std::set<int>& presumed, DynamicRejection& r) const;
  // Sets r.dynamic_mask from the moving instances or surfaces and drops the features on it.
  void dropWholeObjects(const FrameFeatures& current, const std::vector<Instance>& instances,
                        DynamicRejection& r) const;
  struct Earlier {
    double stamp;
    FrameFeatures features;
    std::vector<Eigen::Vector2d> slopes;  // depthSlopes(features), read before its depth image goes
  };
  std::vector<FeatureCorrespondence> correspondences(
      const Earlier& previous, const FrameFeatures& current,
      const std::optional<Eigen::Isometry3d>& T_cur_prev, std::vector<size_t>& feature_of) const;
  // The label of each matched feature (feature_of: its index in `current`) and each label's
  // class kind: the segmenter's instances (full mode) or the depth image's surfaces (geometric).
  void labelByInstances(const FrameFeatures& current, const std::vector<size_t>& feature_of,
                        const std::vector<Instance>& instances, std::vector<int>& label,
                        std::map<int, ClassMotion>& motion) const;
  // What the last frames said of this frame's surfaces.
  struct SurfaceHistory {
    std::map<int, unsigned char> presumed;     // presumed moving: surface -> its age
    std::map<int, unsigned char> seen_moving;  // seen moving once: surface -> frames since
  };
  SurfaceHistory labelBySurfaces(const DepthSurfaces& surfaces, const FrameFeatures& current,
                                 const std::vector<size_t>& feature_of, std::vector<int>& label,
                                 std::map<int, ClassMotion>& motion) const;
  // The surfaces lying mostly on `ages` (an age image of the last frame, may be empty) with an
  // age below carry_frames, each with its median age plus one.
  std::map<int, unsigned char> agedOn(const DepthSurfaces& surfaces, const cv::Mat& ages) const;
  // The features labelled `id` are fewer than minority_share of the static scene's.
  bool minority(const std::vector<int>& label, int id,
                const DelaunayConsistency::StaticFit& fit) const;
  // Sets r.surface_age and r.surface_candidates from this frame's decision.
  void judgeSurfaces(const DepthSurfaces& surfaces, const DynamicDecision& d,
                     const std::vector<FeatureCorrespondence>& matched,
                     const std::vector<int>& label, SurfaceHistory history,
                     DynamicRejection& r) const;
  // The features labelled `id` moved apart from the static scene (DelaunayConsistency).
  bool movedApart(const std::vector<FeatureCorrespondence>& matched, const std::vector<int>& label,
                  int id, const DelaunayConsistency::StaticFit& fit) const;
  // The instances `ids` as one mask, dilated; empty when none.
  cv::Mat unionMask(const std::vector<Instance>& instances, const std::set<int>& ids) const;
  cv::Mat dilated(const cv::Mat& mask) const;  // by mask_dilation_px

  DynamicOptions params_;
  DynamicMode mode_;
  PinholeCamera camera_;
  DynamicFeatureFilter filter_;
  std::set<std::string> active_, passive_;
  std::deque<Earlier> earlier_;  // the last baseline_frames frames, oldest first
  cv::Mat surface_age_;          // the last frame's DynamicRejection::surface_age
  cv::Mat surface_candidates_;   // and its surface_candidates
};

}  // namespace ply_slam
