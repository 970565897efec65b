#include "ply_slam/ros/conversions.h"

#include <sensor_msgs/image_encodings.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "ply_slam/common/camera_check.h"
#include "ply_slam/ros/message_parts.h"

namespace ply_slam {
namespace {

namespace enc = sensor_msgs::image_encodings;

void throwOnCameraProblem(const PinholeCamera& camera, const std::string& source) {
  if (const auto problem = findCameraProblem(camera))
    throw std::invalid_argument(source + ": " + problem->key + " " + problem->what);
}

}  // namespace

// The element conversions are not in the anonymous namespace: toMsgs / fromMsgs find them by
// argument-dependent lookup, which does not look there.
LandmarkMsg toMsg(const LandmarkPoint& p) {
  LandmarkMsg m;
  m.id = p.id;
  m.position = toPointMsg(p.position);
  m.normal = toVector3Msg(p.normal);
  m.position_weight = p.position_weight;
  return m;
}

LandmarkPoint fromMsg(const LandmarkMsg& m) {
  if (!std::isfinite(m.position_weight))
    throw std::invalid_argument("a landmark's weight is not finite");
  return {m.id, fromPointMsg(m.position), fromVector3Msg(m.normal), m.position_weight};
}

Line3DMsg toMsg(const LandmarkLine& l) {
  Line3DMsg m;
  m.id = l.id;
  m.start = toPointMsg(l.start);
  m.end = toPointMsg(l.end);
  m.start_weight = l.start_weight;
  m.end_weight = l.end_weight;
  return m;
}

LandmarkLine fromMsg(const Line3DMsg& m) {
  if (!std::isfinite(m.start_weight) || !std::isfinite(m.end_weight))
    throw std::invalid_argument("a line's weight is not finite");
  return {m.id, fromPointMsg(m.start), fromPointMsg(m.end), m.start_weight, m.end_weight};
}

CameraMsg toMsg(const PinholeCamera& c) {
  CameraMsg m;
  m.fx = c.fx;
  m.fy = c.fy;
  m.cx = c.cx;
  m.cy = c.cy;
  m.width = c.width;
  m.height = c.height;
  // An empty Mat's iterators divide by its zero columns: no distortion, no iterators.
  if (!c.distortion.empty()) {
    cv::Mat d;
    c.distortion.convertTo(d, CV_64F);
    m.distortion.assign(d.begin<double>(), d.end<double>());
  }
  m.depth_factor = c.depth_factor;
  m.min_depth = c.min_depth;
  m.max_depth = c.max_depth;
  m.depth_noise_alpha = c.depth_noise.alpha;
  m.depth_noise_beta = c.depth_noise.beta;
  m.depth_noise_gamma = c.depth_noise.gamma;
  m.depth_noise_delta = c.depth_noise.delta;
  m.rolling_shutter_readout = c.rolling_shutter_readout;
  return m;
}

bool sameCamera(const PinholeCamera& a, const PinholeCamera& b) {
  const CameraMsg x = toMsg(a), y = toMsg(b);
  auto rectified = [](const CameraMsg& m) {
    return std::all_of(m.distortion.begin(), m.distortion.end(), [](double k) { return k == 0; });
  };
  return x.fx == y.fx && x.fy == y.fy && x.cx == y.cx && x.cy == y.cy && x.width == y.width &&
         x.height == y.height && (x.distortion == y.distortion || (rectified(x) && rectified(y))) &&
         x.depth_factor == y.depth_factor && x.min_depth == y.min_depth &&
         x.max_depth == y.max_depth && x.depth_noise_alpha == y.depth_noise_alpha &&
         x.depth_noise_beta == y.depth_noise_beta && x.depth_noise_gamma == y.depth_noise_gamma &&
         x.depth_noise_delta == y.depth_noise_delta &&
         x.rolling_shutter_readout == y.rolling_shutter_readout;
}

std::string intrinsicsText(const PinholeCamera& c) {
  std::ostringstream text;
  text << "fx " << c.fx << " fy " << c.fy << " cx " << c.cx << " cy " << c.cy << ", " << c.width
       << "x" << c.height;
  return text.str();
}

PinholeCamera fromMsg(const CameraMsg& m) {
  PinholeCamera c;
  c.fx = m.fx;
  c.fy = m.fy;
  c.cx = m.cx;
  c.cy = m.cy;
  c.width = m.width;
  c.height = m.height;
  if (!m.distortion.empty())
    c.distortion = cv::Mat(m.distortion, true).reshape(1, 1);  // 1xN CV_64F
  c.depth_factor = m.depth_factor;
  c.min_depth = m.min_depth;
  c.max_depth = m.max_depth;
  c.depth_noise = {m.depth_noise_alpha, m.depth_noise_beta, m.depth_noise_gamma,
                   m.depth_noise_delta};
  c.rolling_shutter_readout = m.rolling_shutter_readout;
  throwOnCameraProblem(c, "keyframe camera");
  return c;
}

geometry_msgs::Pose toPoseMsg(const Eigen::Isometry3d& T) {
  geometry_msgs::Pose m;
  m.position = toPointMsg(T.translation());
  const Eigen::Quaterniond q(T.rotation());
  m.orientation.x = q.x();
  m.orientation.y = q.y();
  m.orientation.z = q.z();
  m.orientation.w = q.w();
  return m;
}

Eigen::Isometry3d fromPoseMsg(const geometry_msgs::Pose& m) {
  Eigen::Quaterniond q(m.orientation.w, m.orientation.x, m.orientation.y, m.orientation.z);
  const double n = q.norm();
  if (!std::isfinite(n) || n < 1e-6) throw std::invalid_argument("pose has no valid quaternion");
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  T.translation() = fromPointMsg(m.position);
  return T;
}

geometry_msgs::TransformStamped toTransformMsg(const Eigen::Isometry3d& T, const ros::Time& stamp,
                                               const std::string& parent,
                                               const std::string& child) {
  const geometry_msgs::Pose pose = toPoseMsg(T);
  geometry_msgs::TransformStamped t;
  t.header.stamp = stamp;
  t.header.frame_id = parent;
  t.child_frame_id = child;
  t.transform.translation.x = pose.position.x;
  t.transform.translation.y = pose.position.y;
  t.transform.translation.z = pose.position.z;
  t.transform.rotation = pose.orientation;
  return t;
}

Eigen::Isometry3d fromTransformMsg(const geometry_msgs::Transform& t) {
  geometry_msgs::Pose pose;
  pose.position.x = t.translation.x;
  pose.position.y = t.translation.y;
  pose.position.z = t.translation.z;
  pose.orientation = t.rotation;
  return fromPoseMsg(pose);
}

PinholeCamera cameraFromInfo(const sensor_msgs::CameraInfo& info, PinholeCamera camera) {
  camera.fx = info.K[0];
  camera.fy = info.K[4];
  camera.cx = info.K[2];
  camera.cy = info.K[5];
  camera.width = static_cast<int>(info.width);
  camera.height = static_cast<int>(info.height);
  cv::Mat d = cv::Mat::zeros(1, 5, CV_64F);
  for (size_t i = 0; i < std::min<size_t>(5, info.D.size()); ++i) d.at<double>(0, i) = info.D[i];
  camera.distortion = d;
  throwOnCameraProblem(camera, "camera_info");
  return camera;
}

KeyFramePoseMsg toMsg(const MapUpdate::KeyFramePose& k) {
  KeyFramePoseMsg m;
  m.id = k.id;
  m.T_cw = toRigidMsg(k.T_cw);
  m.parent = k.parent;
  return m;
}

MapUpdate::KeyFramePose fromMsg(const KeyFramePoseMsg& m) {
  return {m.id, fromRigidMsg(m.T_cw), m.parent};
}

KeyFrameMsg toMsg(const KeyFramePacket& p, const std::string& world_frame) {
  KeyFrameMsg m;
  m.header.frame_id = world_frame;
  m.header.stamp.fromSec(p.stamp);
  m.id = p.id;
  m.frame_id = p.frame_id;
  m.stamp = p.stamp;
  m.T_wc = toPoseMsg(p.T_wc);
  m.camera = toMsg(p.camera);
  m.keypoints.resize(p.keypoints.size());
  for (size_t i = 0; i < p.keypoints.size(); ++i) {
    auto& k = m.keypoints[i];
    k.u = p.keypoints[i].x();
    k.v = p.keypoints[i].y();
    k.depth = i < p.keypoint_depth.size() ? p.keypoint_depth[i] : 0.f;
    k.level = i < p.keypoint_level.size() ? p.keypoint_level[i] : 0;
    k.landmark = i < p.keypoint_landmark.size() ? p.keypoint_landmark[i] : -1;
  }
  m.descriptor_bytes = p.descriptors.cols;
  m.descriptors = toBytes(p.descriptors);
  m.points = toMsgs<LandmarkMsg>(p.points);
  m.lines = toMsgs<Line3DMsg>(p.lines);
  m.rgb = toImageMsg(p.rgb, enc::BGR8);
  m.depth = toImageMsg(p.depth, enc::TYPE_32FC1);
  m.label_image = toImageMsg(p.label_image, enc::TYPE_16UC1);
  m.dynamic_mask = toImageMsg(p.dynamic_mask, enc::MONO8);
  m.instances = toMsgs<InstanceMsg>(p.instances);
  return m;
}

KeyFramePacket fromMsg(const KeyFrameMsg& m) {
  KeyFramePacket p;
  p.id = m.id;
  p.frame_id = m.frame_id;
  p.stamp = m.stamp;
  if (!std::isfinite(p.stamp)) throw std::invalid_argument("keyframe stamp is not finite");
  p.T_wc = fromPoseMsg(m.T_wc);
  p.camera = fromMsg(m.camera);
  const size_t n = m.keypoints.size();
  if (n > 0 && (m.descriptor_bytes <= 0 || m.descriptors.size() != n * m.descriptor_bytes))
    throw std::invalid_argument("keyframe has " + std::to_string(n) + " keypoints but " +
                                std::to_string(m.descriptors.size()) + " descriptor bytes of " +
                                std::to_string(m.descriptor_bytes) + " per row");
  for (const auto& k : m.keypoints) {
    p.keypoints.emplace_back(k.u, k.v);
    p.keypoint_depth.push_back(k.depth);
    p.keypoint_level.push_back(k.level);
    p.keypoint_landmark.push_back(k.landmark);
  }
  if (n > 0)
    p.descriptors = cv::Mat(static_cast<int>(n), m.descriptor_bytes, CV_8U,
                            const_cast<uint8_t*>(m.descriptors.data()))
                        .clone();
  p.points = fromMsgs<LandmarkPoint>(m.points);
  p.lines = fromMsgs<LandmarkLine>(m.lines);
  p.rgb = fromImageMsg(m.rgb, enc::BGR8, "rgb");
  p.depth = fromImageMsg(m.depth, enc::TYPE_32FC1, "depth");
  p.label_image = fromImageMsg(m.label_image, enc::TYPE_16UC1, "label_image");
  p.dynamic_mask = fromImageMsg(m.dynamic_mask, enc::MONO8, "dynamic_mask");
  p.instances = fromMsgs<PacketInstance>(m.instances);
  return p;
}

MapUpdateMsg toMsg(const MapUpdate& u, const std::string& world_frame) {
  MapUpdateMsg m;
  m.header.frame_id = world_frame;
  m.header.stamp.fromSec(u.stamp);
  m.stamp = u.stamp;
  m.keyframes = toMsgs<KeyFramePoseMsg>(u.keyframes);
  m.points = toMsgs<LandmarkMsg>(u.points);
  m.lines = toMsgs<Line3DMsg>(u.lines);
  m.erased_keyframes.assign(u.erased_keyframes.begin(), u.erased_keyframes.end());
  m.erased_points.assign(u.erased_points.begin(), u.erased_points.end());
  m.erased_lines.assign(u.erased_lines.begin(), u.erased_lines.end());
  m.whole_map = u.whole_map;
  m.replayed_keyframe = u.replayed.keyframe;
  for (const auto& [keypoint, point] : u.replayed.points) {
    m.replayed_keypoints.push_back(static_cast<uint32_t>(keypoint));
    m.replayed_points.push_back(point);
  }
  m.journal = toMsgs<JournalEntryMsg>(u.journal.entries);
  for (const auto& correction : u.world_corrections)
    m.world_corrections.push_back(toRigidMsg(correction));
  return m;
}

MapUpdate fromMsg(const MapUpdateMsg& m) {
  MapUpdate u;
  u.stamp = m.stamp;
  u.keyframes = fromMsgs<MapUpdate::KeyFramePose>(m.keyframes);
  u.points = fromMsgs<LandmarkPoint>(m.points);
  u.lines = fromMsgs<LandmarkLine>(m.lines);
  u.erased_keyframes.assign(m.erased_keyframes.begin(), m.erased_keyframes.end());
  u.erased_points.assign(m.erased_points.begin(), m.erased_points.end());
  u.erased_lines.assign(m.erased_lines.begin(), m.erased_lines.end());
  u.whole_map = m.whole_map;
  if (m.replayed_keypoints.size() != m.replayed_points.size())
    throw std::invalid_argument("map update has " + std::to_string(m.replayed_keypoints.size()) +
                                " replayed keypoints but " +
                                std::to_string(m.replayed_points.size()) + " replayed points");
  u.replayed.keyframe = m.replayed_keyframe;
  for (size_t i = 0; i < m.replayed_points.size(); ++i)
    u.replayed.points.emplace_back(m.replayed_keypoints[i], m.replayed_points[i]);
  u.journal.entries = fromMsgs<MapJournal::Entry>(m.journal);
  for (const auto& correction : m.world_corrections)
    u.world_corrections.push_back(fromRigidMsg(correction));
  return u;
}

void checkHandoverCounts(int64_t updates_followed, const Map::Ids& next_ids) {
  for (const auto& [name, value] : {std::make_pair("updates_followed", updates_followed),
                                    std::make_pair("next_keyframe_id", next_ids.keyframe),
                                    std::make_pair("next_point_id", next_ids.point),
                                    std::make_pair("next_line_id", next_ids.line)})
    if (value < 0)
      throw std::invalid_argument(std::string("map handover: ") + name + " " +
                                  std::to_string(value) + " < 0");
}

MapSnapshotMsg toMsg(const MapSnapshot& s, const std::string& world_frame) {
  MapSnapshotMsg m;
  m.header.frame_id = world_frame;
  for (const auto& k : s.keyframes) m.keyframes.push_back(toMsg(k, world_frame));
  for (const StampedPose& pose : s.trajectory) {
    geometry_msgs::PoseStamped p;
    p.header.stamp.fromSec(pose.stamp);
    p.header.frame_id = world_frame;
    p.pose = toPoseMsg(pose.T_wc);
    m.trajectory.push_back(p);
  }
  handoverToFields(s.handover, m);
  return m;
}

MapSnapshot fromMsg(const MapSnapshotMsg& m) {
  MapSnapshot s;
  for (const auto& k : m.keyframes) s.keyframes.push_back(fromMsg(k));
  for (const auto& p : m.trajectory)
    s.trajectory.push_back({p.header.stamp.toSec(), fromPoseMsg(p.pose)});
  s.handover = handoverFromFields(m);
  return s;
}

}  // namespace ply_slam
