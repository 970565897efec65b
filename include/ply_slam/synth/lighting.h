#pragma once

#include <Eigen/Core>

namespace ply_slam {

// Shading: ambient + diffuse * (n . light), with n the normal facing the viewer. The signed
// term is Lambert's law for a key light plus an equally strong fill light from the opposite
// side. The light comes from above and from behind a camera looking along +x; direction and
// strengths were searched (with the scenes' floor and ceiling colours) to maximise the
// smallest brightness step between perpendicular faces - wall and wall, wall and floor or
// ceiling, two faces of one box - which is about 0.09 of full scale: every edge of the scene
// is a visible image edge.
struct Lighting {
  Eigen::Vector3d direction = Eigen::Vector3d(-0.48, 0.05, 0.877).normalized();  // to light
  double ambient = 0.65;
  double diffuse = 0.4;
  double shade(const Eigen::Vector3d& normal) const {
    return ambient + diffuse * normal.normalized().dot(direction);
  }
};

}  // namespace ply_slam
