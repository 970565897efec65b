#pragma once

#include <map>
#include <set>
#include <string>
#include <vector>

#include "ply_slam/dynamic/delaunay_consistency.h"
#include "ply_slam/dynamic/dynamic_filter_options.h"

namespace ply_slam {

// Which instance class kind moves (PAPER.md §3.2).
enum class ClassMotion { kStatic, kPassive, kActive };

struct DynamicDecision {
  std::vector<double> weight;       // per feature, from the Delaunay check
  std::vector<bool> dynamic;        // per feature: leave it out of pose estimation
  std::map<int, double> degree;     // instance id -> r_d = w_lab / N_all
  std::set<int> dynamic_instances;  // instances judged moving as a whole
  std::set<int> measured;           // those of them judged by their own r_d
  std::optional<DelaunayConsistency::StaticFit> static_fit;  // none: scene too small to fit
};

// Fuses the geometric evidence with instance labels: features whose Delaunay weight exceeds
// w_th form DP; each instance's dynamic degree r_d is its share of features in DP; an active
// instance (people, animals, vehicles) with r_d > Th_min, or a passive one (chairs, bags…)
// with r_d > Th_max, is dynamic as a whole; so is an active instance with fewer than
// min_judged_features matched features (it cannot be judged). Static classes are never
// dropped as a whole.
// Features in DP are dropped wherever they are, labelled or not.
class DynamicFeatureFilter {
 public:
  DynamicFeatureFilter(const PinholeCamera& camera, const DynamicFilterOptions& params)
      : consistency_(camera, params.consistency), params_(params) {}

  // instance[i]: the instance id under feature i, or 0; motion: class kind per instance id;
  // predicted_motion: the camera's from the previous to the current frame, when known.
  DynamicDecision decide(const std::vector<FeatureCorrespondence>& features,
                         const std::vector<int>& instance, const std::map<int, ClassMotion>& motion,
                         int width, int height,
                         const Eigen::Isometry3d* predicted_motion = nullptr) const;
  const DelaunayConsistency& consistency() const { return consistency_; }

 private:
  DelaunayConsistency consistency_;
  DynamicFilterOptions params_;
};

}  // namespace ply_slam
