#pragma once

// The small conversions the message files share (conversions.cpp, split_messages.cpp). Every
// number from a message is checked: one NaN in a landmark or a pose would spread through the map.
#include <geometry_msgs/Point.h>
#include <geometry_msgs/Vector3.h>
#include <ply_slam/InstanceMsg.h>
#include <ply_slam/JournalEntryMsg.h>
#include <ply_slam/RigidTransformMsg.h>
#include <sensor_msgs/Image.h>

#include <Eigen/Geometry>
#include <cstdint>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "ply_slam/map/key_frame_packet.h"
#include "ply_slam/map/map_journal.h"

namespace ply_slam {

geometry_msgs::Point toPointMsg(const Eigen::Vector3d& p);
// Throws std::invalid_argument when not finite.
Eigen::Vector3d fromPointMsg(const geometry_msgs::Point& m);
geometry_msgs::Vector3 toVector3Msg(const Eigen::Vector3d& v);
Eigen::Vector3d fromVector3Msg(const geometry_msgs::Vector3& m);

// Bit for bit. fromRigidMsg throws std::invalid_argument when a number is not finite or the
// rotation is not one (orthonormal within 1e-6, determinant +1).
RigidTransformMsg toRigidMsg(const Eigen::Isometry3d& T);
Eigen::Isometry3d fromRigidMsg(const RigidTransformMsg& m);

// An empty cv::Mat travels as a 0x0 image. fromImageMsg throws std::invalid_argument naming
// `what` for another encoding or an inconsistent layout.
sensor_msgs::Image toImageMsg(const cv::Mat& image, const std::string& encoding);
cv::Mat fromImageMsg(const sensor_msgs::Image& m, const std::string& encoding,
                     const std::string& what);

InstanceMsg toMsg(const PacketInstance& instance);
PacketInstance fromMsg(const InstanceMsg& m);

JournalEntryMsg toMsg(const MapJournal::Entry& entry);
// Throws std::invalid_argument for an unknown change.
MapJournal::Entry fromMsg(const JournalEntryMsg& msg);

// A CV_8U matrix's rows as bytes and back (`rows` x `cols`); an empty matrix is no bytes.
std::vector<uint8_t> toBytes(const cv::Mat& rows);
// Throws std::invalid_argument naming `what` when the bytes are not rows x cols.
cv::Mat fromBytes(const std::vector<uint8_t>& bytes, size_t rows, int cols,
                  const std::string& what);

// Element-wise conversions of lists (toMsg / fromMsg found by overload).
template <typename Msg, typename From>
std::vector<Msg> toMsgs(const std::vector<From>& from) {
  std::vector<Msg> to;
  to.reserve(from.size());
  for (const auto& f : from) to.push_back(toMsg(f));
  return to;
}

template <typename To, typename Msg>
std::vector<To> fromMsgs(const std::vector<Msg>& from) {
  std::vector<To> to;
  to.reserve(from.size());
  for (const auto& f : from) to.push_back(fromMsg(f));
  return to;
}

}  // namespace ply_slam
