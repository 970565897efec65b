#include "ply_slam/semantic/mask_carrier.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <stdexcept>

#include "ply_slam/common/statistics.h"

namespace ply_slam {
namespace {

cv::Mat dilated(const cv::Mat& mask, int radius) {
  if (radius <= 0) return mask.clone();
  cv::Mat out;
  cv::dilate(
      mask, out,
      cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * radius + 1, 2 * radius + 1)));
  return out;
}

}  // namespace

std::vector<Instance> MaskCarrier::carry(const std::vector<Instance>& instances,
                                         const cv::Mat& from_gray, const cv::Mat& to_gray) const {
  if (from_gray.type() != CV_8UC1 || to_gray.type() != CV_8UC1 ||
      from_gray.size() != to_gray.size())
    throw std::invalid_argument("MaskCarrier: grey images of one size expected");
  std::vector<Instance> carried;
  for (const Instance& instance : instances) {
    if (instance.mask.size() != from_gray.size())
      throw std::invalid_argument("MaskCarrier: mask size differs from the image");
    // Corners well inside the mask: its rim mixes object and background motion.
    cv::Mat inner;
    cv::erode(instance.mask, inner, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(9, 9)));
    std::vector<cv::Point2f> from;
    cv::goodFeaturesToTrack(from_gray, from, params_.samples_per_instance, 0.01, 5.0, inner);
    Instance moved = instance;
    if (from.size() < 3) {
      moved.mask = dilated(instance.mask, params_.margin_px);
      carried.push_back(moved);
      continue;
    }
    std::vector<cv::Point2f> to;
    std::vector<unsigned char> ok;
    std::vector<float> error;
    cv::calcOpticalFlowPyrLK(from_gray, to_gray, from, to, ok, error, cv::Size(21, 21), 3);
    std::vector<double> dx, dy;
    for (size_t i = 0; i < from.size(); ++i)
      if (ok[i]) {
        dx.push_back(to[i].x - from[i].x);
        dy.push_back(to[i].y - from[i].y);
      }
    if (dx.size() < 3) {
      moved.mask = dilated(instance.mask, params_.margin_px);
      carried.push_back(moved);
      continue;
    }
    const double mx = upperMedian(dx), my = upperMedian(dy);
    std::vector<double> deviation;
    for (size_t i = 0; i < dx.size(); ++i) deviation.push_back(std::hypot(dx[i] - mx, dy[i] - my));
    const int spread = static_cast<int>(std::ceil(upperMedian(deviation)));
    const cv::Matx23d shift(1, 0, mx, 0, 1, my);
    cv::Mat shifted;
    cv::warpAffine(instance.mask, shifted, shift, instance.mask.size(), cv::INTER_NEAREST,
                   cv::BORDER_CONSTANT, 0);
    moved.mask = dilated(shifted, params_.margin_px + spread);
    carried.push_back(moved);
  }
  return carried;
}

}  // namespace ply_slam
