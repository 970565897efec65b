#include "ply_slam/eval/gap_evaluation.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <optional>
#include <stdexcept>

#include "ply_slam/common/number_text.h"
#include "ply_slam/eval/pose_interpolation.h"

namespace ply_slam {
namespace {

constexpr double kMaxGroundTruthGap = 0.1;  // s between the ground-truth poses around a stamp

struct PoseError {
  double metres = 0.0, degrees = 0.0;
};

// How far the estimate's motion from `from` to `to` is from the truth's: what a relocalisation
// got wrong, whatever the run drifted before (both poses carry that) and without an alignment
// (fitted to positions, it hardly fixes a rotation where the camera turns on the spot).
std::optional<PoseError> motionError(const Trajectory& gt, const StampedPose& from,
                                     const StampedPose& to) {
  const auto gt_from = interpolatePose(gt, from.stamp, kMaxGroundTruthGap);
  const auto gt_to = interpolatePose(gt, to.stamp, kMaxGroundTruthGap);
  if (!gt_from || !gt_to) return std::nullopt;
  const Eigen::Isometry3d error =
      (gt_from->inverse() * *gt_to).inverse() * (from.T_wc.inverse() * to.T_wc);
  return PoseError{error.translation().norm(), rotationAngleDeg(error.linear())};
}

}  // namespace

std::optional<FrameGap> parseFrameGap(const std::string& text, bool black) {
  const size_t colon = text.find(':');
  if (colon == std::string::npos) return std::nullopt;
  const auto from = parseWholeNumber(text.substr(0, colon), 1, 1000000000L);
  const auto to = parseWholeNumber(text.substr(colon + 1), 2, 1000000000L);
  if (!from || !to || *to <= *from) return std::nullopt;
  return FrameGap{*from, *to, black};
}

GapReport evaluateGap(const Trajectory& gt, const Trajectory& est, double gap_start, double gap_end,
                      const std::vector<double>& relocalised, const GapTolerance& tolerance) {
  Trajectory before, after;
  for (const StampedPose& p : est) {
    if (p.stamp <= gap_start) before.push_back(p);
    if (p.stamp >= gap_end) after.push_back(p);
  }
  const Eigen::Isometry3d T_gt_est = computeAte(gt, before).T_gt_est;
  GapReport report;
  if (!after.empty()) {
    report.relocalised = true;
    if (const auto first = motionError(gt, before.back(), after.front())) {
      report.first_error_m = first->metres;
      report.first_error_deg = first->degrees;
    }
    try {
      report.after = computeAteInFrame(gt, after, T_gt_est).translation;
    } catch (const std::runtime_error&) {
      // fewer than 3 poses after the gap with a ground truth: no ATE after it
    }
  }
  for (double stamp : relocalised) {
    // The relocalised pose against the last one tracked before it.
    const auto at = std::find_if(est.begin(), est.end(),
                                 [stamp](const StampedPose& p) { return p.stamp == stamp; });
    if (at == est.end() || at == est.begin()) continue;
    const auto error = motionError(gt, *(at - 1), *at);
    if (!error) continue;
    ++report.relocalisations;
    report.wrong_relocalisations +=
        error->metres > tolerance.metres || error->degrees > tolerance.degrees;
  }
  return report;
}

}  // namespace ply_slam
