#include "ply_slam/synth/camera_path.h"

#include <algorithm>
#include <cmath>
#include <opencv2/core.hpp>
#include <stdexcept>

namespace ply_slam {
namespace {

constexpr int kWavesPerAxis = 3;
// Hand-held motion: the body sways slowly, the hand turns faster (hertz).
constexpr double kMinHz[2] = {0.08, 0.2}, kMaxHz[2] = {0.5, 1.0};  // position, rotation

double rotationAngle(const Eigen::Matrix3d& R) { return Eigen::AngleAxisd(R).angle(); }

// Share of a corner's turn made after the fraction u of its length: zero rate at both ends.
double turnShare(double u) { return u * u * (3.0 - 2.0 * u); }

Eigen::Vector2d direction(double heading) { return {std::cos(heading), std::sin(heading)}; }

}  // namespace

Circuit::Circuit(const Eigen::Vector2d& start, double heading, const Eigen::Vector2d& size,
                 double corner_length)
    : corner_length_(corner_length) {
  if (!(corner_length > 0.0)) throw std::invalid_argument("circuit: corner length must be > 0");
  // A corner cuts the rectangle's corner by the same distance along both sides (it is
  // symmetric about its bisector), so the straights are the sides less two cuts.
  const double cut = cornerOffset(corner_length).x();
  if (size.minCoeff() < 2.0 * cut)
    throw std::invalid_argument("circuit: a side is shorter than its two corners");
  // Entered half-way along the first side, left there after the four corners.
  const double straights[] = {0.5 * size.x() - cut, size.y() - 2.0 * cut, size.x() - 2.0 * cut,
                              size.y() - 2.0 * cut, 0.5 * size.x() - cut};
  Place place{start, heading};
  for (int k = 0; k < 5; ++k) {
    if (k > 0) place = append(place, corner_length, true);
    place = append(place, straights[k], false);
  }
}

Circuit::Place Circuit::append(const Place& start, double length, bool corner) {
  pieces_.push_back({start, length, corner});
  length_ += length;
  return placeIn(pieces_.back(), length);
}

Eigen::Vector2d Circuit::cornerOffset(double s) const {
  // Simpson's rule over the heading's direction: the integrand is smooth, 64 intervals leave
  // errors far below a micrometre, and every corner uses the same rule, so the walk closes.
  constexpr int kIntervals = 64;
  auto f = [&](double x) { return direction(0.5 * M_PI * turnShare(x / corner_length_)); };
  const double h = s / kIntervals;
  Eigen::Vector2d sum = f(0.0) + f(s);
  for (int k = 1; k < kIntervals; ++k) sum += (k % 2 ? 4.0 : 2.0) * f(k * h);
  return sum * h / 3.0;
}

Circuit::Place Circuit::placeIn(const Piece& piece, double s) const {
  Place place = piece.start;
  if (!piece.corner) {
    place.position += s * direction(place.heading);
    return place;
  }
  place.position += Eigen::Rotation2Dd(place.heading) * cornerOffset(s);
  place.heading += 0.5 * M_PI * turnShare(s / piece.length);
  return place;
}

Circuit::Place Circuit::at(double s) const {
  s = std::clamp(s, 0.0, length_);
  size_t k = 0;
  while (k + 1 < pieces_.size() && s > pieces_[k].length) s -= pieces_[k++].length;
  return placeIn(pieces_[k], std::min(s, pieces_[k].length));
}

// The smoothstep's steepest slope is 1.5 at the middle of the turn.
double Circuit::maxCurvature() const { return 1.5 * 0.5 * M_PI / corner_length_; }

CameraPath::CameraPath(const CameraPathSpec& spec, int frames, double fps, bool loop, uint64_t seed)
    : spec_(spec), frames_(frames), fps_(fps), loop_(loop) {
  if (frames < 2) throw std::invalid_argument("camera path: needs at least 2 frames");
  if (!(fps > 0)) throw std::invalid_argument("camera path: fps must be > 0");
  duration_ = (frames - 1) / fps;
  if (spec.circuit_size.minCoeff() > 0.0)
    circuit_ = Circuit(spec.centre.head<2>(), spec.yaw, spec.circuit_size, spec.corner_length);
  cv::RNG rng(seed * 2654435761ULL + 12345);
  for (int axis = 0; axis < 6; ++axis) {
    std::vector<double> weights;
    for (int k = 0; k < kWavesPerAxis; ++k) {
      Wave w;
      // One wave per frequency band, slow to fast: every seed gets some quick motion.
      const double band = (kMaxHz[axis / 3] - kMinHz[axis / 3]) / kWavesPerAxis;
      double hz = kMinHz[axis / 3] + band * (k + rng.uniform(0.0, 1.0));
      // Periodic path: whole cycles over the sequence (at least one).
      if (loop) hz = std::max(1.0, std::round(hz * duration_)) / duration_;
      w.omega = 2.0 * M_PI * hz;
      w.phase = rng.uniform(0.0, 2.0 * M_PI);
      w.amplitude = rng.uniform(0.3, 1.0);
      weights.push_back(w.amplitude);
      waves_[axis].push_back(w);
    }
    // Amplitudes sum to the axis' extent: the offset can never leave it.
    double sum = 0.0;
    for (double w : weights) sum += w;
    const double extent = axis < 3 ? spec.position_extent[axis] : spec.angle_extent[axis - 3];
    for (Wave& w : waves_[axis]) w.amplitude *= extent / sum;
  }
  // Scale the sway down until the mean speeds are the requested ones (bisection; the speeds
  // grow monotonically with the scale). Never scale up beyond the extents.
  auto fit = [&](double* scale, auto measure, double target) {
    *scale = 1.0;
    if (measure() <= target) return;
    double lo = 0.0, hi = 1.0;
    for (int it = 0; it < 40; ++it) {
      *scale = 0.5 * (lo + hi);
      (measure() > target ? hi : lo) = *scale;
    }
  };
  fit(
      &position_scale_, [&] { return meanLinearSpeed(); }, spec.linear_speed);
  fit(
      &angle_scale_, [&] { return meanAngularSpeed(); }, spec.angular_speed);
}

Eigen::Vector3d CameraPath::offsetPosition(double t) const {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int a = 0; a < 3; ++a)
    for (const Wave& w : waves_[a]) p[a] += w.amplitude * std::sin(w.omega * t + w.phase);
  return position_scale_ * p;
}

Eigen::Vector3d CameraPath::offsetAngles(double t) const {
  Eigen::Vector3d r = Eigen::Vector3d::Zero();
  for (int a = 0; a < 3; ++a)
    for (const Wave& w : waves_[a + 3]) r[a] += w.amplitude * std::sin(w.omega * t + w.phase);
  return angle_scale_ * r;
}

Eigen::Vector3d CameraPath::drift(double t) const {
  const double speed = spec_.drift_velocity.norm();
  if (speed <= 0.0 || duration_ <= 0.0) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d dir = spec_.drift_velocity / speed;
  if (loop_) {
    // Out and back with the same mean speed: D (1 - cos(2 pi t / T)) / 2 has mean |v| 2D / T.
    const double distance = std::min(0.5 * speed * duration_, spec_.max_drift);
    return dir * distance * 0.5 * (1.0 - std::cos(2.0 * M_PI * t / duration_));
  }
  const double distance = std::min(speed * duration_, spec_.max_drift);
  return dir * distance * (t / duration_);
}

Eigen::Isometry3d CameraPath::poseFrom(const Eigen::Vector3d& position, double yaw, double pitch,
                                       double roll) {
  const Eigen::Vector3d forward(std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw),
                                std::sin(pitch));
  const Eigen::Vector3d right = forward.cross(Eigen::Vector3d::UnitZ()).normalized();
  const Eigen::Vector3d down = forward.cross(right);
  Eigen::Matrix3d R;
  R << right, down, forward;
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = R * Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = position;
  return T;
}

Circuit::Place CameraPath::mean(double t) const {
  if (circuit_.empty()) return {spec_.centre.head<2>(), spec_.yaw};
  return circuit_.at(circuit_.length() * t / duration_);
}

Eigen::Isometry3d CameraPath::pose(double t) const {
  const Eigen::Vector3d angles = offsetAngles(t);
  const Circuit::Place m = mean(t);
  const Eigen::Vector3d centre(m.position.x(), m.position.y(), spec_.centre.z());
  return poseFrom(centre + drift(t) + offsetPosition(t), m.heading + angles[0],
                  spec_.pitch + angles[1], angles[2]);
}

double CameraPath::meanLinearSpeed() const {
  double sum = 0.0;
  for (int i = 1; i < frames_; ++i)
    sum += (poseAtFrame(i).translation() - poseAtFrame(i - 1).translation()).norm();
  return sum / duration_;
}

double CameraPath::meanAngularSpeed() const {
  double sum = 0.0;
  for (int i = 1; i < frames_; ++i)
    sum += rotationAngle(poseAtFrame(i - 1).linear().transpose() * poseAtFrame(i).linear());
  return sum / duration_;
}

}  // namespace ply_slam
