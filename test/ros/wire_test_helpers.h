#pragma once

// Shared by the message tests: a message through ROS serialisation as on the wire, and checks.
#include <gtest/gtest.h>
#include <ros/serialization.h>

#include <cstdint>
#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>
#include <vector>

namespace ply_slam {
namespace test {

template <typename M>
M throughWire(const M& msg, size_t* bytes = nullptr) {
  namespace ser = ros::serialization;
  std::vector<uint8_t> buffer(ser::serializationLength(msg));
  if (bytes) *bytes += buffer.size();
  ser::OStream out(buffer.data(), buffer.size());
  ser::serialize(out, msg);
  M back;
  ser::IStream in(buffer.data(), buffer.size());
  ser::deserialize(in, back);
  return back;
}

// EXPECT that `convert` throws std::invalid_argument whose message names `field`.
template <typename Convert>
void expectRejectedNaming(Convert convert, const std::string& field) {
  try {
    convert();
    ADD_FAILURE() << "accepted a bad " << field;
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find(field), std::string::npos) << e.what();
  }
}

inline bool sameImage(const cv::Mat& a, const cv::Mat& b) {
  return a.type() == b.type() && a.size() == b.size() &&
         (a.empty() || cv::norm(a, b, cv::NORM_INF) == 0);
}

}  // namespace test
}  // namespace ply_slam
