#include "ply_slam/eval/pr_plot.h"

#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "ply_slam/io/image_file.h"

namespace ply_slam {
namespace {

constexpr int kPlotWidth = 760, kPlotHeight = 600;
constexpr int kLeft = 70, kRight = 20, kTop = 50, kBottom = 60;
constexpr int kPlotFont = cv::FONT_HERSHEY_SIMPLEX;
const cv::Scalar kColours[] = {{200, 120, 0}, {0, 150, 0},   {0, 140, 255},
                               {0, 0, 210},   {150, 0, 150}, {90, 90, 90}};

cv::Point toPixel(double recall, double precision) {
  const double w = kPlotWidth - kLeft - kRight, h = kPlotHeight - kTop - kBottom;
  return {kLeft + static_cast<int>(recall * w), kTop + static_cast<int>((1.0 - precision) * h)};
}

void drawAxes(cv::Mat& image) {
  for (int k = 0; k <= 10; ++k) {
    const double v = k / 10.0;
    cv::line(image, toPixel(v, 0), toPixel(v, 1), {225, 225, 225});
    cv::line(image, toPixel(0, v), toPixel(1, v), {225, 225, 225});
    char text[8];
    std::snprintf(text, sizeof(text), "%.1f", v);
    cv::putText(image, text, toPixel(v, 0) + cv::Point(-12, 20), kPlotFont, 0.4, {0, 0, 0});
    cv::putText(image, text, toPixel(0, v) + cv::Point(-35, 5), kPlotFont, 0.4, {0, 0, 0});
  }
  cv::rectangle(image, toPixel(0, 1), toPixel(1, 0), {120, 120, 120});
  cv::putText(image, "recall", {kPlotWidth / 2 - 20, kPlotHeight - 15}, kPlotFont, 0.5, {0, 0, 0});
  cv::putText(image, "precision", {5, kTop - 12}, kPlotFont, 0.5, {0, 0, 0});
}

// Steps as the detector moves: from (0, 1) through each threshold's (recall, precision).
void drawCurve(cv::Mat& image, const PrCurve& curve, const cv::Scalar& colour, int thickness) {
  cv::Point last = toPixel(0.0, 1.0);
  for (const PrPoint& p : curve.points) {
    const cv::Point next = toPixel(p.recall, p.precision);
    cv::line(image, last, next, colour, thickness, cv::LINE_AA);
    last = next;
  }
}

}  // namespace

void writePrPlot(const std::string& png_path,
                 const std::vector<std::pair<std::string, PrCurve>>& curves,
                 const std::string& title) {
  cv::Mat image(kPlotHeight, kPlotWidth, CV_8UC3, cv::Scalar(255, 255, 255));
  drawAxes(image);
  cv::putText(image, title, {kLeft, 25}, kPlotFont, 0.5, {0, 0, 0});
  const int n = static_cast<int>(sizeof(kColours) / sizeof(kColours[0]));
  for (size_t i = 0; i < curves.size(); ++i) {
    const cv::Scalar& colour = kColours[i % n];
    // Earlier curves wider: one that another covers exactly still shows as its border.
    drawCurve(image, curves[i].second, colour, 2 + 2 * static_cast<int>(curves.size() - 1 - i));
    char legend[160];
    std::snprintf(legend, sizeof(legend), "%s  AUC %.3f  R@P1 %.2f", curves[i].first.c_str(),
                  curves[i].second.average_precision, curves[i].second.recall_at_full_precision);
    const cv::Point at = toPixel(0.03, 0.30) + cv::Point(0, 22 * static_cast<int>(i));
    cv::line(image, at + cv::Point(0, -4), at + cv::Point(25, -4), colour, 2);
    cv::putText(image, legend, at + cv::Point(32, 0), kPlotFont, 0.45, {0, 0, 0});
  }
  writeImageFile(png_path, image);
}

}  // namespace ply_slam
