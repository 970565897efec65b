#include "ply_slam/dynamic/dynamic_feature_filter.h"

namespace ply_slam {

DynamicDecision DynamicFeatureFilter::decide(const std::vector<FeatureCorrespondence>& features,
                                             const std::vector<int>& instance,
                                             const std::map<int, ClassMotion>& motion, int width,
                                             int height,
                                             const Eigen::Isometry3d* predicted_motion) const {
  DynamicDecision d;
  std::vector<bool> on_moving_class(features.size(), false);
  for (size_t i = 0; i < features.size(); ++i) {
    const auto kind = motion.find(instance[i]);
    on_moving_class[i] = kind != motion.end() && kind->second == ClassMotion::kActive;
  }
  d.weight = consistency_.weights(features, width, height, {predicted_motion, &on_moving_class},
                                  &d.static_fit);
  d.dynamic.assign(features.size(), false);

  std::map<int, int> all, voted;  // per instance: N_all and w_lab
  for (size_t i = 0; i < features.size(); ++i) {
    const bool in_dp = d.weight[i] > params_.weight_threshold;
    d.dynamic[i] = in_dp;
    if (instance[i] == 0) continue;
    ++all[instance[i]];
    voted[instance[i]] += in_dp;
  }
  for (const auto& [id, n] : all) {
    const double degree = static_cast<double>(voted[id]) / n;
    d.degree[id] = degree;
    const auto kind = motion.count(id) ? motion.at(id) : ClassMotion::kStatic;
    if ((kind == ClassMotion::kActive && degree > params_.active_degree) ||
        (kind == ClassMotion::kPassive && degree > params_.passive_degree))
      d.measured.insert(id);
  }
  d.dynamic_instances = d.measured;
  // Too few matched features to judge a person or an animal by: presume it moves.
  for (const auto& [id, kind] : motion)
    if (kind == ClassMotion::kActive &&
        (all.count(id) ? all.at(id) : 0) < params_.min_judged_features)
      d.dynamic_instances.insert(id);
  for (size_t i = 0; i < features.size(); ++i)
    if (instance[i] != 0 && d.dynamic_instances.count(instance[i])) d.dynamic[i] = true;
  return d;
}

}  // namespace ply_slam
