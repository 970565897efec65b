#pragma once

#include <sensor_msgs/Image.h>

#include <string>

namespace ply_slam {

// Why an image message cannot be read as its header says, or "" when it can: a known
// encoding, a row step that holds a row, exactly step x height bytes, sizes that fit an int,
// little-endian when a channel has more than one byte.
std::string imageLayoutError(const sensor_msgs::Image& image);

}  // namespace ply_slam
