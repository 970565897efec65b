#include "ply_slam/eval/trajectory_plot.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <vector>

#include "ply_slam/io/image_file.h"

namespace ply_slam {
namespace {

constexpr int kWidth = 1200;
constexpr int kHeight = 600;
constexpr int kTitleBand = 75;     // title, legend and panel names above the plot areas
constexpr int kBottomMargin = 55;  // tick labels and axis name below
constexpr int kLeftMargin = 65;    // tick labels left of each plot area
constexpr int kRightMargin = 20;
constexpr double kMinSpan = 0.1;  // m; a single pose still gets a readable grid
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;
constexpr int kShift = 4;  // sub-pixel bits for anti-aliased polylines

const cv::Scalar kBackground(255, 255, 255);
const cv::Scalar kGridColor(225, 225, 225);
const cv::Scalar kFrameColor(120, 120, 120);
const cv::Scalar kTextColor(0, 0, 0);
const cv::Scalar kGtColor(0, 150, 0);   // green (BGR)
const cv::Scalar kEstColor(0, 0, 220);  // red (BGR)

// One view: which coordinates of the position are drawn, and the world-to-pixel mapping.
struct Panel {
  int u_axis, v_axis;               // 0 = x, 1 = y, 2 = z
  cv::Rect area;                    // plot area in pixels
  double scale = 1.0;               // pixels per metre, equal for both axes
  double u_min = 0.0, v_min = 0.0;  // world values at the left and bottom edges

  double uMax() const { return u_min + area.width / scale; }
  double vMax() const { return v_min + area.height / scale; }
  cv::Point2d toPixel(double u, double v) const {
    return {area.x + (u - u_min) * scale, area.y + area.height - (v - v_min) * scale};
  }
};

cv::Point fixedPoint(const cv::Point2d& p) {
  return {cvRound(p.x * (1 << kShift)), cvRound(p.y * (1 << kShift))};
}

std::vector<cv::Point2d> projectedPositions(const Trajectory& trajectory, const Panel& panel) {
  std::vector<cv::Point2d> points;
  for (const StampedPose& pose : trajectory) {
    const Eigen::Vector3d t = pose.T_wc.translation();
    if (t.allFinite()) points.emplace_back(t[panel.u_axis], t[panel.v_axis]);
  }
  return points;
}

// Chooses the metric window so that all positions fit with the same scale on both axes.
void fitPanel(const std::vector<cv::Point2d>& world, Panel* panel) {
  double u_lo = 0.0, u_hi = 0.0, v_lo = 0.0, v_hi = 0.0;
  if (!world.empty()) {
    u_lo = u_hi = world.front().x;
    v_lo = v_hi = world.front().y;
    for (const cv::Point2d& p : world) {
      u_lo = std::min(u_lo, p.x), u_hi = std::max(u_hi, p.x);
      v_lo = std::min(v_lo, p.y), v_hi = std::max(v_hi, p.y);
    }
  }
  // 5 % padding keeps the curves off the frame.
  const double span_u = std::max(u_hi - u_lo, kMinSpan) * 1.1;
  const double span_v = std::max(v_hi - v_lo, kMinSpan) * 1.1;
  panel->scale = std::min(panel->area.width / span_u, panel->area.height / span_v);
  panel->u_min = 0.5 * (u_lo + u_hi) - 0.5 * panel->area.width / panel->scale;
  panel->v_min = 0.5 * (v_lo + v_hi) - 0.5 * panel->area.height / panel->scale;
}

// 1, 2 or 5 times a power of ten, the smallest such step >= raw.
double niceStep(double raw) {
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (double factor : {1.0, 2.0, 5.0}) {
    if (raw <= factor * power * (1.0 + 1e-9)) return factor * power;
  }
  return 10.0 * power;
}

std::string formatMetres(double value, double step) {
  const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  if (std::abs(value) < 1e-6 * step) value = 0.0;  // no "-0.0"
  char text[32];
  std::snprintf(text, sizeof(text), "%.*f", decimals, value);
  return text;
}

void putTextAligned(cv::Mat& image, const std::string& text, cv::Point anchor, double font_scale,
                    double align_x, double align_y, int thickness = 1) {
  int baseline = 0;
  const cv::Size size = cv::getTextSize(text, kFont, font_scale, thickness, &baseline);
  const cv::Point origin(anchor.x - cvRound(align_x * size.width),
                         anchor.y + cvRound(align_y * size.height));
  cv::putText(image, text, origin, kFont, font_scale, kTextColor, thickness, cv::LINE_AA);
}

void drawGrid(cv::Mat& image, const Panel& panel) {
  const double visible = std::max(panel.uMax() - panel.u_min, panel.vMax() - panel.v_min);
  const double step = niceStep(visible / 8.0);
  const cv::Rect& a = panel.area;
  // Integer line indices, so rounding does not accumulate along the grid.
  for (long k = std::lround(std::ceil(panel.u_min / step)); k * step <= panel.uMax(); ++k) {
    const double u = k * step;
    const int x = cvRound(panel.toPixel(u, 0.0).x);
    cv::line(image, {x, a.y}, {x, a.y + a.height}, kGridColor, 1);
    putTextAligned(image, formatMetres(u, step), {x, a.y + a.height + 6}, 0.4, 0.5, 1.0);
  }
  for (long k = std::lround(std::ceil(panel.v_min / step)); k * step <= panel.vMax(); ++k) {
    const double v = k * step;
    const int y = cvRound(panel.toPixel(0.0, v).y);
    cv::line(image, {a.x, y}, {a.x + a.width, y}, kGridColor, 1);
    putTextAligned(image, formatMetres(v, step), {a.x - 6, y}, 0.4, 1.0, 0.5);
  }
  cv::rectangle(image, a, kFrameColor, 1);
  static const char* const kAxisNames[] = {"x [m]", "y [m]", "z [m]"};
  putTextAligned(image, kAxisNames[panel.u_axis], {a.x + a.width / 2, a.y + a.height + 32}, 0.5,
                 0.5, 1.0);
  putTextAligned(image, kAxisNames[panel.v_axis], {a.x - kLeftMargin + 8, a.y - 8}, 0.5, 0.0, 0.0);
}

void drawTrajectory(cv::Mat& image, const Panel& panel, const std::vector<cv::Point2d>& world,
                    const cv::Scalar& color, int thickness) {
  if (world.empty()) return;
  std::vector<cv::Point> pixels;
  pixels.reserve(world.size());
  for (const cv::Point2d& p : world) pixels.push_back(fixedPoint(panel.toPixel(p.x, p.y)));
  if (pixels.size() > 1) {
    cv::polylines(image, pixels, false, color, thickness, cv::LINE_AA, kShift);
  }
  // The start marker also makes a single-pose trajectory visible.
  cv::circle(image, pixels.front(), (thickness + 3) << kShift, color, cv::FILLED, cv::LINE_AA,
             kShift);
}

void drawPanel(cv::Mat& image, Panel panel, const std::string& name, const Trajectory& gt,
               const Trajectory& est) {
  const std::vector<cv::Point2d> gt_world = projectedPositions(gt, panel);
  const std::vector<cv::Point2d> est_world = projectedPositions(est, panel);
  std::vector<cv::Point2d> all = gt_world;
  all.insert(all.end(), est_world.begin(), est_world.end());
  fitPanel(all, &panel);
  drawGrid(image, panel);
  // Ground truth underneath and thicker, so an estimate lying on it leaves a visible rim.
  drawTrajectory(image, panel, gt_world, kGtColor, 3);
  drawTrajectory(image, panel, est_world, kEstColor, 1);
  putTextAligned(image, name, {panel.area.x, panel.area.y - 8}, 0.55, 0.0, 0.0);
  if (all.empty()) {
    putTextAligned(image, "no poses",
                   {panel.area.x + panel.area.width / 2, panel.area.y + panel.area.height / 2}, 0.7,
                   0.5, 0.5);
  }
}

// Legend entries right-aligned in the title band; returns its left edge.
int drawLegend(cv::Mat& image) {
  const std::pair<const char*, cv::Scalar> entries[] = {{"ground truth", kGtColor},
                                                        {"estimate (aligned)", kEstColor}};
  int right = kWidth - kRightMargin;
  for (int k = 1; k >= 0; --k) {
    int baseline = 0;
    const cv::Size size = cv::getTextSize(entries[k].first, kFont, 0.5, 1, &baseline);
    const int text_left = right - size.width;
    cv::putText(image, entries[k].first, {text_left, 28}, kFont, 0.5, kTextColor, 1, cv::LINE_AA);
    cv::line(image, {text_left - 35, 23}, {text_left - 8, 23}, entries[k].second, 3, cv::LINE_AA);
    right = text_left - 55;
  }
  return right;
}

void drawTitle(cv::Mat& image, std::string title, int right_limit) {
  const int left = 15;
  const int available = right_limit - left;
  double font_scale = 0.8;
  int baseline = 0;
  // Shrink long titles first, then cut them, rather than let them run under the legend.
  while (font_scale > 0.45 &&
         cv::getTextSize(title, kFont, font_scale, 2, &baseline).width > available) {
    font_scale -= 0.05;
  }
  while (title.size() > 3 &&
         cv::getTextSize(title, kFont, font_scale, 2, &baseline).width > available) {
    title = title.substr(0, title.size() - 4) + "...";
  }
  cv::putText(image, title, {left, 32}, kFont, font_scale, kTextColor, 2, cv::LINE_AA);
}

}  // namespace

void writeTrajectoryPlot(const std::string& png_path, const Trajectory& gt,
                         const Trajectory& est_aligned, const std::string& title) {
  cv::Mat image(kHeight, kWidth, CV_8UC3, kBackground);
  const int panel_width = kWidth / 2;
  const int area_width = panel_width - kLeftMargin - kRightMargin;
  const int area_height = kHeight - kTitleBand - kBottomMargin;
  Panel top{0, 1, cv::Rect(kLeftMargin, kTitleBand, area_width, area_height)};
  Panel side{0, 2, cv::Rect(panel_width + kLeftMargin, kTitleBand, area_width, area_height)};
  drawPanel(image, top, "top view (x-y)", gt, est_aligned);
  drawPanel(image, side, "side view (x-z)", gt, est_aligned);
  drawTitle(image, title, drawLegend(image) - 20);

  writeImageFile(png_path, image);
}

}  // namespace ply_slam
