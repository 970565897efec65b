#include "ply_slam/ros/message_parts.h"

#include <cv_bridge/cv_bridge.h>

#include <cmath>
#include <stdexcept>

#include "ply_slam/common/rotation_check.h"
#include "ply_slam/ros/image_layout.h"

namespace ply_slam {

geometry_msgs::Point toPointMsg(const Eigen::Vector3d& p) {
  geometry_msgs::Point m;
  m.x = p.x();
  m.y = p.y();
  m.z = p.z();
  return m;
}

Eigen::Vector3d fromPointMsg(const geometry_msgs::Point& m) {
  const Eigen::Vector3d p(m.x, m.y, m.z);
  if (!p.allFinite()) throw std::invalid_argument("a point or position is not finite");
  return p;
}

geometry_msgs::Vector3 toVector3Msg(const Eigen::Vector3d& v) {
  geometry_msgs::Vector3 m;
  m.x = v.x();
  m.y = v.y();
  m.z = v.z();
  return m;
}

Eigen::Vector3d fromVector3Msg(const geometry_msgs::Vector3& m) {
  const Eigen::Vector3d v(m.x, m.y, m.z);
  if (!v.allFinite()) throw std::invalid_argument("a vector is not finite");
  return v;
}

RigidTransformMsg toRigidMsg(const Eigen::Isometry3d& T) {
  RigidTransformMsg m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) m.matrix[4 * r + c] = T.matrix()(r, c);
  return m;
}

Eigen::Isometry3d fromRigidMsg(const RigidTransformMsg& m) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) T.matrix()(r, c) = m.matrix[4 * r + c];
  if (!T.matrix().allFinite()) throw std::invalid_argument("a rigid transform is not finite");
  if (!isRotationMatrix(T.linear()))
    throw std::invalid_argument("a rigid transform's rotation is not a rotation");
  return T;
}

sensor_msgs::Image toImageMsg(const cv::Mat& image, const std::string& encoding) {
  sensor_msgs::Image m;
  if (image.empty()) {
    m.encoding = encoding;
    return m;
  }
  cv_bridge::CvImage(std_msgs::Header(), encoding, image).toImageMsg(m);
  return m;
}

cv::Mat fromImageMsg(const sensor_msgs::Image& m, const std::string& encoding,
                     const std::string& what) {
  if (m.width == 0 || m.height == 0) return {};
  if (m.encoding != encoding)
    throw std::invalid_argument("keyframe " + what + " must be " + encoding + ", not " +
                                m.encoding);
  // cv_bridge checks the layout too, but with 32-bit sums that a huge width wraps round.
  const std::string error = imageLayoutError(m);
  if (!error.empty()) throw std::invalid_argument("keyframe " + what + ": " + error);
  return cv_bridge::toCvCopy(m, encoding)->image;
}

InstanceMsg toMsg(const PacketInstance& instance) {
  InstanceMsg m;
  m.id = instance.id;
  m.class_name = instance.class_name;
  m.score = instance.score;
  m.dynamic = instance.dynamic;
  return m;
}

PacketInstance fromMsg(const InstanceMsg& m) {
  return {m.id, m.class_name, m.score, static_cast<bool>(m.dynamic)};
}

JournalEntryMsg toMsg(const MapJournal::Entry& e) {
  JournalEntryMsg m;
  m.change = static_cast<uint8_t>(e.change);
  m.keyframe = e.keyframe;
  m.point = e.point;
  m.winner = e.winner;
  m.index = static_cast<uint32_t>(e.index);
  m.min_point_observers = e.min_point_observers;
  return m;
}

MapJournal::Entry fromMsg(const JournalEntryMsg& m) {
  if (m.change > JournalEntryMsg::ERASE_KEYFRAME)
    throw std::invalid_argument("journal entry of unknown change " + std::to_string(m.change));
  return {static_cast<MapJournal::Change>(m.change),
          m.keyframe,
          m.point,
          m.winner,
          m.index,
          m.min_point_observers};
}

std::vector<uint8_t> toBytes(const cv::Mat& rows) {
  if (rows.empty()) return {};
  const cv::Mat d = rows.isContinuous() ? rows : rows.clone();
  return std::vector<uint8_t>(d.data, d.data + d.total() * d.elemSize());
}

cv::Mat fromBytes(const std::vector<uint8_t>& bytes, size_t rows, int cols,
                  const std::string& what) {
  if (cols <= 0 || bytes.size() != rows * static_cast<size_t>(cols))
    throw std::invalid_argument(what + ": " + std::to_string(bytes.size()) + " bytes for " +
                                std::to_string(rows) + " rows of " + std::to_string(cols));
  if (rows == 0) return {};
  return cv::Mat(static_cast<int>(rows), cols, CV_8U, const_cast<uint8_t*>(bytes.data())).clone();
}

}  // namespace ply_slam
