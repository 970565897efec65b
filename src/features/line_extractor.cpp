#include "ply_slam/features/line_extractor.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>
#include <opencv2/line_descriptor.hpp>
#include <stdexcept>

#include "ply_slam/features/edge_refiner.h"

namespace ply_slam {

namespace {

namespace ld = cv::line_descriptor;

// Mean grey difference between the left and the right side of a segment (left of start -> end
// in image axes), sampled at a few points 2 px to either side.
double leftMinusRight(const cv::Mat& gray, const cv::Vec4f& s) {
  const Eigen::Vector2d a(s[0], s[1]), b(s[2], s[3]);
  const double length = (b - a).norm();
  if (length < 1e-6) return 0.0;
  const Eigen::Vector2d d = (b - a) / length;
  const Eigen::Vector2d left(d.y(), -d.x());
  constexpr int kSamples = 8;
  constexpr double kOffset = 2.0;
  double sum = 0.0;
  int count = 0;
  for (int k = 0; k < kSamples; ++k) {
    const Eigen::Vector2d p = a + (b - a) * ((k + 0.5) / kSamples);
    const Eigen::Vector2d l = p + kOffset * left, r = p - kOffset * left;
    const int lu = cvRound(l.x()), lv = cvRound(l.y()), ru = cvRound(r.x()), rv = cvRound(r.y());
    if (lu < 0 || lv < 0 || ru < 0 || rv < 0 || lu >= gray.cols || ru >= gray.cols ||
        lv >= gray.rows || rv >= gray.rows)
      continue;
    sum += static_cast<double>(gray.at<uchar>(lv, lu)) - gray.at<uchar>(rv, ru);
    ++count;
  }
  return count > 0 ? sum / count : 0.0;
}

}  // namespace

bool LineExtractor::lsdAvailable() {
  // OpenCV versions without LSD throw from the constructor ("not implemented").
  static const bool available = [] {
    try {
      return !cv::createLineSegmentDetector().empty();
    } catch (const cv::Exception&) {
      return false;
    }
  }();
  return available;
}

LineExtractor::LineExtractor(const LineOptions& params) : params_(params), merger_(params) {
  switch (params_.detector) {
    case LineDetectorChoice::kEdlines:
      detector_name_ = "edlines";
      break;
    case LineDetectorChoice::kLsd:
      if (!lsdAvailable())
        throw std::runtime_error("lines.detector: lsd is not available in OpenCV " CV_VERSION
                                 " (removed in 4.1.0-4.5.3); use auto or edlines");
      detector_name_ = "lsd";
      break;
    case LineDetectorChoice::kAuto:
      detector_name_ = lsdAvailable() ? "lsd" : "edlines";
      break;
  }
}

std::vector<cv::Vec4f> LineExtractor::detectRaw(const cv::Mat& gray) const {
  std::vector<cv::Vec4f> segments;
  if (detector_name_ == "lsd") {
    // LSD's own Gaussian sub-sampling (lsd_scale) trades short, weak segments for time.
    cv::Ptr<cv::LineSegmentDetector> lsd =
        cv::createLineSegmentDetector(cv::LSD_REFINE_STD, params_.lsd_scale);
    lsd->detect(gray, segments);
    // LSD scales its coordinates back by 1 / scale, which maps pixel centres to the wrong
    // place: x_full = (x_small + 0.5) / scale - 0.5. Without this, edges come out 0.75 px up
    // and left at scale 0.4 (measured on drawn edges).
    const float shift = static_cast<float>(0.5 * (1.0 / params_.lsd_scale - 1.0));
    for (cv::Vec4f& s : segments) s += cv::Vec4f(shift, shift, shift, shift);
  } else {
    cv::Ptr<ld::BinaryDescriptor> edlines = ld::BinaryDescriptor::createBinaryDescriptor();
    std::vector<ld::KeyLine> keylines;
    edlines->detect(gray, keylines);
    segments.reserve(keylines.size());
    for (const ld::KeyLine& k : keylines)
      segments.emplace_back(k.startPointX, k.startPointY, k.endPointX, k.endPointY);
  }
  return segments;
}

std::vector<LineFeature> LineExtractor::detect(const cv::Mat& gray,
                                               const PinholeCamera& camera) const {
  CV_Assert(gray.type() == CV_8UC1);
  std::vector<cv::Vec4f> segments = detectRaw(gray);

  // Orientation by polarity, whatever the detector's convention: brighter side on the left.
  for (cv::Vec4f& s : segments) {
    if (leftMinusRight(gray, s) < 0.0) s = cv::Vec4f(s[2], s[3], s[0], s[1]);
  }

  const size_t n = segments.size();
  std::vector<cv::Point2f> raw(2 * n);
  for (size_t i = 0; i < n; ++i) {
    raw[2 * i] = cv::Point2f(segments[i][0], segments[i][1]);
    raw[2 * i + 1] = cv::Point2f(segments[i][2], segments[i][3]);
  }
  const std::vector<cv::Point2f> undistorted = camera.undistortPixels(raw);
  std::vector<LineFeature> lines(n);
  for (size_t i = 0; i < n; ++i) {
    LineFeature& l = lines[i];
    l.raw_start = Eigen::Vector2d(raw[2 * i].x, raw[2 * i].y);
    l.raw_end = Eigen::Vector2d(raw[2 * i + 1].x, raw[2 * i + 1].y);
    l.start = Eigen::Vector2d(undistorted[2 * i].x, undistorted[2 * i].y);
    l.end = Eigen::Vector2d(undistorted[2 * i + 1].x, undistorted[2 * i + 1].y);
  }

  lines = merger_.merge(std::move(lines));  // comes back longest first
  lines.erase(
      std::remove_if(lines.begin(), lines.end(),
                     [&](const LineFeature& l) { return l.length() < params_.min_length_px; }),
      lines.end());
  if (params_.max_lines > 0 && lines.size() > static_cast<size_t>(params_.max_lines))
    lines.resize(params_.max_lines);
  refineOnEdges(gray, camera, lines);
  return lines;
}

void LineExtractor::refineOnEdges(const cv::Mat& gray, const PinholeCamera& camera,
                                  std::vector<LineFeature>& lines) const {
  if (!params_.refine_edges) return;
  std::vector<size_t> moved;
  std::vector<cv::Point2f> raw;
  for (size_t i = 0; i < lines.size(); ++i) {
    if (!EdgeRefiner::refine(gray, lines[i].raw_start, lines[i].raw_end)) continue;
    moved.push_back(i);
    raw.emplace_back(lines[i].raw_start.x(), lines[i].raw_start.y());
    raw.emplace_back(lines[i].raw_end.x(), lines[i].raw_end.y());
  }
  const std::vector<cv::Point2f> undistorted = camera.undistortPixels(raw);
  for (size_t k = 0; k < moved.size(); ++k) {
    lines[moved[k]].start = Eigen::Vector2d(undistorted[2 * k].x, undistorted[2 * k].y);
    lines[moved[k]].end = Eigen::Vector2d(undistorted[2 * k + 1].x, undistorted[2 * k + 1].y);
  }
}

cv::Mat LineExtractor::describe(const cv::Mat& gray, const std::vector<LineFeature>& lines) const {
  if (lines.empty()) return cv::Mat(0, 32, CV_8U);
  // LBD's cost grows with the pixels under its 9 bands; at half size it takes half the time
  // and matched as well on the fr1 sequences (LSD itself runs at lsd_scale).
  const double s = params_.lbd_scale;
  cv::Mat image = gray;
  if (s < 1.0) cv::resize(gray, image, cv::Size(), s, s, cv::INTER_AREA);
  // BinaryDescriptor::compute describes given KeyLines: class_id indexes them, octave 0 is
  // the given image, and the band geometry follows angle and numOfPixels.
  std::vector<ld::KeyLine> keylines(lines.size());
  const float max_u = static_cast<float>(image.cols - 1),
              max_v = static_cast<float>(image.rows - 1);
  auto scaled = [&](double x, float max) {  // pixel centres stay pixel centres
    return std::clamp(static_cast<float>((x + 0.5) * s - 0.5), 0.f, max);
  };
  for (size_t i = 0; i < lines.size(); ++i) {
    const float su = scaled(lines[i].raw_start.x(), max_u);
    const float sv = scaled(lines[i].raw_start.y(), max_v);
    const float eu = scaled(lines[i].raw_end.x(), max_u);
    const float ev = scaled(lines[i].raw_end.y(), max_v);
    ld::KeyLine& k = keylines[i];
    k.startPointX = k.sPointInOctaveX = su;
    k.startPointY = k.sPointInOctaveY = sv;
    k.endPointX = k.ePointInOctaveX = eu;
    k.endPointY = k.ePointInOctaveY = ev;
    k.lineLength = std::hypot(eu - su, ev - sv);
    k.numOfPixels = static_cast<int>(std::max(std::abs(eu - su), std::abs(ev - sv))) + 1;
    k.angle = std::atan2(ev - sv, eu - su);
    k.class_id = static_cast<int>(i);
    k.octave = 0;
    k.pt = cv::Point2f((su + eu) / 2, (sv + ev) / 2);
    k.response = k.lineLength / std::max(image.cols, image.rows);
    k.size = (eu - su) * (ev - sv);
  }
  ld::BinaryDescriptor::Params p;
  p.widthOfBand_ = params_.lbd_band_width;
  p.numOfOctave_ = 1;
  cv::Ptr<ld::BinaryDescriptor> lbd = ld::BinaryDescriptor::createBinaryDescriptor(p);
  cv::Mat descriptors;
  lbd->compute(image, keylines, descriptors);
  CV_Assert(descriptors.rows == static_cast<int>(lines.size()) && descriptors.cols == 32 &&
            descriptors.type() == CV_8U);
  return descriptors;
}

}  // namespace ply_slam
