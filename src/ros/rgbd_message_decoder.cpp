#include "ply_slam/ros/rgbd_message_decoder.h"

#include <cv_bridge/cv_bridge.h>
#include <sensor_msgs/image_encodings.h>

#include <cmath>

#include "ply_slam/ros/image_layout.h"

namespace ply_slam {
namespace {

namespace enc = sensor_msgs::image_encodings;

std::string sizeOf(const sensor_msgs::Image& m) {
  return std::to_string(m.width) + "x" + std::to_string(m.height);
}

// Same checks for both images: not empty, data as long as the header says.
void checkLayout(const sensor_msgs::Image& m, const std::string& what) {
  if (m.width == 0 || m.height == 0 || m.data.empty())
    throw BadRgbdMessage("empty", what + " image is empty");
  const std::string error = imageLayoutError(m);
  if (!error.empty()) throw BadRgbdMessage("size", what + " image " + error);
}

}  // namespace

RgbdImages RgbdMessageDecoder::decode(const sensor_msgs::Image& rgb,
                                      const sensor_msgs::Image& depth,
                                      const sensor_msgs::CameraInfo* info) {
  const bool colour = rgb.encoding == enc::RGB8 || rgb.encoding == enc::BGR8 ||
                      rgb.encoding == enc::RGBA8 || rgb.encoding == enc::BGRA8;
  if (!colour)
    throw BadRgbdMessage("encoding", "colour image encoding '" + rgb.encoding +
                                         "' (expected rgb8, bgr8, rgba8 or bgra8)");
  const bool metres = depth.encoding == enc::TYPE_32FC1;
  const bool units = depth.encoding == enc::TYPE_16UC1 || depth.encoding == enc::MONO16;
  if (!metres && !units)
    throw BadRgbdMessage("encoding", "depth image encoding '" + depth.encoding +
                                         "' (expected 32FC1 in m or 16UC1 in mm)");
  if (depth.is_bigendian)  // cv_bridge would turn it into a 4-channel byte image
    throw BadRgbdMessage("encoding", "depth image is big-endian (only little-endian is read)");
  checkLayout(rgb, "colour");
  checkLayout(depth, "depth");
  if (rgb.width != depth.width || rgb.height != depth.height)
    throw BadRgbdMessage("size", "colour image is " + sizeOf(rgb) + " but depth is " +
                                     sizeOf(depth) + " (depth must be aligned to colour)");
  if (info && info->width > 0 && (info->width != rgb.width || info->height != rgb.height))
    throw BadRgbdMessage("size", "image is " + sizeOf(rgb) + " but camera_info says " +
                                     std::to_string(info->width) + "x" +
                                     std::to_string(info->height));
  const double stamp = rgb.header.stamp.toSec();
  if (stamp <= last_stamp_)
    throw BadRgbdMessage("stamp", "stamp " + std::to_string(stamp) +
                                      " does not follow the previous frame's " +
                                      std::to_string(last_stamp_));

  RgbdImages images;
  images.stamp = stamp;
  images.depth_stamp = depth.header.stamp.toSec();
  try {
    images.rgb = cv_bridge::toCvCopy(rgb, enc::BGR8)->image;
    const auto d = cv_bridge::toCvShare(depth, nullptr);
    if (metres) {
      d->image.copyTo(images.depth);
      cv::patchNaNs(images.depth, 0.0);  // NaN marks invalid depth in TUM bags
    } else {
      d->image.convertTo(images.depth, CV_32F, depth_16u_scale_);
    }
  } catch (const cv_bridge::Exception& e) {
    throw BadRgbdMessage("encoding", std::string("cannot convert: ") + e.what());
  }
  last_stamp_ = stamp;
  return images;
}

}  // namespace ply_slam
