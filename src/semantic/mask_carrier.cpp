#include "ply_slam/semantic/mask_carrier.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <opencv2/video/tracking.hpp>
#include <stdexcept>

#include "ply_slam/common/statistics.h"

namespace ply_slam {
namespace {

constexpr int kWindow = 21, kLevels = 3;

// The mask shifted by (dx, dy) whole pixels and dilated by `radius`. Both only touch the
// mask's bounding box and its surroundings: full-image morphology per instance and frame
// cost more than the tracking itself.
cv::Mat shiftedAndDilated(const cv::Mat& mask, const cv::Rect& box, int dx, int dy, int radius,
                          int largest_kernel) {
  cv::Mat out = cv::Mat::zeros(mask.size(), CV_8UC1);
  const cv::Rect image(0, 0, mask.cols, mask.rows);
  const cv::Rect to = (box + cv::Point(dx, dy)) & image;
  if (to.empty()) return out;
  mask(to - cv::Point(dx, dy)).copyTo(out(to));
  if (radius <= 0) return out;
  const cv::Rect around =
      cv::Rect(to.x - radius, to.y - radius, to.width + 2 * radius, to.height + 2 * radius) & image;
  cv::Mat grown;
  if (largest_kernel <= 0 || radius <= largest_kernel) {
    cv::dilate(
        out(around), grown,
        cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * radius + 1, 2 * radius + 1)));
  } else {  // the disc of the Euclidean distance map: its cost does not grow with the radius
    cv::Mat distance;
    cv::distanceTransform(out(around) == 0, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE);
    cv::compare(distance, static_cast<double>(radius), grown, cv::CMP_LE);
  }
  grown.copyTo(out(around));
  return out;
}

}  // namespace

MaskCarrier::Source MaskCarrier::prepare(const std::vector<Instance>& instances,
                                         const cv::Mat& from_gray) const {
  if (from_gray.type() != CV_8UC1) throw std::invalid_argument("MaskCarrier: grey image expected");
  for (const Instance& instance : instances)
    if (instance.mask.size() != from_gray.size())
      throw std::invalid_argument("MaskCarrier: mask size differs from the image");
  Source source;
  source.instances = instances;
  source.size = from_gray.size();
  if (instances.empty()) return source;
  // One pyramid for every instance.
  cv::buildOpticalFlowPyramid(from_gray, source.pyramid, cv::Size(kWindow, kWindow), kLevels);
  for (const Instance& instance : instances) {
    const cv::Rect box = cv::boundingRect(instance.mask);
    std::vector<cv::Point2f> corners;
    if (!box.empty()) {
      // Corners well inside the mask: its rim mixes object and background motion.
      cv::Mat inner;
      cv::erode(instance.mask(box), inner,
                cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(9, 9)), cv::Point(-1, -1), 1,
                cv::BORDER_CONSTANT, cv::Scalar(0));
      if (box.width >= 3 && box.height >= 3)
        cv::goodFeaturesToTrack(from_gray(box), corners, params_.samples_per_instance, 0.01, 5.0,
                                inner);
      for (auto& p : corners)
        p += cv::Point2f(static_cast<float>(box.x), static_cast<float>(box.y));
    }
    source.boxes.push_back(box);
    source.corners.push_back(std::move(corners));
  }
  return source;
}

std::vector<Instance> MaskCarrier::carry(const Source& source, const cv::Mat& to_gray) const {
  if (to_gray.type() != CV_8UC1 || to_gray.size() != source.size)
    throw std::invalid_argument("MaskCarrier: grey images of one size expected");
  std::vector<Instance> carried;
  if (source.instances.empty()) return carried;
  std::vector<cv::Mat> to_pyramid;
  // Lucas-Kanade differentiates only the image it tracks from: the one it tracks to needs no
  // derivatives (the pyramid costs half as much).
  cv::buildOpticalFlowPyramid(to_gray, to_pyramid, cv::Size(kWindow, kWindow), kLevels, false);
  for (size_t k = 0; k < source.instances.size(); ++k) {
    const Instance& instance = source.instances[k];
    const cv::Rect& box = source.boxes[k];
    const std::vector<cv::Point2f>& from = source.corners[k];
    Instance moved = instance;
    if (box.empty()) {
      carried.push_back(moved);
      continue;
    }
    std::vector<double> dx, dy;
    if (from.size() >= 3) {
      std::vector<cv::Point2f> to;
      std::vector<unsigned char> ok;
      std::vector<float> error;
      cv::calcOpticalFlowPyrLK(source.pyramid, to_pyramid, from, to, ok, error,
                               cv::Size(kWindow, kWindow), kLevels);
      for (size_t i = 0; i < from.size(); ++i)
        if (ok[i]) {
          dx.push_back(to[i].x - from[i].x);
          dy.push_back(to[i].y - from[i].y);
        }
    }
    if (dx.size() < 3) {  // nothing to follow: where it was, a little wider
      moved.mask =
          shiftedAndDilated(instance.mask, box, 0, 0, params_.margin_px, params_.largest_kernel_px);
      carried.push_back(moved);
      continue;
    }
    const double mx = upperMedian(dx), my = upperMedian(dy);
    std::vector<double> deviation;
    for (size_t i = 0; i < dx.size(); ++i) deviation.push_back(std::hypot(dx[i] - mx, dy[i] - my));
    const int spread = static_cast<int>(std::ceil(upperMedian(deviation)));
    moved.mask = shiftedAndDilated(instance.mask, box, cvRound(mx), cvRound(my),
                                   params_.margin_px + spread, params_.largest_kernel_px);
    carried.push_back(moved);
  }
  return carried;
}

}  // namespace ply_slam
