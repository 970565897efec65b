#include "ply_slam/mapping/landmark_creator.h"

#include <cmath>

namespace ply_slam {

LandmarkCreator::LandmarkCreator(const PinholeCamera& camera, double max_point_depth,
                                 const LineOptions& lines, Map& map)
    : camera_(camera),
      max_point_depth_(max_point_depth),
      lines_enabled_(lines.enabled),
      line_match_angle_deg_(lines.match_angle_deg),
      map_(map) {}

void LandmarkCreator::countVisible(const std::vector<MapPoint*>& in_view) {
  for (MapPoint* p : in_view) ++p->visible;
}

void LandmarkCreator::recordTracked(const Frame& frame, bool fuse_lines) {
  for (const auto& p : frame.map_points)
    if (p) ++p->found;
  for (const auto& l : frame.map_lines)
    if (l) ++l->found;
  if (fuse_lines) fuseLineFits(frame);
}

std::shared_ptr<KeyFrame> LandmarkCreator::addKeyFrame(Frame& frame) {
  auto kf = std::make_shared<KeyFrame>();
  kf->frame_id = frame.id;
  kf->stamp = frame.stamp;
  kf->T_cw = frame.T_cw;
  kf->features = frame.features;
  kf->features.depth_image.release();  // the image stays with the frame only while it is tracked
  kf->map_points.resize(frame.features.size());
  map_.addKeyFrame(kf);
  addPoints(frame, *kf);
  if (lines_enabled_) addLines(frame, *kf);
  return kf;
}

double LandmarkCreator::pointWeight(double z, double scale) const {
  const double lateral = z * scale / camera_.fx;
  return 1.0 / (camera_.depth_noise.variance(z) + lateral * lateral);
}

void LandmarkCreator::addPoints(Frame& frame, KeyFrame& kf) {
  const auto& f = frame.features;
  if (f.size() == 0) return;
  const Eigen::Isometry3d T_wc = frame.T_cw.inverse();
  const Eigen::Vector3d centre = T_wc.translation();
  const double last_scale = f.scales->back();
  for (size_t i = 0; i < f.size(); ++i) {
    auto& p = frame.map_points[i];
    const bool has_depth = f.hasDepth(i) && f.depth[i] <= max_point_depth_;
    if (p && !frame.outlier[i]) {
      map_.addObservation(kf, i, p);
      // Average the landmark with this keyframe's depth measurement.
      if (has_depth)
        p->fuse(T_wc * camera_.backProject(f.undistorted[i], f.depth[i]),
                pointWeight(f.depth[i], f.scale(i)));
      continue;
    }
    if (!has_depth) continue;
    const double z = f.depth[i];
    const Eigen::Vector3d world = T_wc * camera_.backProject(f.undistorted[i], z);
    auto point = map_.createMapPoint(world, f.descriptors.row(static_cast<int>(i)), kf.id);
    const Eigen::Vector3d ray = world - centre;
    point->normal = ray.normalized();
    point->max_distance = ray.norm() * f.scale(i);
    point->min_distance = point->max_distance / last_scale;
    point->position_weight = pointWeight(z, f.scale(i));
    map_.addObservation(kf, i, point);
    p = point;
    frame.outlier[i] = false;
  }
}

void LandmarkCreator::addLines(Frame& frame, KeyFrame& kf) {
  // The matched lines gain an observation, the accepted 3D fits of the rest become new ones
  // (world frame by the keyframe's pose).
  const Eigen::Isometry3d T_wc = frame.T_cw.inverse();
  kf.map_lines.resize(frame.lines.size());
  for (size_t i = 0; i < frame.lines.size(); ++i) {
    auto& l = frame.map_lines[i];
    const Line3D& fit = frame.lines.lines3d[i];
    if (l && !frame.line_outlier[i]) {
      ++l->observations;
      kf.map_lines[i] = l;
      continue;
    }
    if (!fit.valid) continue;
    l = map_.createMapLine(T_wc * fit.start, T_wc * fit.end, frame.lines.descriptor(i), kf.id);
    fuseFit(*l, fit, T_wc);  // its first fit: the weights
    l->observations = 1;
    kf.map_lines[i] = l;
    frame.line_outlier[i] = false;
  }
}

void LandmarkCreator::fuseLineFits(const Frame& frame) const {
  const DepthNoiseModel& noise = camera_.depth_noise;
  const Eigen::Isometry3d T_wc = frame.T_cw.inverse();
  const double min_cos = std::cos(line_match_angle_deg_ * M_PI / 180.0);
  for (size_t i = 0; i < frame.map_lines.size(); ++i) {
    const Line3D& fit = frame.lines.lines3d[i];
    if (!frame.map_lines[i] || !fit.valid) continue;
    MapLine& l = *frame.map_lines[i];
    const Eigen::Vector3d s = T_wc * fit.start, e = T_wc * fit.end;
    // Only a fit of the same 3D line: a match to a parallel edge a few pixels away (the other
    // side of a desk leg) passes the 2D tests but lies centimetres off, and a short fit across
    // the line can have both ends near it.
    if (l.distanceToLine(s) > noise.surfaceGap(fit.start.z()) ||
        l.distanceToLine(e) > noise.surfaceGap(fit.end.z()) ||
        std::abs((e - s).normalized().dot((l.end - l.start).normalized())) < min_cos)
      continue;
    fuseFit(l, fit, T_wc);
  }
}

void LandmarkCreator::fuseFit(MapLine& line, const Line3D& fit,
                              const Eigen::Isometry3d& T_wc) const {
  const DepthNoiseModel& noise = camera_.depth_noise;
  line.fuse(T_wc * fit.start, T_wc * fit.end, 1.0 / noise.variance(fit.start.z()),
            1.0 / noise.variance(fit.end.z()));
}

}  // namespace ply_slam
