#pragma once

#include <opencv2/core.hpp>

namespace ply_slam {

// One rendered view. Everything is sampled at the pixel centre (u, v) = (col, row), the
// convention of PinholeCamera::project; only the colour of pixels on a silhouette is
// averaged over sub-pixel rays (anti-aliasing).
struct RenderedFrame {
  cv::Mat rgb;             // 8UC3 BGR
  cv::Mat depth;           // 32FC1, z along the optical axis in metres; 0 = no surface
  cv::Mat instance;        // 8UC1 instance id (Scene::kFirstObjectInstance); 0 = unlabelled
  cv::Mat surface;         // 32SC1 index of the visible quad in the rendered list; -1 = none
  cv::Mat surface_coords;  // 32FC2 metres along the quad's u and v axes: the texture point
};

}  // namespace ply_slam
