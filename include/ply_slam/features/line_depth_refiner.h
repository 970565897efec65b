#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <vector>

#include "ply_slam/common/pinhole_camera.h"
#include "ply_slam/features/line_3d.h"
#include "ply_slam/features/line_feature.h"
#include "ply_slam/features/line_options.h"
#include "ply_slam/features/registered_depth.h"

namespace ply_slam {

// Beyond the paper: the depth along an accepted 3D line re-read from the surfaces beside its
// 2D segment. PAPER.md §3.1 reads one depth per pixel of the segment; on a short line a few
// metres away their noise turns the fitted direction by degrees (a 48 px line at 3.5 m:
// 1.5 degrees sigma with sigma_Z = 1.8 cm), while the surface on either side, planar over a
// few pixels, holds several times as many depths.
//
// Each side is fitted with 1/Z = a + b s + c t (exact for a plane; s along the segment, t
// across it, weights 1/var(1/Z) from the sensor's sigma_Z), on a band of columns t = 2, 3, ...
// px off the segment, one position per pixel along the fitted extent (at most 48). The band
// grows a column at a time up to surface_band_px while the new column continues the plane
// (mean residual within 3 sigma), so a narrow face is not fitted across its far edge; the
// column at t = 1 joins on the same test (at an occluding edge it is a hole or mixes both
// surfaces). Then samples off the plane by more than 3 sigma are dropped, twice. Each depth is
// placed at the pixel centre it was read from: at a surface seen at a grazing angle half a pixel is
// a centimetre. A side needs 3 columns of which half the pixels have depth.
//
// Who owns the line: both sides meeting at the segment (a crease, a painted edge): both,
// combined by their information; a step between them (an occluding edge): the nearer side;
// one side only: it, where it agrees with the paper's fit at both ends (within
// max(3 sigma_Z, 2 % of Z)). The line keeps its extent along the segment; its ends take the
// owner's depth. No owner: the paper's fit stays.
class LineDepthRefiner {
 public:
  LineDepthRefiner(const LineOptions& params, const PinholeCamera& camera);

  // line: the accepted fit of segment (camera frame). True when its ends were replaced; off
  // (false) when lines.surface_band_px is 0.
  bool refine(const LineFeature& segment, const cv::Mat& depth_m, Line3D& line) const;

 private:
  // Inverse depth at the segment (t = 0) as alpha + beta (s - s_mid), with its covariance.
  struct SideFit {
    bool ok = false;
    Eigen::Vector2d alpha_beta = Eigen::Vector2d::Zero();
    Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
  };
  // Positions along the fitted extent where the band's columns are read.
  struct Band {
    Eigen::Vector2d d, across;                // the segment's direction and normal (undistorted)
    std::vector<double> s;                    // along, from the extent's middle (undistorted px)
    std::vector<Eigen::Vector2d> raw;         // the raw pixel of each position on the segment
    std::vector<Eigen::Vector2d> raw_across;  // and the raw step of one px across there
  };
  SideFit fitSide(const Band& band, const cv::Mat& depth_m, double side) const;

  LineOptions params_;
  PinholeCamera camera_;
  RegisteredDepth depth_;
};

}  // namespace ply_slam
