#include "ply_slam/features/frame_lines.h"

#include "ply_slam/common/stopwatch.h"
#include "ply_slam/features/line_extractor.h"
#include "ply_slam/features/line_fitter.h"

namespace ply_slam {

FrameLines FrameLines::extract(const cv::Mat& gray, const cv::Mat& depth_m,
                               const PinholeCamera& camera, const LineExtractor& extractor,
                               const LineFitter& fitter, LineFitMethod method,
                               LineTimings* timings) {
  FrameLines f;
  Stopwatch watch;
  f.lines = extractor.detect(gray, camera);
  const double extraction_ms = watch.elapsedMs();
  watch.restart();
  f.descriptors = extractor.describe(gray, f.lines);
  const double description_ms = watch.elapsedMs();
  watch.restart();
  f.fit(depth_m, fitter, method);
  if (timings) {
    timings->extraction_ms = extraction_ms;
    timings->description_ms = description_ms;
    timings->fitting_ms = watch.elapsedMs();
  }
  return f;
}

void FrameLines::fit(const cv::Mat& depth_m, const LineFitter& fitter, LineFitMethod method) {
  CV_Assert(depth_m.type() == CV_32F);
  average_length = LineFitter::averageLength(lines);
  lines3d.resize(lines.size());
  for (size_t i = 0; i < lines.size(); ++i) {
    lines3d[i] = method == LineFitMethod::kSampled
                     ? fitter.fitSampled(lines[i], depth_m, average_length)
                     : fitter.fitEndpoints(lines[i], depth_m);
  }
}

size_t FrameLines::numLines3D() const {
  size_t n = 0;
  for (const Line3D& l : lines3d) n += l.valid;
  return n;
}

double FrameLines::reconstructionRate() const {
  return lines.empty() ? 0.0 : static_cast<double>(numLines3D()) / lines.size();
}

void FrameLines::correctMotion(const PinholeCamera& camera, const CameraVelocity& velocity) {
  if (camera.rolling_shutter_readout == 0.0) return;
  auto toStamp = [&](double raw_row) { return velocity.over(-camera.rowTime(raw_row)); };
  for (size_t i = 0; i < lines.size(); ++i) {
    LineFeature& l = lines[i];
    Line3D& fit = lines3d[i];
    const Eigen::Isometry3d T_start = toStamp(l.raw_start.y()), T_end = toStamp(l.raw_end.y());
    // With the 3D segment, its ends' depths; without, the rotation alone (it dominates).
    const double z_start = fit.valid ? fit.start.z() : 0.0, z_end = fit.valid ? fit.end.z() : 0.0;
    auto move = [&](const Eigen::Vector2d& uv, double z, const Eigen::Isometry3d& T) {
      return z > 0 ? camera.project(T * camera.backProject(uv, z))
                   : camera.project(T.linear() * camera.backProject(uv, 1.0));
    };
    l.start = move(l.start, z_start, T_start);
    l.end = move(l.end, z_end, T_end);
    if (fit.valid) {
      fit.start = T_start * fit.start;
      fit.end = T_end * fit.end;
    }
  }
}

size_t FrameLines::removeIf(const std::vector<bool>& drop) {
  CV_Assert(drop.size() == lines.size());
  size_t kept = 0;
  cv::Mat kept_descriptors;
  for (size_t i = 0; i < lines.size(); ++i) {
    if (drop[i]) continue;
    lines[kept] = lines[i];
    lines3d[kept] = lines3d[i];
    kept_descriptors.push_back(descriptors.row(static_cast<int>(i)));
    ++kept;
  }
  const size_t dropped = lines.size() - kept;
  lines.resize(kept);
  lines3d.resize(kept);
  descriptors = kept_descriptors;
  return dropped;
}

}  // namespace ply_slam
