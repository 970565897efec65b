#include "ply_slam/mapping/landmark_creator.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include "ply_slam/common/angles.h"
#include "ply_slam/map/by_id.h"

namespace ply_slam {
namespace {

// A point's state without its links to keyframes (they belong to one copy of the map).
std::shared_ptr<const MapPoint> unlinkedCopy(const MapPoint& point) {
  auto copy = std::make_shared<MapPoint>(point);
  copy->observers.clear();
  return copy;
}

void fuse(MapLine& line, const TrackerReport::LineFit& fit) {
  line.fuse(fit.start, fit.end, fit.start_weight, fit.end_weight);
}

}  // namespace

LandmarkCreator::LandmarkCreator(const PinholeCamera& camera, double max_point_depth,
                                 const LineOptions& lines, Map& map)
    : camera_(camera),
      max_point_depth_(max_point_depth),
      lines_enabled_(lines.enabled),
      line_match_angle_deg_(lines.match_angle_deg),
      map_(map) {}

void LandmarkCreator::countVisible(const std::vector<MapPoint*>& in_view) {
  for (MapPoint* p : in_view) {
    ++p->visible;
    if (report_) ++report_->points[p->id].visible;
  }
}

void LandmarkCreator::recordTracked(const Frame& frame, bool fuse_lines) {
  for (const auto& p : frame.map_points)
    if (p) {
      ++p->found;
      if (report_) ++report_->points[p->id].found;
    }
  for (const auto& l : frame.map_lines)
    if (l) {
      ++l->found;
      if (report_) ++report_->lines[l->id];
    }
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
  if (report_) report_->keyframe = kf->id;
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
      TrackerReport::PointLink link{i, p->id, nullptr};
      // Average the landmark with this keyframe's depth measurement.
      if (has_depth) {
        link.measured = T_wc * camera_.backProject(f.undistorted[i], f.depth[i]);
        link.weight = pointWeight(f.depth[i], f.scale(i));
        p->fuse(link.measured, link.weight);
      }
      if (report_) report_->point_links.push_back(std::move(link));
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
    if (report_) report_->point_links.push_back({i, point->id, unlinkedCopy(*point)});
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
      if (report_) report_->line_links.push_back({i, l->id, nullptr});
      continue;
    }
    if (!fit.valid) continue;
    l = map_.createMapLine(T_wc * fit.start, T_wc * fit.end, frame.lines.descriptor(i), kf.id);
    fuse(*l, worldFit(*l, fit, T_wc));  // its first fit: the weights
    l->observations = 1;
    kf.map_lines[i] = l;
    if (report_) report_->line_links.push_back({i, l->id, std::make_shared<const MapLine>(*l)});
    frame.line_outlier[i] = false;
  }
}

void LandmarkCreator::fuseLineFits(const Frame& frame) {
  const DepthNoiseModel& noise = camera_.depth_noise;
  const Eigen::Isometry3d T_wc = frame.T_cw.inverse();
  const double min_cos = std::cos(radians(line_match_angle_deg_));
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
    const TrackerReport::LineFit world = worldFit(l, fit, T_wc);
    fuse(l, world);
    if (report_) report_->line_fits.push_back(world);
  }
}

TrackerReport::LineFit LandmarkCreator::worldFit(const MapLine& line, const Line3D& fit,
                                                 const Eigen::Isometry3d& T_wc) const {
  const DepthNoiseModel& noise = camera_.depth_noise;
  return {line.id, T_wc * fit.start, T_wc * fit.end, 1.0 / noise.variance(fit.start.z()),
          1.0 / noise.variance(fit.end.z())};
}

namespace {

// The point of that id in this map, or the one it was merged into; null when gone.
std::shared_ptr<MapPoint> survivorOf(
    long id, const std::unordered_map<long, std::shared_ptr<MapPoint>>& points,
    const LandmarkCreator::MergedPoints& merged) {
  for (size_t hops = 0; hops <= merged.size(); ++hops) {  // a chain, never longer than the map
    if (const auto p = points.find(id); p != points.end()) return p->second;
    const auto m = merged.find(id);
    if (m == merged.end()) return nullptr;
    id = m->second;
  }
  return nullptr;
}

}  // namespace

std::shared_ptr<KeyFrame> LandmarkCreator::replay(const TrackerReport& report,
                                                  std::shared_ptr<KeyFrame> keyframe,
                                                  const MergedPoints& merged) {
  if (report.keyframe != keyframe->id)
    throw std::invalid_argument("LandmarkCreator::replay: the report is of keyframe " +
                                std::to_string(report.keyframe) + ", not " +
                                std::to_string(keyframe->id));
  const auto points = byId(map_.mapPoints());
  const auto lines = byId(map_.mapLines());
  for (const auto& [id, counts] : report.points)
    if (const auto p = survivorOf(id, points, merged)) {
      p->visible += counts.visible;
      p->found += counts.found;
    }
  for (const auto& [id, found] : report.lines)
    if (const auto l = lines.find(id); l != lines.end()) l->second->found += found;
  for (const auto& fit : report.line_fits)
    if (const auto l = lines.find(fit.id); l != lines.end()) fuse(*l->second, fit);
  map_.adoptKeyFrame(keyframe);
  replayPoints(report.point_links, points, merged, *keyframe);
  replayLines(report.line_links, lines, *keyframe);
  return keyframe;
}

void LandmarkCreator::replayPoints(const std::vector<TrackerReport::PointLink>& links,
                                   const PointsById& points, const MergedPoints& merged,
                                   KeyFrame& keyframe) {
  std::vector<std::pair<const TrackerReport::PointLink*, std::shared_ptr<MapPoint>>> moved;
  for (const auto& link : links) {
    std::shared_ptr<MapPoint> point;
    if (link.created) {
      point = std::make_shared<MapPoint>(*link.created);
      map_.adoptPoint(point);
    } else if (const auto p = points.find(link.id); p != points.end()) {
      point = p->second;
    } else {
      // Merged away meanwhile: the other copy moves this link to the survivor when it follows
      // the merge, after its own links, and only where the keyframe does not see it yet.
      if (auto survivor = survivorOf(link.id, points, merged))
        moved.emplace_back(&link, std::move(survivor));
      continue;  // else gone from this map meanwhile
    }
    map_.addObservation(keyframe, link.keypoint, point);
    if (link.weight > 0.0) point->fuse(link.measured, link.weight);
  }
  for (const auto& [link, point] : moved) {
    if (point->seenBy(&keyframe)) continue;
    map_.addObservation(keyframe, link->keypoint, point);
    if (link->weight > 0.0) point->fuse(link->measured, link->weight);
  }
}

void LandmarkCreator::replayLines(const std::vector<TrackerReport::LineLink>& links,
                                  const LinesById& lines, KeyFrame& keyframe) {
  for (const auto& link : links) {
    std::shared_ptr<MapLine> line;
    if (link.created) {
      line = std::make_shared<MapLine>(*link.created);
      map_.adoptLine(line);
    } else if (const auto l = lines.find(link.id); l != lines.end()) {
      line = l->second;
      ++line->observations;
    } else {
      continue;
    }
    keyframe.map_lines[link.line] = line;
  }
}

}  // namespace ply_slam
