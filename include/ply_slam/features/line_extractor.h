#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/features/line_feature.h"
#include "ply_slam/features/line_merger.h"
#include "ply_slam/features/line_options.h"

namespace ply_slam {

// 2D line segments and their LBD descriptors.
//
// Detector: OpenCV's LSD (cv::createLineSegmentDetector) where it exists, otherwise EDLines
// (contrib line_descriptor's BinaryDescriptor::detect). LSD's implementation was removed
// from OpenCV 3.4.6-3.4.15 and 4.1.0-4.5.3 for licence reasons and restored in 4.5.4; on
// those versions (Ubuntu 20.04 / ROS Noetic ships 4.2) both cv::createLineSegmentDetector and
// contrib's line_descriptor::LSDDetector, which calls it, throw "not implemented". "auto"
// tries LSD once at construction and falls back to EDLines at run time; the LBD descriptor
// (BinaryDescriptor::compute on our own segments) works on every version.
//
// Not tied to one thread: each call builds its own OpenCV detector, whose state is per image.
class LineExtractor {
 public:
  explicit LineExtractor(const LineOptions& params);

  const std::string& detectorName() const { return detector_name_; }  // "lsd" or "edlines"
  static bool lsdAvailable();

  // Segments of a grey raw image: detected, oriented by polarity, undistorted, merged,
  // shorter than min_length_px dropped, the max_lines longest kept (longest first) and
  // moved onto the full-resolution edge (EdgeRefiner).
  std::vector<LineFeature> detect(const cv::Mat& gray, const PinholeCamera& camera) const;
  // LBD descriptors (N x 32 CV_8U, row i for lines[i]) at the raw segments.
  cv::Mat describe(const cv::Mat& gray, const std::vector<LineFeature>& lines) const;

  const LineOptions& params() const { return params_; }

 private:
  std::vector<cv::Vec4f> detectRaw(const cv::Mat& gray) const;
  // EdgeRefiner on each segment (lines.refine_edges), undistorted ends updated.
  void refineOnEdges(const cv::Mat& gray, const PinholeCamera& camera,
                     std::vector<LineFeature>& lines) const;

  LineOptions params_;
  LineMerger merger_;
  std::string detector_name_;
};

}  // namespace ply_slam
