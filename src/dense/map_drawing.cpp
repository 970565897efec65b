#include "ply_slam/dense/map_drawing.h"

#include <cmath>
#include <opencv2/imgproc.hpp>

namespace ply_slam {

void drawTrajectory(cv::Mat& image, const std::vector<cv::Point>& path) {
  if (path.empty()) return;
  cv::polylines(image, path, false, cv::Scalar(255, 255, 255), 5, cv::LINE_AA);
  cv::polylines(image, path, false, cv::Scalar(40, 40, 40), 2, cv::LINE_AA);
  cv::circle(image, path.front(), 6, cv::Scalar(0, 160, 0), cv::FILLED, cv::LINE_AA);
  cv::rectangle(image, path.back() - cv::Point(5, 5), path.back() + cv::Point(5, 5),
                cv::Scalar(0, 0, 200), cv::FILLED);
}

void drawScaleBar(cv::Mat& image, double px_per_m) {
  const int bar = static_cast<int>(std::lround(px_per_m));
  const cv::Point start(15, image.rows - 15);
  cv::line(image, start, start + cv::Point(bar, 0), cv::Scalar(0, 0, 0), 3);
  cv::putText(image, "1 m", start + cv::Point(0, -8), cv::FONT_HERSHEY_SIMPLEX, 0.5,
              cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
}

}  // namespace ply_slam
