#include "ply_slam/ros/split_messages.h"

#include <sensor_msgs/image_encodings.h>

#include <cmath>
#include <stdexcept>

#include "ply_slam/ros/message_parts.h"

namespace ply_slam {
namespace {

namespace enc = sensor_msgs::image_encodings;

constexpr int kDescriptorBytes = 32;  // ORB and LBD

double finite(double x, const char* what) {
  if (!std::isfinite(x)) throw std::invalid_argument(std::string(what) + " is not finite");
  return x;
}

// A landmark's descriptor: 32 bytes, or none.
cv::Mat descriptorOf(const std::vector<uint8_t>& bytes, const char* what) {
  if (bytes.empty()) return {};
  return fromBytes(bytes, 1, kDescriptorBytes, what);
}

MapPointMsg toMsg(const MapPoint& p) {
  MapPointMsg m;
  m.id = p.id;
  m.position = toPointMsg(p.position);
  m.normal = toVector3Msg(p.normal);
  m.min_distance = p.min_distance;
  m.max_distance = p.max_distance;
  m.position_weight = p.position_weight;
  m.descriptor = toBytes(p.descriptor);
  m.visible = p.visible;
  m.found = p.found;
  m.first_keyframe = p.first_keyframe_id;
  return m;
}

std::shared_ptr<const MapPoint> fromMsg(const MapPointMsg& m) {
  auto p = std::make_shared<MapPoint>();
  p->id = m.id;
  p->position = fromPointMsg(m.position);
  p->normal = fromVector3Msg(m.normal);
  p->min_distance = finite(m.min_distance, "a point's min distance");
  p->max_distance = finite(m.max_distance, "a point's max distance");
  p->position_weight = finite(m.position_weight, "a point's weight");
  p->descriptor = descriptorOf(m.descriptor, "a point's descriptor");
  p->visible = m.visible;
  p->found = m.found;
  p->first_keyframe_id = m.first_keyframe;
  return p;
}

MapLineMsg toMsg(const MapLine& l) {
  MapLineMsg m;
  m.id = l.id;
  m.start = toPointMsg(l.start);
  m.end = toPointMsg(l.end);
  m.start_weight = l.start_weight;
  m.end_weight = l.end_weight;
  m.descriptor = toBytes(l.descriptor);
  m.first_keyframe = l.first_keyframe_id;
  m.observations = l.observations;
  m.found = l.found;
  return m;
}

std::shared_ptr<const MapLine> fromMsg(const MapLineMsg& m) {
  auto l = std::make_shared<MapLine>();
  l->id = m.id;
  l->start = fromPointMsg(m.start);
  l->end = fromPointMsg(m.end);
  l->start_weight = finite(m.start_weight, "a line's start weight");
  l->end_weight = finite(m.end_weight, "a line's end weight");
  l->descriptor = descriptorOf(m.descriptor, "a line's descriptor");
  l->first_keyframe_id = m.first_keyframe;
  l->observations = m.observations;
  l->found = m.found;
  return l;
}

// Zero or one created landmark, named as its link names it.
template <typename Landmark, typename Msg>
std::shared_ptr<const Landmark> createdOf(const std::vector<Msg>& created, long id) {
  if (created.empty()) return nullptr;
  if (created.size() > 1 || created[0].id != id)
    throw std::invalid_argument("report link to landmark " + std::to_string(id) +
                                " carries another landmark as made");
  return fromMsg(created[0]);
}

FeatureMsg featureMsg(const FrameFeatures& f, size_t i) {
  FeatureMsg m;
  const cv::KeyPoint& k = f.keypoints[i];
  m.x = k.pt.x;
  m.y = k.pt.y;
  m.size = k.size;
  m.angle = k.angle;
  m.response = k.response;
  m.octave = k.octave;
  m.rectified_u = f.rectified[i].x();
  m.rectified_v = f.rectified[i].y();
  m.u = f.undistorted[i].x();
  m.v = f.undistorted[i].y();
  m.depth = f.depth[i];
  return m;
}

void addFeature(const FeatureMsg& m, size_t levels, FrameFeatures& f) {
  if (m.octave < 0 || static_cast<size_t>(m.octave) >= levels)
    throw std::invalid_argument("a feature's level " + std::to_string(m.octave) +
                                " is outside the pyramid's " + std::to_string(levels));
  f.keypoints.emplace_back(cv::Point2f(m.x, m.y), m.size, m.angle, m.response, m.octave);
  f.rectified.emplace_back(finite(m.rectified_u, "a feature"), finite(m.rectified_v, "a feature"));
  f.undistorted.emplace_back(finite(m.u, "a feature"), finite(m.v, "a feature"));
  f.depth.push_back(static_cast<float>(finite(m.depth, "a feature's depth")));
}

// An image of the job must be of the receiver's camera (or empty, where the job may leave it out).
void checkSize(const cv::Size& size, const cv::Size& camera, const std::string& what) {
  if (size != camera)
    throw std::invalid_argument("the job's " + what + " is " + std::to_string(size.width) + "x" +
                                std::to_string(size.height) + ", the camera here " +
                                std::to_string(camera.width) + "x" + std::to_string(camera.height));
}

cv::Mat imageOf(const sensor_msgs::Image& m, const std::string& encoding, const std::string& what,
                const cv::Size& camera) {
  cv::Mat image = fromImageMsg(m, encoding, what);
  if (!image.empty()) checkSize(image.size(), camera, what);
  return image;
}

FrameFeatures featuresOf(const MappingJobMsg& m, const JobReceiver& receiver) {
  checkSize({m.image_width, m.image_height}, receiver.image_size, "features' image");
  const std::vector<double>* scales = receiver.scales;
  FrameFeatures f;
  f.scales = scales;
  f.width = m.image_width;
  f.height = m.image_height;
  f.depth_dt = finite(m.depth_dt, "the depth's delay");
  for (const FeatureMsg& feature : m.features) addFeature(feature, scales->size(), f);
  f.descriptors = fromBytes(m.descriptors, m.features.size(), kDescriptorBytes, "descriptors");
  f.buildGrid();
  return f;
}

std::shared_ptr<KeyFrame> keyFrameOf(const MappingJobMsg& m, const JobReceiver& receiver) {
  auto kf = std::make_shared<KeyFrame>();
  kf->id = m.id;
  kf->frame_id = m.frame_id;
  kf->stamp = finite(m.stamp, "the keyframe's stamp");
  kf->T_cw = fromRigidMsg(m.T_cw);
  kf->features = featuresOf(m, receiver);
  kf->map_points.assign(kf->features.size(), nullptr);
  kf->map_lines.assign(m.line_slots, nullptr);
  return kf;
}

// The report's links must name keypoints and lines the keyframe has.
void checkLinks(const TrackerReport& report, const KeyFrame& kf) {
  if (report.keyframe != kf.id)
    throw std::invalid_argument("the report is of keyframe " + std::to_string(report.keyframe) +
                                ", the job's is " + std::to_string(kf.id));
  for (const auto& link : report.point_links)
    if (link.keypoint >= kf.map_points.size())
      throw std::invalid_argument("a report link names keypoint " + std::to_string(link.keypoint) +
                                  " of " + std::to_string(kf.map_points.size()));
  for (const auto& link : report.line_links)
    if (link.line >= kf.map_lines.size())
      throw std::invalid_argument("a report link names line " + std::to_string(link.line) + " of " +
                                  std::to_string(kf.map_lines.size()));
}

}  // namespace

TrackerReportMsg toMsg(const TrackerReport& r) {
  TrackerReportMsg m;
  for (const auto& [id, counts] : r.points) {
    LandmarkCountsMsg c;
    c.id = id;
    c.visible = counts.visible;
    c.found = counts.found;
    m.points.push_back(c);
  }
  for (const auto& [id, found] : r.lines) {
    LandmarkCountsMsg c;
    c.id = id;
    c.found = found;
    m.lines.push_back(c);
  }
  for (const auto& fit : r.line_fits) {
    LineFitMsg f;
    f.id = fit.id;
    f.start = toPointMsg(fit.start);
    f.end = toPointMsg(fit.end);
    f.start_weight = fit.start_weight;
    f.end_weight = fit.end_weight;
    m.line_fits.push_back(f);
  }
  m.keyframe = r.keyframe;
  for (const auto& link : r.point_links) {
    PointLinkMsg l;
    l.keypoint = static_cast<uint32_t>(link.keypoint);
    l.id = link.id;
    if (link.created) l.created.push_back(toMsg(*link.created));
    l.measured = toPointMsg(link.measured);
    l.weight = link.weight;
    m.point_links.push_back(l);
  }
  for (const auto& link : r.line_links) {
    LineLinkMsg l;
    l.line = static_cast<uint32_t>(link.line);
    l.id = link.id;
    if (link.created) l.created.push_back(toMsg(*link.created));
    m.line_links.push_back(l);
  }
  return m;
}

TrackerReport fromMsg(const TrackerReportMsg& m) {
  TrackerReport r;
  for (const auto& c : m.points) r.points[c.id] = {c.visible, c.found};
  for (const auto& c : m.lines) r.lines[c.id] = c.found;
  for (const auto& f : m.line_fits)
    r.line_fits.push_back({f.id, fromPointMsg(f.start), fromPointMsg(f.end),
                           finite(f.start_weight, "a line fit's weight"),
                           finite(f.end_weight, "a line fit's weight")});
  r.keyframe = m.keyframe;
  for (const auto& l : m.point_links)
    r.point_links.push_back({l.keypoint, l.id, createdOf<MapPoint>(l.created, l.id),
                             fromPointMsg(l.measured), finite(l.weight, "a link's weight")});
  for (const auto& l : m.line_links)
    r.line_links.push_back({l.line, l.id, createdOf<MapLine>(l.created, l.id)});
  return r;
}

MappingJobMsg toMsg(const MappingJob& job, const std::string& world_frame) {
  const KeyFrame& kf = *job.keyframe;
  MappingJobMsg m;
  m.header.frame_id = world_frame;
  m.header.stamp.fromSec(kf.stamp);
  m.id = kf.id;
  m.frame_id = kf.frame_id;
  m.stamp = kf.stamp;
  m.T_cw = toRigidMsg(kf.T_cw);
  const FrameFeatures& f = kf.features;
  for (size_t i = 0; i < f.size(); ++i) m.features.push_back(featureMsg(f, i));
  m.descriptors = toBytes(f.descriptors);
  m.image_width = f.width;
  m.image_height = f.height;
  m.depth_dt = f.depth_dt;
  m.line_slots = static_cast<uint32_t>(kf.map_lines.size());
  m.report = toMsg(job.report);
  m.followed_updates = static_cast<uint64_t>(job.followed_updates);
  m.made_after = job.made_after;
  m.made_after_T_cw = toRigidMsg(job.made_after_T_cw);
  m.reference_keyframe = job.reference_keyframe;
  m.loaded_map = job.loaded_map;
  m.depth_stamp = job.images.depth_stamp;
  m.rgb = toImageMsg(job.images.rgb, enc::BGR8);
  m.depth = toImageMsg(job.images.depth, enc::TYPE_32FC1);
  m.label_image = toImageMsg(job.segmentation.label_image, enc::TYPE_16UC1);
  m.instances = toMsgs<InstanceMsg>(job.segmentation.instances);
  m.dynamic_mask = toImageMsg(job.segmentation.dynamic_mask, enc::MONO8);
  return m;
}

MappingJob fromMsg(const MappingJobMsg& m, const JobReceiver& receiver) {
  MappingJob job;
  job.keyframe = keyFrameOf(m, receiver);
  job.report = fromMsg(m.report);
  checkLinks(job.report, *job.keyframe);
  job.followed_updates = static_cast<long>(m.followed_updates);
  if (m.made_after < -1 || m.made_after >= m.id)
    throw std::invalid_argument("the job says keyframe " + std::to_string(m.id) +
                                " was made after keyframe " + std::to_string(m.made_after));
  job.made_after = m.made_after;
  job.made_after_T_cw = fromRigidMsg(m.made_after_T_cw);
  job.reference_keyframe = m.reference_keyframe;
  job.loaded_map = m.loaded_map;
  job.images.stamp = job.keyframe->stamp;
  job.images.depth_stamp = finite(m.depth_stamp, "the depth stamp");
  const cv::Size& camera = receiver.image_size;
  job.images.rgb = imageOf(m.rgb, enc::BGR8, "rgb", camera);
  job.images.depth = imageOf(m.depth, enc::TYPE_32FC1, "depth", camera);
  job.segmentation.label_image = imageOf(m.label_image, enc::TYPE_16UC1, "label_image", camera);
  job.segmentation.instances = fromMsgs<PacketInstance>(m.instances);
  job.segmentation.dynamic_mask = imageOf(m.dynamic_mask, enc::MONO8, "dynamic_mask", camera);
  return job;
}

}  // namespace ply_slam
