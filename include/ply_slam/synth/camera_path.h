#pragma once

#include <Eigen/Geometry>
#include <array>
#include <cstdint>
#include <vector>

namespace ply_slam {

// Where and how a hand-held camera moves in a scene.
struct CameraPathSpec {
  Eigen::Vector3d centre = Eigen::Vector3d(0.0, 0.0, 1.4);  // mean position (world, m)
  double yaw = 0.0;    // rad, mean viewing direction about world z, from +x
  double pitch = 0.0;  // rad, positive looks up
  Eigen::Vector3d drift_velocity = Eigen::Vector3d::Zero();  // m/s, walking along
  double max_drift = 0.0;  // m, cap on the whole drift (keeps the camera in the room)
  Eigen::Vector3d position_extent = Eigen::Vector3d(0.3, 0.3, 0.1);  // max |offset| per axis
  Eigen::Vector3d angle_extent = Eigen::Vector3d(0.4, 0.15, 0.08);   // rad: yaw, pitch, roll
  double linear_speed = 0.3;                                         // m/s, mean
  double angular_speed = 0.524;                                      // rad/s, mean (30 deg/s)
  // A circuit walked once over the whole sequence at constant speed, counter-clockwise: a
  // rectangle of corridor centre lines, `circuit_size` along the first heading `yaw` and to
  // its left, entered at `centre` half-way along its first side. The mean pose then moves along
  // the circuit, facing along it; the sway comes on top. Zero size: no circuit.
  Eigen::Vector2d circuit_size = Eigen::Vector2d::Zero();  // m
  double corner_length = 1.5;  // m of path over which each 90-degree turn is spread
};

// A closed walk around a rectangle with 90-degree left turns at the corners. Over a corner the
// heading follows a smoothstep of the arc length, so the turn rate rises from zero and falls
// back to it as a walker's does, instead of jumping to the rate of a circular arc. The four
// corners have the same shape, so the walk ends exactly where it started.
class Circuit {
 public:
  struct Place {
    Eigen::Vector2d position;  // world xy, m
    double heading;            // rad from +x; grows by 2 pi over the circuit
  };

  Circuit() = default;
  // Throws std::invalid_argument when a side is too short for its two corners.
  Circuit(const Eigen::Vector2d& start, double heading, const Eigen::Vector2d& size,
          double corner_length);

  bool empty() const { return pieces_.empty(); }
  double length() const { return length_; }
  // Where the walk is after s metres (clamped to [0, length()]).
  Place at(double s) const;
  // Highest turn rate per metre walked (rad/m): times the speed, the corners' rad/s.
  double maxCurvature() const;

 private:
  struct Piece {
    Place start;
    double length;
    bool corner;
  };
  Eigen::Vector2d cornerOffset(double s) const;  // corner-local, s metres into the turn
  Place append(const Place& start, double length, bool corner);  // returns the piece's end
  Place placeIn(const Piece& piece, double s) const;

  std::vector<Piece> pieces_;
  double length_ = 0.0;
  double corner_length_ = 0.0;
};

// Smooth hand-held motion: the mean pose (fixed, drifting, or walking a circuit) plus, per axis of
// position and of yaw / pitch / roll, a sum of sinusoids with seeded frequencies and phases, scaled
// so that the mean speeds match the spec (within the extents). With `loop` every frequency is a
// multiple of the sequence's period, so the last frame's pose equals the first's.
class CameraPath {
 public:
  CameraPath(const CameraPathSpec& spec, int frames, double fps, bool loop, uint64_t seed);

  // T_wc at time t (s): camera x right, y down, z forward.
  Eigen::Isometry3d pose(double t) const;
  Eigen::Isometry3d poseAtFrame(int i) const { return pose(i / fps_); }

  int frames() const { return frames_; }
  double fps() const { return fps_; }
  // Mean speeds over the frames, measured from consecutive poses.
  double meanLinearSpeed() const;
  double meanAngularSpeed() const;  // rad/s

 private:
  struct Wave {
    double amplitude, omega, phase;
  };
  Eigen::Vector3d offsetPosition(double t) const;
  Eigen::Vector3d offsetAngles(double t) const;
  Eigen::Vector3d drift(double t) const;
  Circuit::Place mean(double t) const;  // position (xy) and heading without the sway
  static Eigen::Isometry3d poseFrom(const Eigen::Vector3d& position, double yaw, double pitch,
                                    double roll);

  CameraPathSpec spec_;
  int frames_;
  double fps_;
  bool loop_;
  double duration_;                         // s, from the first to the last frame
  Circuit circuit_;                         // empty: the camera stays around the centre
  std::array<std::vector<Wave>, 6> waves_;  // x y z yaw pitch roll
  double position_scale_ = 1.0, angle_scale_ = 1.0;
};

}  // namespace ply_slam
