#include "ply_slam/map/map_file_writer.h"

#include <set>

#include "ply_slam/io/atomic_file.h"
#include "ply_slam/io/byte_writer.h"
#include "ply_slam/io/fnv1a.h"
#include "ply_slam/map/map_file_format.h"

namespace ply_slam {
namespace {

using map_file::kDescriptorBytes;

void putDescriptor(ByteWriter& out, const cv::Mat& descriptors, int row) {
  CV_Assert(descriptors.type() == CV_8UC1 && descriptors.cols == kDescriptorBytes);
  out.raw(descriptors.ptr(row), kDescriptorBytes);
}

void putVector(ByteWriter& out, const Eigen::Vector3d& v) {
  for (int i = 0; i < 3; ++i) out.f64(v[i]);
}

void putVocabulary(ByteWriter& out, const MapVocabulary& vocabulary) {
  out.text(vocabulary.name);
  out.u64(vocabulary.checksum);
  out.u64(vocabulary.words);
}

void putSetup(ByteWriter& out, const MapFileSetup& setup) {
  for (double v : {setup.camera.fx, setup.camera.fy, setup.camera.cx, setup.camera.cy}) out.f64(v);
  out.u32(static_cast<uint32_t>(setup.camera.width));
  out.u32(static_cast<uint32_t>(setup.camera.height));
  out.u32(static_cast<uint32_t>(setup.orb_levels));
  out.f64(setup.orb_scale_factor);
  putVocabulary(out, setup.orb_vocabulary);
  putVocabulary(out, setup.lbd_vocabulary);
}

void putKeypoints(ByteWriter& out, const FrameFeatures& f) {
  out.u32(static_cast<uint32_t>(f.size()));
  for (size_t i = 0; i < f.size(); ++i) {
    const cv::KeyPoint& k = f.keypoints[i];
    for (float v : {k.pt.x, k.pt.y, k.size, k.angle, k.response}) out.f32(v);
    out.i32(k.octave);
    for (double v :
         {f.rectified[i].x(), f.rectified[i].y(), f.undistorted[i].x(), f.undistorted[i].y()})
      out.f64(v);
    out.f32(f.depth[i]);
  }
  for (size_t i = 0; i < f.size(); ++i) putDescriptor(out, f.descriptors, static_cast<int>(i));
}

// What the file holds: links to anything else (an erased keyframe, a bad landmark) are left out,
// so that every id in the file resolves when it is read.
struct Written {
  std::set<long> keyframes, lines;
};

void putKeyFrame(ByteWriter& out, const KeyFrame& kf, const Written& written) {
  out.i64(kf.id);
  out.i64(kf.frame_id);
  out.f64(kf.stamp);
  const Eigen::Matrix<double, 3, 4> T = kf.T_cw.matrix().topRows<3>();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) out.f64(T(r, c));
  out.i64(kf.parent && written.keyframes.count(kf.parent->id) ? kf.parent->id : -1);
  putKeypoints(out, kf.features);
  out.u32(static_cast<uint32_t>(kf.map_lines.size()));
  std::vector<std::pair<uint32_t, long>> lines;
  for (size_t i = 0; i < kf.map_lines.size(); ++i)
    if (kf.map_lines[i] && written.lines.count(kf.map_lines[i]->id))
      lines.emplace_back(static_cast<uint32_t>(i), kf.map_lines[i]->id);
  out.u32(static_cast<uint32_t>(lines.size()));
  for (const auto& [slot, id] : lines) {
    out.u32(slot);
    out.i64(id);
  }
  // By id: the file must not depend on where the keyframes lie in memory.
  std::map<long, int> covisible;
  for (const auto& [other, shared] : kf.covisibility)
    if (written.keyframes.count(other->id)) covisible[other->id] = shared;
  out.u32(static_cast<uint32_t>(covisible.size()));
  for (const auto& [id, shared] : covisible) {
    out.i64(id);
    out.i32(shared);
  }
}

void putPoint(ByteWriter& out, const MapPoint& p, const Written& written) {
  out.i64(p.id);
  putVector(out, p.position);
  putVector(out, p.normal);
  for (double v : {p.min_distance, p.max_distance, p.position_weight}) out.f64(v);
  putDescriptor(out, p.descriptor, 0);
  out.i32(p.visible);
  out.i32(p.found);
  out.i64(p.first_keyframe_id);
  std::vector<MapPoint::Observer> observers;
  for (const auto& o : p.observers)
    if (written.keyframes.count(o.keyframe->id) && o.index < o.keyframe->map_points.size() &&
        o.keyframe->map_points[o.index].get() == &p)  // the keypoint's landmark: one per slot
      observers.push_back(o);
  out.u32(static_cast<uint32_t>(observers.size()));
  for (const auto& o : observers) {
    out.i64(o.keyframe->id);
    out.u32(static_cast<uint32_t>(o.index));
  }
}

void putLine(ByteWriter& out, const MapLine& l) {
  out.i64(l.id);
  putVector(out, l.start);
  putVector(out, l.end);
  out.f64(l.start_weight);
  out.f64(l.end_weight);
  putDescriptor(out, l.descriptor, 0);
  out.i64(l.first_keyframe_id);
  out.i32(l.observations);
  out.i32(l.found);
}

void putPlace(ByteWriter& out, long id, const KeyFramePlace& place) {
  out.i64(id);
  out.u32(static_cast<uint32_t>(place.used_keypoints.size()));
  out.raw(place.used_keypoints.data(), place.used_keypoints.size());
  out.u32(static_cast<uint32_t>(place.lbd_descriptors.rows));
  for (int r = 0; r < place.lbd_descriptors.rows; ++r) putDescriptor(out, place.lbd_descriptors, r);
  out.u32(static_cast<uint32_t>(place.instances.size()));
  for (const InstanceBox& b : place.instances) {
    out.text(b.class_name);
    for (double v : {b.box.x, b.box.y, b.box.width, b.box.height}) out.f64(v);
  }
}

std::vector<uint8_t> payload(const MapFileSetup& setup, const Map& map,
                             const std::map<long, KeyFramePlace>& places) {
  ByteWriter out;
  putSetup(out, setup);
  const auto keyframes = map.keyFrames();
  Written written;
  for (const auto& kf : keyframes) written.keyframes.insert(kf->id);
  std::vector<std::shared_ptr<MapLine>> lines;
  for (const auto& l : map.mapLines())
    if (!l->bad && written.lines.insert(l->id).second) lines.push_back(l);
  out.u32(static_cast<uint32_t>(keyframes.size()));
  for (const auto& kf : keyframes) putKeyFrame(out, *kf, written);
  std::vector<std::shared_ptr<MapPoint>> points;
  for (const auto& p : map.mapPoints())
    if (!p->bad) points.push_back(p);
  out.u32(static_cast<uint32_t>(points.size()));
  for (const auto& p : points) putPoint(out, *p, written);
  out.u32(static_cast<uint32_t>(lines.size()));
  for (const auto& l : lines) putLine(out, *l);
  std::vector<long> placed;
  for (const auto& [id, place] : places)
    if (written.keyframes.count(id)) placed.push_back(id);
  out.u32(static_cast<uint32_t>(placed.size()));
  for (long id : placed) putPlace(out, id, places.at(id));
  return std::move(out.bytes());
}

}  // namespace

std::vector<uint8_t> MapFileWriter::encode(const MapFileSetup& setup, const Map& map,
                                           const std::map<long, KeyFramePlace>& places) {
  const std::vector<uint8_t> body = payload(setup, map, places);
  ByteWriter out;
  out.raw(reinterpret_cast<const uint8_t*>(map_file::kMagic), sizeof(map_file::kMagic));
  out.u32(map_file::kVersion);
  out.u64(body.size());
  out.raw(body.data(), body.size());
  out.u64(fnv1a64(out.bytes().data(), out.bytes().size()));
  return std::move(out.bytes());
}

void MapFileWriter::write(const std::string& path, const MapFileSetup& setup, const Map& map,
                          const std::map<long, KeyFramePlace>& places) {
  const std::vector<uint8_t> bytes = encode(setup, map, places);
  AtomicFile file(path, std::ios::binary);
  file.stream().write(reinterpret_cast<const char*>(bytes.data()),
                      static_cast<std::streamsize>(bytes.size()));
  file.commit();
}

}  // namespace ply_slam
