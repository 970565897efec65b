#include "ply_slam/synth/quad.h"

namespace ply_slam {

Eigen::Vector3d Quad::corner(int k) const {
  switch (k & 3) {
    case 0:
      return origin;
    case 1:
      return origin + axis_u;
    case 2:
      return origin + axis_u + axis_v;
    default:
      return origin + axis_v;
  }
}

}  // namespace ply_slam
