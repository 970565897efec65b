#include "ply_slam/eval/trajectory_metrics.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "ply_slam/common/angles.h"
#include "ply_slam/common/statistics.h"
#include "ply_slam/eval/trajectory_association.h"

namespace ply_slam {
namespace {

// Stamps of one trajectory are treated as equal within this tolerance when looking for "the
// first pose at least delta_seconds later": differences of stamps near 1e9 s carry rounding
// noise of ~1e-7 s, far below any frame interval.
constexpr double kStampTolerance = 1e-6;

ErrorStats summarize(std::vector<double> errors) {
  ErrorStats stats;
  stats.count = errors.size();
  if (errors.empty()) return stats;
  double sum = 0.0, sum_sq = 0.0;
  for (double e : errors) {
    sum += e;
    sum_sq += e * e;
    stats.max = std::max(stats.max, e);
  }
  const double n = static_cast<double>(errors.size());
  stats.mean = sum / n;
  stats.rmse = std::sqrt(sum_sq / n);
  // numpy.median, as TUM's scripts use: the mean of the two middle values for an even count.
  stats.median = median(errors);
  return stats;
}

// Associated poses, in the estimate's time order (the order RPE steps through).
struct PosePairs {
  std::vector<const StampedPose*> gt;
  std::vector<const StampedPose*> est;
};

PosePairs associatePoses(const Trajectory& gt, const Trajectory& est, double max_dt) {
  std::vector<std::pair<size_t, size_t>> pairs = associateByStamp(gt, est, max_dt);
  std::stable_sort(pairs.begin(), pairs.end(), [&est](const auto& l, const auto& r) {
    return est[l.second].stamp < est[r.second].stamp;
  });
  PosePairs poses;
  for (const auto& [i_gt, i_est] : pairs) {
    poses.gt.push_back(&gt[i_gt]);
    poses.est.push_back(&est[i_est]);
  }
  return poses;
}

std::string describeInputs(const Trajectory& gt, const Trajectory& est, double max_dt) {
  std::ostringstream msg;
  msg << "ground truth has " << gt.size() << " poses, estimate " << est.size() << ", max_dt "
      << max_dt << " s";
  return msg.str();
}

// RPE over explicit (i, j) index pairs into the associated poses.
RpeResult relativeErrors(const PosePairs& poses, const std::vector<std::pair<size_t, size_t>>& ij) {
  std::vector<double> translation_errors, rotation_errors;
  translation_errors.reserve(ij.size());
  rotation_errors.reserve(ij.size());
  for (const auto& [i, j] : ij) {
    const Eigen::Isometry3d gt_motion = poses.gt[i]->T_wc.inverse() * poses.gt[j]->T_wc;
    const Eigen::Isometry3d est_motion = poses.est[i]->T_wc.inverse() * poses.est[j]->T_wc;
    const Eigen::Isometry3d error = gt_motion.inverse() * est_motion;
    translation_errors.push_back(error.translation().norm());
    rotation_errors.push_back(rotationAngleDeg(error.linear()));
  }
  RpeResult result;
  result.translation = summarize(std::move(translation_errors));
  result.rotation = summarize(std::move(rotation_errors));
  return result;
}

struct AssociatedPositions {
  std::vector<Eigen::Vector3d> gt, est;
};

AssociatedPositions associatedPositions(const Trajectory& gt, const Trajectory& est,
                                        double max_dt) {
  const std::vector<std::pair<size_t, size_t>> pairs = associateByStamp(gt, est, max_dt);
  if (pairs.size() < 3) {
    throw std::runtime_error("ATE needs at least 3 pose pairs with stamps within max_dt, found " +
                             std::to_string(pairs.size()) + " (" + describeInputs(gt, est, max_dt) +
                             ")");
  }
  AssociatedPositions positions;
  for (const auto& [i_gt, i_est] : pairs) {
    positions.gt.push_back(gt[i_gt].T_wc.translation());
    positions.est.push_back(est[i_est].T_wc.translation());
  }
  return positions;
}

// The distances between the ground truth and the estimate mapped into its frame by `align`.
template <typename Align>
ErrorStats errorsAfter(const AssociatedPositions& positions, const Align& align) {
  std::vector<double> errors;
  errors.reserve(positions.gt.size());
  for (size_t k = 0; k < positions.gt.size(); ++k)
    errors.push_back((positions.gt[k] - align(positions.est[k])).norm());
  return summarize(std::move(errors));
}

AteResult ateWith(const AssociatedPositions& positions, const Eigen::Isometry3d& T_gt_est) {
  AteResult result;
  result.T_gt_est = T_gt_est;
  result.translation = errorsAfter(
      positions, [&](const Eigen::Vector3d& p) -> Eigen::Vector3d { return T_gt_est * p; });
  return result;
}

}  // namespace

AteResult computeAte(const Trajectory& gt, const Trajectory& est, double max_dt) {
  const AssociatedPositions positions = associatedPositions(gt, est, max_dt);
  return ateWith(positions, alignRigid(positions.est, positions.gt));
}

SimilarityAteResult computeAteSimilarity(const Trajectory& gt, const Trajectory& est,
                                         double max_dt) {
  const AssociatedPositions positions = associatedPositions(gt, est, max_dt);
  const SimilarityAlignment align = alignSimilarity(positions.est, positions.gt);
  return {errorsAfter(positions, align), align.scale};
}

AteResult computeAteInFrame(const Trajectory& gt, const Trajectory& est,
                            const Eigen::Isometry3d& T_gt_est, double max_dt) {
  return ateWith(associatedPositions(gt, est, max_dt), T_gt_est);
}

RpeResult computeRpeFrames(const Trajectory& gt, const Trajectory& est, int delta_frames,
                           double max_dt) {
  if (delta_frames < 1) {
    throw std::invalid_argument("RPE: delta must be at least 1 frame, got " +
                                std::to_string(delta_frames));
  }
  const PosePairs poses = associatePoses(gt, est, max_dt);
  const size_t delta = static_cast<size_t>(delta_frames);
  std::vector<std::pair<size_t, size_t>> ij;
  for (size_t i = 0; i + delta < poses.est.size(); ++i) ij.emplace_back(i, i + delta);
  if (ij.empty()) {
    throw std::runtime_error("RPE needs two associated poses " + std::to_string(delta_frames) +
                             " frame(s) apart, but only " + std::to_string(poses.est.size()) +
                             " poses associate (" + describeInputs(gt, est, max_dt) + ")");
  }
  return relativeErrors(poses, ij);
}

RpeResult computeRpeSeconds(const Trajectory& gt, const Trajectory& est, double delta_seconds,
                            double max_dt) {
  if (!(delta_seconds > 0.0) || !std::isfinite(delta_seconds)) {
    throw std::invalid_argument("RPE: delta_seconds must be positive, got " +
                                std::to_string(delta_seconds));
  }
  const PosePairs poses = associatePoses(gt, est, max_dt);
  std::vector<std::pair<size_t, size_t>> ij;
  // Poses are in stamp order, so the partner index only ever moves forward.
  size_t j = 0;
  for (size_t i = 0; i < poses.est.size(); ++i) {
    j = std::max(j, i + 1);
    const double wanted = poses.est[i]->stamp + delta_seconds - kStampTolerance;
    while (j < poses.est.size() && poses.est[j]->stamp < wanted) ++j;
    if (j == poses.est.size()) break;
    ij.emplace_back(i, j);
  }
  if (ij.empty()) {
    std::ostringstream msg;
    msg << "RPE needs two associated poses at least " << delta_seconds << " s apart, but the "
        << poses.est.size() << " associated poses do not contain any ("
        << describeInputs(gt, est, max_dt) << ")";
    throw std::runtime_error(msg.str());
  }
  return relativeErrors(poses, ij);
}

}  // namespace ply_slam
