#include "ply_slam/common/pinhole_camera.h"

namespace ply_slam {

bool PinholeCamera::hasDistortion() const {
  return !distortion.empty() && cv::countNonZero(distortion != 0.0) > 0;
}

}  // namespace ply_slam
