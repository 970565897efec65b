#include "ply_slam/map/map_file_reader.h"

#include <cstring>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

#include "ply_slam/common/number_text.h"
#include "ply_slam/io/byte_reader.h"
#include "ply_slam/io/fnv1a.h"
#include "ply_slam/map/map_file_format.h"
#include "ply_slam/map/map_value_check.h"

namespace ply_slam {
namespace {

using map_file::kDescriptorBytes;
constexpr uint32_t kMaxLineSlots = 1000000;  // lines of one image; more is a forged count

// A fault of the content found after the checksum passed: a writer's bug or a forged file.
struct Inconsistent : std::runtime_error {
  using std::runtime_error::runtime_error;
};

[[noreturn]] void fail(const std::string& path, const std::string& what) {
  throw std::runtime_error("map file " + path + ": " + what);
}

// Links of a keyframe to what is read after it, by id.
struct PendingLinks {
  long parent = -1;
  std::vector<std::pair<uint32_t, long>> lines;  // (slot, line id)
  std::vector<std::pair<long, int>> covisible;
};

// A count of items of at least `min_bytes` each that the rest of the payload can hold.
size_t count(ByteReader& in, size_t min_bytes) {
  const uint32_t n = in.u32();
  if (n * uint64_t{min_bytes} > in.remaining())
    throw Inconsistent("a count of " + std::to_string(n) + " exceeds the file");
  return n;
}

cv::Mat descriptorRows(ByteReader& in, size_t rows) {
  cv::Mat m(static_cast<int>(rows), kDescriptorBytes, CV_8UC1);
  if (rows > 0) std::memcpy(m.data, in.raw(rows * kDescriptorBytes), rows * kDescriptorBytes);
  return m;
}

Eigen::Vector3d vector3(ByteReader& in) {
  const double x = in.f64(), y = in.f64(), z = in.f64();
  return {x, y, z};
}

MapVocabulary vocabulary(ByteReader& in) {
  MapVocabulary v;
  v.name = in.text();
  v.checksum = in.u64();
  v.words = in.u64();
  return v;
}

MapFileSetup setup(ByteReader& in) {
  MapFileSetup s;
  s.camera.fx = in.f64();
  s.camera.fy = in.f64();
  s.camera.cx = in.f64();
  s.camera.cy = in.f64();
  s.camera.width = static_cast<int>(in.u32());
  s.camera.height = static_cast<int>(in.u32());
  s.orb_levels = static_cast<int>(in.u32());
  s.orb_scale_factor = in.f64();
  s.orb_vocabulary = vocabulary(in);
  s.lbd_vocabulary = vocabulary(in);
  return s;
}

std::string describe(const MapVocabulary& v) {
  if (v.words == 0) return "none (no place recognition)";
  std::ostringstream text;
  text << (v.name.empty() ? "?" : v.name) << " (checksum " << std::hex << v.checksum << std::dec
       << ", " << v.words << " words)";
  return text.str();
}

// Empty when a map of `stored` fits a system set up as `expected`; else what differs.
std::string mismatch(const MapFileSetup& stored, const MapFileSetup& expected) {
  const PinholeCamera &a = stored.camera, &b = expected.camera;
  std::ostringstream text;
  if (a.fx != b.fx || a.fy != b.fy || a.cx != b.cx || a.cy != b.cy || a.width != b.width ||
      a.height != b.height) {
    // Every digit: 517.3 and 517.30000000000001 differ, and the message must show how.
    auto intrinsics = [](const PinholeCamera& c) {
      return exactText(c.fx) + ' ' + exactText(c.fy) + ' ' + exactText(c.cx) + ' ' +
             exactText(c.cy) + ", " + std::to_string(c.width) + "x" + std::to_string(c.height);
    };
    text << "made with another camera: fx fy cx cy " << intrinsics(a)
         << " (this system: " << intrinsics(b) << ")";
  } else if (stored.orb_levels != expected.orb_levels ||
             stored.orb_scale_factor != expected.orb_scale_factor) {
    text << "made with another ORB pyramid: " << stored.orb_levels << " levels, scale "
         << exactText(stored.orb_scale_factor) << " (this system: " << expected.orb_levels << ", "
         << exactText(expected.orb_scale_factor) << ")";
  } else {
    for (const auto& [kind, s, e] :
         {std::make_tuple("ORB", stored.orb_vocabulary, expected.orb_vocabulary),
          std::make_tuple("LBD", stored.lbd_vocabulary, expected.lbd_vocabulary)})
      if (!s.sameContent(e)) {
        text << "built with the " << kind << " vocabulary " << describe(s) << ", this system uses "
             << describe(e);
        break;
      }
  }
  return text.str();
}

void keypoints(ByteReader& in, FrameFeatures& f, size_t levels) {
  const size_t n = count(in, 5 * 4 + 4 + 4 * 8 + 4 + kDescriptorBytes);
  f.keypoints.resize(n);
  f.rectified.resize(n);
  f.undistorted.resize(n);
  f.depth.resize(n);
  for (size_t i = 0; i < n; ++i) {
    cv::KeyPoint& k = f.keypoints[i];
    k.pt.x = in.f32();
    k.pt.y = in.f32();
    k.size = in.f32();
    k.angle = in.f32();
    k.response = in.f32();
    k.octave = in.i32();
    if (k.octave < 0 || static_cast<size_t>(k.octave) >= levels)
      throw Inconsistent("keypoint level " + std::to_string(k.octave) + " outside the pyramid");
    const double ru = in.f64(), rv = in.f64(), uu = in.f64(), uv = in.f64();
    f.rectified[i] = {ru, rv};
    f.undistorted[i] = {uu, uv};
    f.depth[i] = in.f32();
  }
  f.descriptors = descriptorRows(in, n);
}

std::shared_ptr<KeyFrame> keyFrame(ByteReader& in, const MapFileSetup& setup,
                                   const std::vector<double>* scales, PendingLinks& links) {
  auto kf = std::make_shared<KeyFrame>();
  kf->id = in.i64();
  kf->frame_id = in.i64();
  kf->stamp = in.f64();
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) T(r, c) = in.f64();
  kf->T_cw.matrix() = T;
  links.parent = in.i64();
  FrameFeatures& f = kf->features;
  keypoints(in, f, scales->size());
  f.scales = scales;
  f.width = setup.camera.width;
  f.height = setup.camera.height;
  f.buildGrid();
  kf->map_points.resize(f.size());
  const uint32_t slots = in.u32();
  if (slots > kMaxLineSlots) throw Inconsistent(std::to_string(slots) + " line slots");
  kf->map_lines.resize(slots);
  const size_t lines = count(in, 12);
  for (size_t i = 0; i < lines; ++i) {
    const uint32_t slot = in.u32();
    links.lines.emplace_back(slot, in.i64());
  }
  const size_t covisible = count(in, 12);
  for (size_t i = 0; i < covisible; ++i) {
    const long id = in.i64();
    links.covisible.emplace_back(id, in.i32());
  }
  return kf;
}

using KeyFrameIndex = std::unordered_map<long, std::shared_ptr<KeyFrame>>;

KeyFrame& find(const KeyFrameIndex& keyframes, long id, const char* what) {
  const auto it = keyframes.find(id);
  if (it == keyframes.end())
    throw Inconsistent(std::string(what) + " names keyframe " + std::to_string(id) +
                       ", which the file does not hold");
  return *it->second;
}

std::shared_ptr<MapPoint> point(ByteReader& in, const KeyFrameIndex& keyframes) {
  auto p = std::make_shared<MapPoint>();
  p->id = in.i64();
  p->position = vector3(in);
  p->normal = vector3(in);
  p->min_distance = in.f64();
  p->max_distance = in.f64();
  p->position_weight = in.f64();
  p->descriptor = descriptorRows(in, 1);
  p->visible = in.i32();
  p->found = in.i32();
  p->first_keyframe_id = in.i64();
  const size_t observers = count(in, 12);
  for (size_t i = 0; i < observers; ++i) {
    KeyFrame& kf = find(keyframes, in.i64(), "a point's observer");
    const uint32_t index = in.u32();
    if (index >= kf.map_points.size() || kf.map_points[index])
      throw Inconsistent("point " + std::to_string(p->id) + " observed at keypoint " +
                         std::to_string(index) + " of keyframe " + std::to_string(kf.id) +
                         ", which is missing or taken");
    kf.map_points[index] = p;
    p->observers.push_back({&kf, index});
  }
  return p;
}

std::shared_ptr<MapLine> line(ByteReader& in) {
  auto l = std::make_shared<MapLine>();
  l->id = in.i64();
  l->start = vector3(in);
  l->end = vector3(in);
  l->start_weight = in.f64();
  l->end_weight = in.f64();
  l->descriptor = descriptorRows(in, 1);
  l->first_keyframe_id = in.i64();
  l->observations = in.i32();
  l->found = in.i32();
  return l;
}

KeyFramePlace place(ByteReader& in, const KeyFrame& kf) {
  KeyFramePlace p;
  const size_t flags = count(in, 1);
  if (flags != kf.features.size())
    throw Inconsistent("keyframe " + std::to_string(kf.id) + "'s place flags do not match its " +
                       std::to_string(kf.features.size()) + " keypoints");
  const uint8_t* data = in.raw(flags);
  p.used_keypoints.assign(data, data + flags);
  p.lbd_descriptors = descriptorRows(in, count(in, kDescriptorBytes));
  const size_t instances = count(in, 4 + 32);
  for (size_t i = 0; i < instances; ++i) {
    InstanceBox b;
    b.class_name = in.text();
    b.box.x = in.f64();
    b.box.y = in.f64();
    b.box.width = in.f64();
    b.box.height = in.f64();
    p.instances.push_back(b);
  }
  return p;
}

void linkKeyFrames(MapFileContents& map, const KeyFrameIndex& index,
                   const std::vector<PendingLinks>& links,
                   const std::unordered_map<long, std::shared_ptr<MapLine>>& lines) {
  for (size_t k = 0; k < map.keyframes.size(); ++k) {
    KeyFrame& kf = *map.keyframes[k];
    const PendingLinks& l = links[k];
    if (k == 0 && l.parent >= 0)
      throw Inconsistent("the first keyframe, the spanning tree's root, has a parent");
    if (l.parent >= 0) kf.parent = &find(index, l.parent, "a keyframe's parent");
    for (const auto& [id, shared] : l.covisible)
      kf.covisibility[&find(index, id, "a covisibility link")] = shared;
    for (const auto& [slot, id] : l.lines) {
      const auto it = lines.find(id);
      if (slot >= kf.map_lines.size() || it == lines.end())
        throw Inconsistent("keyframe " + std::to_string(kf.id) + " names line " +
                           std::to_string(id) + " at slot " + std::to_string(slot) +
                           ", which the file does not hold");
      kf.map_lines[slot] = it->second;
    }
  }
}

MapFileContents decodePayload(ByteReader& in, const MapFileSetup& stored,
                              const std::vector<double>* scales) {
  MapFileContents map;
  map.setup = stored;
  KeyFrameIndex index;
  std::vector<PendingLinks> links(count(in, 100));
  for (PendingLinks& l : links) {
    auto kf = keyFrame(in, stored, scales, l);
    if (!map.keyframes.empty() && kf->id <= map.keyframes.back()->id)
      throw Inconsistent("keyframe ids not increasing at " + std::to_string(kf->id));
    index.emplace(kf->id, kf);
    map.keyframes.push_back(kf);
  }
  if (map.keyframes.empty()) throw Inconsistent("no keyframes");
  const size_t points = count(in, 100);
  std::unordered_set<long> point_ids;
  for (size_t i = 0; i < points; ++i) {
    map.points.push_back(point(in, index));
    if (!point_ids.insert(map.points.back()->id).second)
      throw Inconsistent("point " + std::to_string(map.points.back()->id) + " stored twice");
  }
  std::unordered_map<long, std::shared_ptr<MapLine>> line_index;
  const size_t lines = count(in, 100);
  for (size_t i = 0; i < lines; ++i) {
    map.lines.push_back(line(in));
    if (!line_index.emplace(map.lines.back()->id, map.lines.back()).second)
      throw Inconsistent("line " + std::to_string(map.lines.back()->id) + " stored twice");
  }
  linkKeyFrames(map, index, links, line_index);
  const size_t places = count(in, 20);
  for (size_t i = 0; i < places; ++i) {
    const long id = in.i64();
    map.places[id] = place(in, find(index, id, "a place record"));
  }
  if (in.remaining() != 0) throw Inconsistent("bytes left after the last place record");
  return map;
}

// Throws naming `path` unless `bytes` are a whole map file of this version whose checksum holds.
void checkBytes(const std::vector<uint8_t>& bytes, const std::string& path) {
  if (bytes.size() < sizeof(map_file::kMagic)) fail(path, "truncated (no header)");
  if (std::memcmp(bytes.data(), map_file::kMagic, sizeof(map_file::kMagic)) != 0)
    fail(path, "bad magic: not a ply_slam map file");
  if (bytes.size() < map_file::kHeaderBytes) fail(path, "truncated (header incomplete)");
  const auto version = ByteReader::word(bytes.data() + 8, 4);
  if (version != map_file::kVersion)
    fail(path, "format version " + std::to_string(version) + ", this build reads " +
                   std::to_string(map_file::kVersion));
  const uint64_t payload = ByteReader::word(bytes.data() + 12, 8);
  const uint64_t size = map_file::kHeaderBytes + payload + 8;
  if (payload > bytes.size() || bytes.size() < size)
    fail(path, "truncated: " + std::to_string(bytes.size()) + " bytes, the header announces " +
                   std::to_string(size));
  if (bytes.size() > size) fail(path, "trailing bytes after the checksum");
  if (fnv1a64(bytes.data(), size - 8) != ByteReader::word(bytes.data() + size - 8, 8))
    fail(path, "checksum mismatch (corrupted)");
}

}  // namespace

MapFileContents MapFileReader::read(const std::string& path, const MapFileSetup& expected,
                                    const std::vector<double>* scales) {
  std::string why;
  std::optional<std::vector<uint8_t>> bytes = readFileBytes(path, &why);
  if (!bytes) fail(path, why);
  return decode(*bytes, path, expected, scales);
}

MapFileContents MapFileReader::decode(const std::vector<uint8_t>& bytes, const std::string& name,
                                      const MapFileSetup& expected,
                                      const std::vector<double>* scales) {
  checkBytes(bytes, name);
  ByteReader in(bytes.data() + map_file::kHeaderBytes, bytes.size() - map_file::kHeaderBytes - 8);
  try {
    const MapFileSetup stored = setup(in);
    const std::string differs = mismatch(stored, expected);
    if (!differs.empty()) fail(name, differs);
    MapFileContents contents = decodePayload(in, stored, scales);
    if (const std::string problem = findMapValueProblem(contents); !problem.empty())
      fail(name, problem);
    contents.checksum = ByteReader::word(bytes.data() + bytes.size() - 8, 8);
    return contents;
  } catch (const Inconsistent& e) {
    fail(name, std::string("inconsistent content: ") + e.what());
  } catch (const ByteReader::Truncated& e) {
    fail(name, std::string("inconsistent content (a record runs past the payload): ") + e.what());
  }
}

}  // namespace ply_slam
