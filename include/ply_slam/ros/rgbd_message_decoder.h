#pragma once

#include <sensor_msgs/CameraInfo.h>
#include <sensor_msgs/Image.h>

#include <stdexcept>
#include <string>

#include "ply_slam/io/rgbd_images.h"

namespace ply_slam {

// A message pair the tracker cannot use; `kind` groups faults for throttled logging.
class BadRgbdMessage : public std::invalid_argument {
 public:
  BadRgbdMessage(std::string kind, const std::string& what)
      : std::invalid_argument(what), kind_(std::move(kind)) {}
  const std::string& kind() const { return kind_; }

 private:
  std::string kind_;
};

// RGB + depth messages -> RgbdImages as the library takes them (BGR 8UC3, 32FC1 metres).
// Colour: rgb8, bgr8, rgba8, bgra8. Depth: 32FC1 (m) or 16UC1 / mono16 (units of
// depth_16u_scale m; REP 118: mm). Checks emptiness, encodings, data size, agreement with
// each other and with camera_info (when given) and that stamps move forward.
class RgbdMessageDecoder {
 public:
  explicit RgbdMessageDecoder(double depth_16u_scale = 0.001) : depth_16u_scale_(depth_16u_scale) {}

  // Throws BadRgbdMessage (kinds: empty, encoding, size, stamp).
  RgbdImages decode(const sensor_msgs::Image& rgb, const sensor_msgs::Image& depth,
                    const sensor_msgs::CameraInfo* info);

 private:
  double depth_16u_scale_;
  double last_stamp_ = -1.0;
};

}  // namespace ply_slam
