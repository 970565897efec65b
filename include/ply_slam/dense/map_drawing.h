#pragma once

#include <opencv2/core.hpp>
#include <vector>

namespace ply_slam {

// Marks shared by the map pictures (map_top.png, grid.png).
// The camera path: a dark line with a white casing, a green start circle, a red end square.
void drawTrajectory(cv::Mat& image, const std::vector<cv::Point>& path);
// A 1 m bar in the bottom-left corner.
void drawScaleBar(cv::Mat& image, double px_per_m);

}  // namespace ply_slam
