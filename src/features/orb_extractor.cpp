#include "ply_slam/features/orb_extractor.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace ply_slam {
namespace {

constexpr int kPatchSize = 31;
constexpr int kHalfPatch = 15;

// Orientation by intensity centroid over a circular patch (Rublee et al. 2011).
float intensityCentroidAngle(const cv::Mat& image, const cv::Point2f& pt) {
  const int cx = cvRound(pt.x), cy = cvRound(pt.y);
  double m01 = 0, m10 = 0;
  for (int dy = -kHalfPatch; dy <= kHalfPatch; ++dy) {
    const uchar* row = image.ptr<uchar>(cy + dy);
    const int half_width = static_cast<int>(std::sqrt(kHalfPatch * kHalfPatch - dy * dy + 0.5));
    for (int dx = -half_width; dx <= half_width; ++dx) {
      const double value = row[cx + dx];
      m10 += dx * value;
      m01 += dy * value;
    }
  }
  float angle = static_cast<float>(std::atan2(m01, m10) * 180.0 / CV_PI);
  return angle < 0 ? angle + 360.f : angle;
}

}  // namespace

OrbExtractor::OrbExtractor(const OrbOptions& params) : params_(params) {
  scales_.resize(params_.num_levels);
  for (int i = 0; i < params_.num_levels; ++i) scales_[i] = std::pow(params_.scale_factor, i);

  // Split the feature budget over levels in proportion to each level's image area^(1/2),
  // a geometric series in 1/scale_factor (as ORB-SLAM does).
  const double f = 1.0 / params_.scale_factor;
  double per_level = params_.num_features * (1 - f) / (1 - std::pow(f, params_.num_levels));
  int total = 0;
  features_per_level_.resize(params_.num_levels);
  for (int i = 0; i < params_.num_levels - 1; ++i) {
    features_per_level_[i] = static_cast<int>(std::round(per_level));
    total += features_per_level_[i];
    per_level *= f;
  }
  features_per_level_.back() = std::max(params_.num_features - total, 0);

  for (int i = 0; i < params_.num_levels; ++i)
    descriptors_.push_back(cv::ORB::create(params_.num_features, 1.2f, 1, params_.edge_threshold, 0,
                                           2, cv::ORB::FAST_SCORE, kPatchSize,
                                           params_.fast_threshold));
}

void OrbExtractor::detectLevel(const cv::Mat& image, int level,
                               std::vector<cv::KeyPoint>& out) const {
  // Corners must keep the descriptor patch inside the image.
  const int border = std::max(params_.edge_threshold, kHalfPatch + 1) + 1;
  const cv::Rect inner(border, border, image.cols - 2 * border, image.rows - 2 * border);
  if (inner.width <= 0 || inner.height <= 0) return;

  const int cell = params_.grid_cell_size;
  const int cols = std::max(1, inner.width / cell), rows = std::max(1, inner.height / cell);
  const double cell_w = static_cast<double>(inner.width) / cols;
  const double cell_h = static_cast<double>(inner.height) / rows;
  std::vector<std::vector<cv::KeyPoint>> cells(cols * rows);

  // FAST looks at a radius-3 circle, so each cell is scanned with a 3 px margin.
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const int x0 = inner.x + static_cast<int>(c * cell_w);
      const int y0 = inner.y + static_cast<int>(r * cell_h);
      const int x1 = inner.x + static_cast<int>((c + 1) * cell_w);
      const int y1 = inner.y + static_cast<int>((r + 1) * cell_h);
      const cv::Rect scan(x0 - 3, y0 - 3, x1 - x0 + 6, y1 - y0 + 6);
      std::vector<cv::KeyPoint> found;
      cv::FAST(image(scan), found, params_.fast_threshold, true);
      if (found.empty()) cv::FAST(image(scan), found, params_.min_fast_threshold, true);
      auto& bucket = cells[r * cols + c];
      for (auto& kp : found) {
        kp.pt.x += scan.x;
        kp.pt.y += scan.y;
        if (kp.pt.x >= x0 && kp.pt.x < x1 && kp.pt.y >= y0 && kp.pt.y < y1) bucket.push_back(kp);
      }
      std::sort(bucket.begin(), bucket.end(), [](const cv::KeyPoint& a, const cv::KeyPoint& b) {
        return a.response > b.response;
      });
    }
  }

  // Round-robin over cells, strongest remaining corner of each cell per round.
  const size_t target = features_per_level_[level];
  std::vector<cv::KeyPoint> selected;
  selected.reserve(target);
  for (size_t round = 0; selected.size() < target; ++round) {
    bool any = false;
    for (const auto& bucket : cells) {
      if (round < bucket.size()) {
        selected.push_back(bucket[round]);
        any = true;
        if (selected.size() == target) break;
      }
    }
    if (!any) break;
  }

  for (auto& kp : selected) {
    kp.angle = intensityCentroidAngle(image, kp.pt);
    kp.octave = 0;
    kp.size = kPatchSize;
  }
  out = std::move(selected);
}

void OrbExtractor::extract(const cv::Mat& gray, std::vector<cv::KeyPoint>& keypoints,
                           cv::Mat& descriptors) const {
  CV_Assert(gray.type() == CV_8UC1 && params_.num_levels <= 32);
  keypoints.clear();
  std::vector<cv::KeyPoint> level_keypoints[32];
  cv::Mat level_descriptors[32];

  // Levels are independent: detect and describe them in parallel.
  cv::parallel_for_(cv::Range(0, params_.num_levels), [&](const cv::Range& range) {
    for (int level = range.start; level < range.end; ++level) {
      cv::Mat image;
      if (level == 0) {
        image = gray;
      } else {
        const cv::Size size(cvRound(gray.cols / scales_[level]),
                            cvRound(gray.rows / scales_[level]));
        if (size.width < 1 || size.height < 1) continue;  // tiny image: the level vanishes
        cv::resize(gray, image, size, 0, 0, cv::INTER_LINEAR);
      }
      detectLevel(image, level, level_keypoints[level]);
      if (!level_keypoints[level].empty())
        descriptors_[level]->compute(image, level_keypoints[level], level_descriptors[level]);
    }
  });

  std::vector<cv::Mat> all_descriptors;
  for (int level = 0; level < params_.num_levels; ++level) {
    const float s = static_cast<float>(scales_[level]);
    for (auto kp : level_keypoints[level]) {
      kp.pt *= s;
      kp.octave = level;
      kp.size = kPatchSize * s;
      keypoints.push_back(kp);
    }
    if (!level_descriptors[level].empty()) all_descriptors.push_back(level_descriptors[level]);
  }
  if (all_descriptors.empty())
    descriptors.release();
  else
    cv::vconcat(all_descriptors, descriptors);
}

}  // namespace ply_slam
