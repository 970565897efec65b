#pragma once

#include <opencv2/core.hpp>
#include <vector>

#include "ply_slam/common/camera_velocity.h"
#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/features/line_3d.h"
#include "ply_slam/features/line_feature.h"

namespace ply_slam {

class LineExtractor;
class LineFitter;

// How the 3D segments are made: PAPER.md §3.1, or the endpoints' own depth ("traditional").
enum class LineFitMethod { kSampled, kEndpoints };

// Wall-clock cost of one frame's lines (ms).
struct LineTimings {
  double extraction_ms = 0.0;   // detection, orientation, undistortion, merging
  double description_ms = 0.0;  // LBD
  double fitting_ms = 0.0;      // 3D segments
};

// The line features of one RGB-D image: 2D segments, LBD descriptors and 3D segments, all
// parallel (index i is one segment).
struct FrameLines {
  std::vector<LineFeature> lines;
  cv::Mat descriptors;          // N x 32 CV_8U LBD
  std::vector<Line3D> lines3d;  // camera frame; valid = accepted
  int average_length = 0;       // L_avg of this frame (px)

  static FrameLines extract(const cv::Mat& gray, const cv::Mat& depth_m,
                            const PinholeCamera& camera, const LineExtractor& extractor,
                            const LineFitter& fitter,
                            LineFitMethod method = LineFitMethod::kSampled,
                            LineTimings* timings = nullptr);
  // The 3D segments again, by another method, for the same 2D segments.
  void fit(const cv::Mat& depth_m, const LineFitter& fitter, LineFitMethod method);

  // Undoes the camera's motion during a rolling-shutter exposure (as FrameFeatures does for
  // points): each endpoint and 3D end is moved to where it was at the stamp. Call once.
  void correctMotion(const PinholeCamera& camera, const CameraVelocity& velocity);

  size_t size() const { return lines.size(); }
  // Drops segment i where drop[i] (one flag per segment). Returns how many were dropped.
  size_t removeIf(const std::vector<bool>& drop);
  cv::Mat descriptor(size_t i) const { return descriptors.row(static_cast<int>(i)); }
  bool hasLine3D(size_t i) const { return lines3d[i].valid; }
  size_t numLines3D() const;
  // N_3D / N_2D (PAPER.md §3.1); 0 without segments.
  double reconstructionRate() const;
};

}  // namespace ply_slam
