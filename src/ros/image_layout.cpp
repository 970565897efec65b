#include "ply_slam/ros/image_layout.h"

#include <sensor_msgs/image_encodings.h>

#include <climits>
#include <cstdint>
#include <stdexcept>

namespace ply_slam {

std::string imageLayoutError(const sensor_msgs::Image& m) {
  namespace enc = sensor_msgs::image_encodings;
  uint64_t pixel_bytes = 0;
  try {
    pixel_bytes =
        static_cast<uint64_t>(enc::numChannels(m.encoding)) * (enc::bitDepth(m.encoding) / 8);
  } catch (const std::runtime_error&) {
    return "unknown encoding '" + m.encoding + "'";
  }
  // In 64 bits: in 32 a huge width times the pixel size wraps round to a small row.
  const uint64_t row = pixel_bytes * m.width;
  const std::string size = std::to_string(m.width) + "x" + std::to_string(m.height);
  if (m.step < row || m.data.size() != uint64_t{m.step} * m.height)
    return size + " " + m.encoding + " image has " + std::to_string(m.data.size()) +
           " bytes, step " + std::to_string(m.step);
  // cv_bridge "swaps" big-endian data into a multi-channel byte image, not 16- or 32-bit.
  if (m.is_bigendian && pixel_bytes > static_cast<uint64_t>(enc::numChannels(m.encoding)))
    return size + " " + m.encoding + " image is big-endian (only little-endian is read)";
  // cv::Mat takes int sizes and steps.
  if (m.width > INT_MAX || m.height > INT_MAX || m.step > INT_MAX)
    return size + " image is too large";
  return "";
}

}  // namespace ply_slam
