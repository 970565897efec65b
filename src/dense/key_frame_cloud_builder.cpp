#include "ply_slam/dense/key_frame_cloud_builder.h"

#include <pcl/point_cloud.h>
#include <pcl/point_types.h>

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <unordered_map>

#include "ply_slam/dense/voxel_filter.h"

namespace ply_slam {
namespace {

void require(bool ok, const KeyFramePacket& packet, const std::string& what) {
  if (!ok)
    throw std::invalid_argument("dense cloud of keyframe " + std::to_string(packet.id) + ": " +
                                what);
}

bool sameIntrinsics(const PinholeCamera& a, const PinholeCamera& b) {
  if (a.fx != b.fx || a.fy != b.fy || a.cx != b.cx || a.cy != b.cy || a.width != b.width ||
      a.height != b.height || a.distortion.total() != b.distortion.total())
    return false;
  return a.distortion.empty() || cv::norm(a.distortion, b.distortion, cv::NORM_INF) == 0.0;
}

}  // namespace

KeyFrameCloudBuilder::KeyFrameCloudBuilder(const DenseOptions& params, ClassPalette palette)
    : params_(params), palette_(std::move(palette)) {
  if (params_.stride < 1) throw std::invalid_argument("dense: stride must be >= 1");
  if (!(params_.min_depth > 0.0) || !(params_.max_depth > params_.min_depth))
    throw std::invalid_argument("dense: need 0 < min_depth < max_depth");
  if (!(params_.voxel_size > 0.0)) throw std::invalid_argument("dense: voxel_size must be > 0");
}

const cv::Mat& KeyFrameCloudBuilder::rayTable(const PinholeCamera& camera) const {
  if (!rays_.empty() && sameIntrinsics(camera, rays_camera_)) return rays_;
  std::vector<cv::Point2f> pixels;
  pixels.reserve(static_cast<size_t>(camera.width) * camera.height);
  for (int v = 0; v < camera.height; ++v)
    for (int u = 0; u < camera.width; ++u) pixels.emplace_back(u, v);
  std::vector<cv::Point2f> normalised;
  if (camera.hasDistortion()) {
    // Without P, undistortPoints returns normalised coordinates directly.
    cv::undistortPoints(pixels, normalised, cv::Mat(camera.K()), camera.distortion);
  } else {
    normalised.reserve(pixels.size());
    for (const auto& p : pixels)
      normalised.emplace_back(static_cast<float>((p.x - camera.cx) / camera.fx),
                              static_cast<float>((p.y - camera.cy) / camera.fy));
  }
  rays_ = cv::Mat(normalised, true).reshape(2, camera.height);
  rays_camera_ = camera;
  rays_camera_.distortion = camera.distortion.clone();
  return rays_;
}

cv::Mat KeyFrameCloudBuilder::excludedPixels(const KeyFramePacket& packet) const {
  cv::Mat excluded = packet.dynamic_mask.empty() ? cv::Mat::zeros(packet.depth.size(), CV_8UC1)
                                                 : (packet.dynamic_mask != 0);
  if (!packet.label_image.empty())
    for (const auto& instance : packet.instances)
      if (instance.dynamic) excluded |= (packet.label_image == instance.id);
  if (params_.dilation_px > 0) {
    const int k = 2 * params_.dilation_px + 1;
    cv::dilate(excluded, excluded, cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(k, k)));
  }
  return excluded;
}

KeyFrameCloud KeyFrameCloudBuilder::build(const KeyFramePacket& packet,
                                          const cv::Mat& tag_mask) const {
  require(!packet.depth.empty() && packet.depth.type() == CV_32FC1, packet,
          "depth must be a non-empty 32FC1 image");
  require(!packet.rgb.empty() && packet.rgb.type() == CV_8UC3, packet,
          "rgb must be a non-empty 8UC3 image");
  const cv::Size size = packet.depth.size();
  require(packet.rgb.size() == size, packet, "rgb and depth differ in size");
  require(packet.camera.width == size.width && packet.camera.height == size.height, packet,
          "the camera's size differs from the images'");
  require(packet.camera.fx > 0 && packet.camera.fy > 0, packet, "the camera has no intrinsics");
  require(packet.label_image.empty() ||
              (packet.label_image.type() == CV_16UC1 && packet.label_image.size() == size),
          packet, "label_image must be empty or 16UC1 of the image size");
  require(packet.dynamic_mask.empty() ||
              (packet.dynamic_mask.type() == CV_8UC1 && packet.dynamic_mask.size() == size),
          packet, "dynamic_mask must be empty or 8UC1 of the image size");
  require(tag_mask.empty() || (tag_mask.type() == CV_8UC1 && tag_mask.size() == size), packet,
          "the tag mask must be empty or 8UC1 of the image size");

  std::unordered_map<int, std::uint32_t> instance_label;
  for (const auto& instance : packet.instances)
    instance_label[instance.id] = palette_.label(instance.class_name);
  const cv::Mat excluded = excludedPixels(packet);
  const cv::Mat& rays = rayTable(packet.camera);

  DenseCloud points, tags;
  std::vector<Eigen::Vector3f> clearing_rays;
  const int stride = params_.stride;
  const double far_limit = packet.camera.max_depth;
  for (int v = 0; v < size.height; v += stride) {
    const float* depth = packet.depth.ptr<float>(v);
    const cv::Vec3b* bgr = packet.rgb.ptr<cv::Vec3b>(v);
    const cv::Vec2f* ray = rays.ptr<cv::Vec2f>(v);
    const std::uint8_t* out = excluded.ptr<std::uint8_t>(v);
    const std::uint16_t* ids =
        packet.label_image.empty() ? nullptr : packet.label_image.ptr<std::uint16_t>(v);
    const std::uint8_t* tag = tag_mask.empty() ? nullptr : tag_mask.ptr<std::uint8_t>(v);
    for (int u = 0; u < size.width; u += stride) {
      const float z = depth[u];
      if (!std::isfinite(z) || z < params_.min_depth || out[u]) continue;
      if (z > params_.max_depth) {
        if (z <= far_limit) clearing_rays.emplace_back(ray[u][0] * z, ray[u][1] * z, z);
        continue;
      }
      pcl::PointXYZRGBL p;
      p.x = ray[u][0] * z;
      p.y = ray[u][1] * z;
      p.z = z;
      p.r = bgr[u][2];
      p.g = bgr[u][1];
      p.b = bgr[u][0];
      p.a = 255;
      p.label = ClassPalette::kUnknown;
      if (ids && ids[u]) {
        const auto it = instance_label.find(ids[u]);
        if (it != instance_label.end()) p.label = it->second;
      }
      points.push_back(p);
      if (tag) {
        p.label = tag[u] ? 1 : 0;
        tags.push_back(p);
      }
    }
  }

  KeyFrameCloud cloud;
  cloud.id = packet.id;
  cloud.T_wc = packet.T_wc;
  cloud.clearing_rays = std::move(clearing_rays);
  // Same points, same voxel grid: the filtered tags line up with the filtered points.
  cloud.points = voxelFilter(points, params_.voxel_size);
  if (!tag_mask.empty()) cloud.tags = voxelFilter(tags, params_.voxel_size);
  return cloud;
}

}  // namespace ply_slam
