#include "ply_slam/dense/top_view_renderer.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

#include "ply_slam/dense/map_drawing.h"
#include "ply_slam/io/image_file.h"

namespace ply_slam {
namespace {

// A right-handed frame whose z is `up`: map x = e1, map y = e2.
struct ViewFrame {
  Eigen::Vector3d e1, e2, up;
  explicit ViewFrame(const Eigen::Vector3d& up_in) : up(up_in.normalized()) {
    const Eigen::Vector3d seed =
        std::abs(up.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
    e1 = (seed - seed.dot(up) * up).normalized();
    e2 = up.cross(e1);
  }
};

cv::Scalar bgr(const ClassColour& c, double shade = 1.0) {
  return cv::Scalar(c.b * shade, c.g * shade, c.r * shade);
}

constexpr int kTitleHeight = 30;  // px above the map

// Voxels above the highest camera position + the margin are left out (the ceiling).
double ceilingOver(const Trajectory& trajectory, const ViewFrame& frame, double margin) {
  double ceiling = std::numeric_limits<double>::infinity();
  if (!trajectory.empty()) {
    ceiling = -ceiling;
    for (const auto& p : trajectory)
      ceiling = std::max(ceiling, p.T_wc.translation().dot(frame.up));
    ceiling += margin;
  }
  return ceiling;
}

std::vector<const SemanticOctree::Voxel*> voxelsBelow(
    const std::vector<SemanticOctree::Voxel>& voxels, double ceiling, const ViewFrame& frame) {
  std::vector<const SemanticOctree::Voxel*> shown;
  for (const auto& v : voxels)
    if (!(v.centre.dot(frame.up) > ceiling)) shown.push_back(&v);
  return shown;
}

// Where the map goes in the image: the extent of the voxels and the trajectory (m), their
// height range, the voxel size and the scale.
struct MapLayout {
  ViewFrame frame;
  double x0 = 1e9, x1 = -1e9, y0 = 1e9, y1 = -1e9, z0 = 1e9, z1 = -1e9, voxel = 0.05;
  double px_per_m = 0.0;
  int map_w = 0, map_h = 0;

  MapLayout(const std::vector<const SemanticOctree::Voxel*>& shown, const Trajectory& trajectory,
            const ViewFrame& view, int max_map_px)
      : frame(view) {
    for (const auto* v : shown) {
      grow(v->centre);
      const double h = v->centre.dot(frame.up);
      z0 = std::min(z0, h), z1 = std::max(z1, h);
      voxel = v->size;
    }
    for (const auto& p : trajectory) grow(p.T_wc.translation());
    if (x0 > x1) x0 = -1, x1 = 1, y0 = -1, y1 = 1;
    const double margin = 0.3;
    x0 -= margin, x1 += margin, y0 -= margin, y1 += margin;
    px_per_m = max_map_px / std::max(x1 - x0, y1 - y0);
    map_w = static_cast<int>(std::ceil((x1 - x0) * px_per_m));
    map_h = static_cast<int>(std::ceil((y1 - y0) * px_per_m));
  }
  void grow(const Eigen::Vector3d& p) {
    x0 = std::min(x0, p.dot(frame.e1)), x1 = std::max(x1, p.dot(frame.e1));
    y0 = std::min(y0, p.dot(frame.e2)), y1 = std::max(y1, p.dot(frame.e2));
  }
  // Map y grows away from the viewer's bottom edge: image rows run the other way.
  cv::Point2d toPixel(const Eigen::Vector3d& p) const {
    return cv::Point2d((p.dot(frame.e1) - x0) * px_per_m, (y1 - p.dot(frame.e2)) * px_per_m);
  }
};

// Highest voxel per column wins: drawn from the lowest up, shaded by height. Returns the
// number of voxels drawn per class label.
std::map<std::uint32_t, size_t> drawVoxels(cv::Mat& map,
                                           std::vector<const SemanticOctree::Voxel*> shown,
                                           const MapLayout& layout) {
  const Eigen::Vector3d up = layout.frame.up;
  std::sort(shown.begin(), shown.end(),
            [&](const auto* a, const auto* b) { return a->centre.dot(up) < b->centre.dot(up); });
  const double half = 0.5 * layout.voxel * layout.px_per_m;
  std::map<std::uint32_t, size_t> columns_per_label;
  for (const auto* v : shown) {
    const double h = v->centre.dot(up);
    const double shade =
        layout.z1 > layout.z0 ? 0.55 + 0.45 * (h - layout.z0) / (layout.z1 - layout.z0) : 1.0;
    const cv::Point2d c = layout.toPixel(v->centre);
    cv::rectangle(map, cv::Point(std::lround(c.x - half), std::lround(c.y - half)),
                  cv::Point(std::lround(c.x + half), std::lround(c.y + half)),
                  bgr(v->colour, shade), cv::FILLED);
    ++columns_per_label[v->label];
  }
  return columns_per_label;
}

// The classes shown, most columns first; the trajectory's marks; the voxel size.
void drawLegend(cv::Mat& image, const std::map<std::uint32_t, size_t>& columns_per_label,
                const ClassPalette& palette, const MapLayout& layout) {
  std::vector<std::pair<size_t, std::uint32_t>> order;
  for (const auto& [label, n] : columns_per_label) order.emplace_back(n, label);
  std::sort(order.rbegin(), order.rend());
  int y = kTitleHeight + 20;
  const int x = layout.map_w + 12;
  auto entry = [&](const cv::Scalar& colour, const std::string& text) {
    cv::rectangle(image, cv::Rect(x, y - 11, 14, 14), colour, cv::FILLED);
    cv::putText(image, text, cv::Point(x + 22, y), cv::FONT_HERSHEY_SIMPLEX, 0.45,
                cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
    y += 20;
  };
  for (const auto& [n, label] : order) {
    if (y > image.rows - 60) break;
    entry(bgr(palette.colour(label)), palette.name(label));
  }
  y += 10;
  entry(cv::Scalar(0, 160, 0), "trajectory start");
  entry(cv::Scalar(0, 0, 200), "trajectory end");
  const int voxel_cm = static_cast<int>(std::lround(layout.voxel * 100));
  cv::putText(image, "voxel " + std::to_string(voxel_cm) + " cm", cv::Point(x, y + 5),
              cv::FONT_HERSHEY_SIMPLEX, 0.45, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
}

}  // namespace

TopViewRenderer::TopViewRenderer(double max_height_above_camera, int max_map_px)
    : max_height_above_camera_(max_height_above_camera), max_map_px_(max_map_px) {
  if (max_map_px < 100) throw std::invalid_argument("TopViewRenderer: max_map_px must be >= 100");
}

Eigen::Vector3d TopViewRenderer::upFromTrajectory(const Trajectory& trajectory) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& p : trajectory) sum -= p.T_wc.linear().col(1);
  return sum.norm() > 1e-9 ? Eigen::Vector3d(sum.normalized()) : Eigen::Vector3d::UnitZ();
}

cv::Mat TopViewRenderer::render(const std::vector<SemanticOctree::Voxel>& voxels,
                                const Trajectory& trajectory, const Eigen::Vector3d& up,
                                const ClassPalette& palette, const std::string& title) const {
  const ViewFrame frame(up);
  const std::vector<const SemanticOctree::Voxel*> shown =
      voxelsBelow(voxels, ceilingOver(trajectory, frame, max_height_above_camera_), frame);
  const MapLayout layout(shown, trajectory, frame, max_map_px_);
  const int legend_w = 230;
  cv::Mat image(std::max(layout.map_h, 300) + kTitleHeight, layout.map_w + legend_w, CV_8UC3,
                cv::Scalar(255, 255, 255));
  cv::Mat map = image(cv::Rect(0, kTitleHeight, layout.map_w, layout.map_h));
  const std::map<std::uint32_t, size_t> columns_per_label = drawVoxels(map, shown, layout);
  std::vector<cv::Point> path;
  for (const auto& p : trajectory) {
    const cv::Point2d q = layout.toPixel(p.T_wc.translation());
    path.emplace_back(std::lround(q.x), std::lround(q.y));
  }
  drawTrajectory(map, path);
  drawScaleBar(map, layout.px_per_m);
  cv::putText(image, title, cv::Point(8, 21), cv::FONT_HERSHEY_SIMPLEX, 0.55, cv::Scalar(0, 0, 0),
              1, cv::LINE_AA);
  drawLegend(image, columns_per_label, palette, layout);
  return image;
}

void TopViewRenderer::write(const std::string& png_path,
                            const std::vector<SemanticOctree::Voxel>& voxels,
                            const Trajectory& trajectory, const Eigen::Vector3d& up,
                            const ClassPalette& palette, const std::string& title) const {
  writeImageFile(png_path, render(voxels, trajectory, up, palette, title));
}

}  // namespace ply_slam
