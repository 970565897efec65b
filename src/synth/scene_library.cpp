#include "ply_slam/synth/scene_library.h"

#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

#include "ply_slam/synth/quad_builder.h"

namespace ply_slam {
namespace {

using Eigen::Vector3d;
constexpr double kPictureOffset = 0.015;   // m a picture stands off its wall
constexpr double kDoorLeafOffset = 0.003;  // m a door leaf stands off its wall

cv::Vec3f bgr(float b, float g, float r) { return {b, g, r}; }
// Dark door frames stand out from light walls and light door leaves on their lit and shaded
// sides alike, and the leaves from the floor: every edge of a door is an image edge.
const cv::Vec3f kDarkWood = bgr(0.2f, 0.32f, 0.45f);
const cv::Vec3f kPaleLeaves[] = {bgr(0.8f, 0.85f, 0.9f), bgr(0.85f, 0.78f, 0.7f),
                                 bgr(0.7f, 0.85f, 0.75f)};
SurfaceMaterial plain(const cv::Vec3f& c) { return SurfaceMaterial::plain(c); }

// Builds scenes from rooms, boxes, pictures and doors, and records their edges as lines.
class Assembler {
 public:
  Assembler(Scene& scene, std::string texture_dir) : scene_(scene), dir_(std::move(texture_dir)) {}

  // A photograph from the texture folder (optionally a crop), loaded once.
  int photo(const std::string& file, const cv::Rect& crop = cv::Rect()) {
    const std::string key = file + "@" + std::to_string(crop.x) + "," + std::to_string(crop.y) +
                            "," + std::to_string(crop.width) + "," + std::to_string(crop.height);
    auto it = cache_.find(key);
    if (it != cache_.end()) return it->second;
    const std::string path = dir_ + "/" + file;
    // Checked first: imread would also print its own warning.
    cv::Mat image;
    if (std::filesystem::is_regular_file(path)) image = cv::imread(path, cv::IMREAD_COLOR);
    if (image.empty())
      throw std::runtime_error(path +
                               ": cannot read the photograph (install the Debian package "
                               "opencv-doc, or point --textures at a folder holding it)");
    if (crop.area() > 0) image = image(crop & cv::Rect(0, 0, image.cols, image.rows)).clone();
    const int index = scene_.addTexture(Texture(image, file));
    cache_[key] = index;
    return index;
  }
  const Texture& texture(int index) const { return scene_.textures().at(index); }
  SurfaceMaterial fitted(const std::string& file, double width, double height) {
    const int t = photo(file);
    return fittedPhoto(t, texture(t), width, height);
  }

  // The inside of a box-shaped room; its 12 edges are lines (floor, ceiling, corners).
  void room(const Vector3d& min, const Vector3d& max, const SurfaceMaterial& walls,
            const SurfaceMaterial& floor, const SurfaceMaterial& ceiling) {
    std::array<SurfaceMaterial, 6> faces{walls, walls, walls, walls, ceiling, floor};
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() << 0.5 * (min.x() + max.x()), 0.5 * (min.y() + max.y()), min.z();
    scene_.addQuads(makeBox(pose, max - min, faces));
    scene_.addLines(alignedBoxEdges(min, max));
    scene_.setBounds(min, max);
  }

  // An axis-aligned box with all 12 edges as lines: callers keep boxes from sharing a plane
  // with a neighbour of the same colour, where an edge would not be visible.
  void box(const Vector3d& min, const Vector3d& max, const std::array<SurfaceMaterial, 6>& faces) {
    Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
    pose.translation() << 0.5 * (min.x() + max.x()), 0.5 * (min.y() + max.y()), min.z();
    scene_.addQuads(makeBox(pose, max - min, faces));
    scene_.addLines(alignedBoxEdges(min, max));
  }
  void box(const Vector3d& min, const Vector3d& max, const SurfaceMaterial& m) {
    std::array<SurfaceMaterial, 6> faces;
    faces.fill(m);
    box(min, max, faces);
  }
  // A box with one photographed face (the others plain).
  void photoBox(const Vector3d& min, const Vector3d& max, BoxFace face, const std::string& file,
                const SurfaceMaterial& rest) {
    std::array<SurfaceMaterial, 6> faces;
    faces.fill(rest);
    const Vector3d size = max - min;
    double w = 0, h = 0;  // the face's u and v lengths, as makeBox builds them
    switch (face) {
      case kBoxFront:
      case kBoxBack:
        w = size.y(), h = size.z();
        break;
      case kBoxLeft:
      case kBoxRight:
        w = size.x(), h = size.z();
        break;
      default:
        w = size.y(), h = size.x();
    }
    faces[face] = fitted(file, w, h);
    box(min, max, faces);
  }

  // A photograph with a dark frame, flat on the plane spanned by unit `right` and `down`
  // around `centre`; outer_width includes the frame. Its outer border is a line.
  void framedPhoto(const Vector3d& centre, const Vector3d& right, const Vector3d& down,
                   double outer_width, const std::string& file, double frame,
                   const cv::Vec3f& frame_colour) {
    const int t = photo(file);
    const double w = outer_width - 2.0 * frame;
    const double h = w * texture(t).height() / texture(t).width();
    const double W = outer_width, H = h + 2.0 * frame;
    auto rect = [&](const Vector3d& origin, double du, double dv, const SurfaceMaterial& m) {
      Quad q;
      q.origin = origin;
      q.axis_u = du * right;
      q.axis_v = dv * down;
      q.material = m;
      scene_.addQuad(q);
      return q;
    };
    rect(centre - 0.5 * w * right - 0.5 * h * down, w, h, fittedPhoto(t, texture(t), w, h));
    const SurfaceMaterial f = plain(frame_colour);
    const Quad top = rect(centre - 0.5 * W * right - 0.5 * H * down, W, frame, f);
    rect(centre - 0.5 * W * right + (0.5 * H - frame) * down, W, frame, f);
    rect(centre - 0.5 * W * right - 0.5 * h * down, frame, h, f);
    rect(centre + (0.5 * W - frame) * right - 0.5 * h * down, frame, h, f);
    Quad outline = top;
    outline.axis_v = H * down;
    scene_.addLines(quadEdges(outline));
  }

  // A picture on a wall; centre on the wall plane, `facing` the wall's inward normal. Not a
  // labelled object: COCO has no class for pictures, doors, shelves or cabinets.
  void wallPicture(const Vector3d& centre, const Vector3d& facing, double outer_width,
                   const std::string& file) {
    const Vector3d right = (-facing).cross(Vector3d::UnitZ()).normalized();
    framedPhoto(centre + kPictureOffset * facing, right, -Vector3d::UnitZ(), outer_width, file,
                0.035, bgr(0.08f, 0.07f, 0.06f));
  }

  // The static quads that `build` adds form one object of a COCO class (masks, instances.txt):
  // the furniture a COCO segmenter reports, the desk and its monitor.
  template <class Build>
  void object(const std::string& class_name, Build build) {
    const std::size_t first = scene_.staticQuads().size();
    build();
    scene_.labelObject(first, class_name);
  }

  // A door in a wall: the leaf just off the wall and a frame (two jambs and a lintel)
  // standing out of it. bottom_centre on the wall plane at floor height.
  void door(const Vector3d& bottom_centre, const Vector3d& facing, double width, double height,
            const SurfaceMaterial& leaf, const SurfaceMaterial& frame) {
    const double jamb = 0.07, depth = 0.03, lf = kDoorLeafOffset;
    const Vector3d n = facing.normalized();
    const Vector3d r = (-n).cross(Vector3d::UnitZ()).normalized();
    const Vector3d z = Vector3d::UnitZ();
    auto at = [&](double s, double up, double d) {
      return Vector3d(bottom_centre + s * r + up * z + d * n);
    };
    scene_.addQuad(makeUprightRect(at(0, 0.5 * height, lf), n, width, height, leaf));
    auto aligned = [&](const Vector3d& a, const Vector3d& b) {
      scene_.addQuads(makeAlignedBox(a.cwiseMin(b), a.cwiseMax(b), frame));
    };
    const double hw = 0.5 * width, ow = hw + jamb;
    aligned(at(-ow, 0, 0), at(-hw, height, depth));
    aligned(at(hw, 0, 0), at(ow, height, depth));
    aligned(at(-ow, height, 0), at(ow, height + jamb, depth));
    // Only the edges between faces that differ: where the jambs meet the lintel the fronts
    // are one plane, and the leaf hides the wall behind the jambs' inner sides.
    auto line = [&](const Vector3d& a, const Vector3d& b) { scene_.addLine({a, b}); };
    for (double sign : {-1.0, 1.0}) {
      for (double d : {0.0, depth}) line(at(sign * ow, 0, d), at(sign * ow, height + jamb, d));
      for (double d : {lf, depth}) line(at(sign * hw, 0, d), at(sign * hw, height, d));
    }
    for (double d : {0.0, depth}) line(at(-ow, height + jamb, d), at(ow, height + jamb, d));
    for (double d : {lf, depth}) line(at(-hw, height, d), at(hw, height, d));
    line(at(-hw, 0, lf), at(hw, 0, lf));
  }

  // A person: a box with a photograph of one on its four sides.
  void walker(int instance, const Walker::Path& path, const std::string& file,
              const cv::Rect& crop) {
    const int t = photo(file, crop);
    const Vector3d size(0.3, 0.5, 1.7);
    scene_.addWalker(Walker(instance, path, size, fittedPhoto(t, texture(t), size.y(), size.z()),
                            plain(bgr(0.22f, 0.24f, 0.3f))));
  }

 private:
  Scene& scene_;
  std::string dir_;
  std::map<std::string, int> cache_;
};

// Walkers spread over the given loops: walker i takes loop i % loops, evenly spaced along it.
void addWalkers(Assembler& a, int count, const std::vector<Walker::Path>& loops) {
  static const struct {
    const char* file;
    cv::Rect crop;
  } kPeople[] = {{"basketball1.png", cv::Rect(30, 78, 136, 402)},
                 {"basketball2.png", cv::Rect(430, 20, 210, 460)}};
  const int n_loops = static_cast<int>(loops.size());
  for (int i = 0; i < count; ++i) {
    Walker::Path path = loops[i % n_loops];
    const int on_loop = (count - 1 - i % n_loops) / n_loops + 1;
    const double length = 2.0 * path.straight + 2.0 * M_PI * path.radius;
    path.start += (i / n_loops) * length / on_loop;
    const auto& person = kPeople[i % 2];
    a.walker(i + 1, path, person.file, person.crop);
  }
}

// Long on purpose: the office is a list of the things in it and where they stand, read top to
// bottom like a floor plan (walls, far wall, left wall, right wall, desk, back wall, people,
// camera); split into functions it would only scatter the coordinates.
SceneSetup office(const std::string& dir, int walkers, bool textured) {
  SceneSetup setup{Scene(textured ? "office" : "lowtexture"), CameraPathSpec()};
  Assembler a(setup.scene, dir);
  const cv::Vec3f wall = textured ? bgr(0.80f, 0.85f, 0.88f) : bgr(0.9f, 0.9f, 0.9f);
  const cv::Vec3f floor = textured ? bgr(0.2f, 0.27f, 0.38f) : bgr(0.27f, 0.28f, 0.3f);
  a.room({0, 0, 0}, {6, 5, 2.7}, plain(wall), plain(floor), plain(bgr(0.85f, 0.85f, 0.85f)));
  const Vector3d to_x(1, 0, 0), to_y(0, 1, 0);

  // Rug in the middle of the floor.
  if (textured) {
    a.framedPhoto({3.3, 2.6, 0.004}, to_x, -to_y, 2.8, "aero1.jpg", 0.1, bgr(0.15f, 0.15f, 0.45f));
  }

  // Far wall (x = 6).
  a.wallPicture({6, 3.3, 1.55}, -to_x, textured ? 1.7 : 0.7, "graf1.png");
  if (textured) {
    a.wallPicture({6, 1.25, 1.7}, -to_x, 1.2, "building.jpg");
    a.wallPicture({6, 4.55, 1.4}, -to_x, 0.5, "sudoku.png");
  }
  // Left wall (y = 0): picture, cabinet, door; a picture over the desk.
  a.wallPicture({2.0, 0, 1.55}, to_y, textured ? 1.3 : 0.6, "starry_night.jpg");
  if (textured) a.wallPicture({5.2, 0, 1.65}, to_y, 0.6, "fruits.jpg");
  a.box({2.5, 0, 0}, {3.3, 0.5, 0.9}, plain(bgr(0.45f, 0.6f, 0.75f)));
  if (textured)
    a.photoBox({2.6, 0.1, 0.9}, {2.9, 0.35, 1.15}, kBoxLeft, "apple.jpg",
               plain(bgr(0.3f, 0.5f, 0.3f)));
  a.door({4.0, 0, 0}, to_y, 0.9, 2.05, plain(kPaleLeaves[0]), plain(kDarkWood));
  // Right wall (y = 5): shelf with photographed boxes, pictures.
  if (textured) {
    a.wallPicture({5.3, 5, 1.6}, -to_y, 1.0, "leuvenA.jpg");
    a.wallPicture({3.8, 5, 2.2}, -to_y, 0.6, "butterfly.jpg");
  }
  const SurfaceMaterial shelf = plain(bgr(0.72f, 0.8f, 0.86f));
  a.box({3.0, 4.62, 0}, {3.02, 5.0, 1.8}, shelf);
  a.box({4.58, 4.62, 0}, {4.6, 5.0, 1.8}, shelf);
  const double boards[][2] = {{0.0, 0.04}, {0.45, 0.47}, {0.9, 0.92}, {1.35, 1.37}, {1.76, 1.78}};
  for (const auto& b : boards) a.box({3.02, 4.63, b[0]}, {4.58, 5.0, b[1]}, shelf);
  const struct {
    const char* file;
    double width, aspect;  // aspect: height / width of the photograph
  } kShelfItems[4][2] = {
      {{"rubberwhale1.png", 0.55, 388.0 / 584}, {"smarties.png", 0.4, 356.0 / 413}},
      {{"left.jpg", 0.52, 459.0 / 612}, {"box_in_scene.png", 0.5, 0.75}},
      {{"cards.png", 0.5, 0.75}, {"licenseplate_motion.jpg", 0.45, 482.0 / 600}},
      {{"pca_test1.jpg", 0.5, 0.75}, {"orange.jpg", 0.35, 1.0}}};
  const cv::Vec3f item_colours[] = {bgr(0.2f, 0.3f, 0.6f), bgr(0.55f, 0.35f, 0.25f),
                                    bgr(0.3f, 0.55f, 0.35f), bgr(0.6f, 0.6f, 0.3f)};
  for (int shelf_level = 0; shelf_level < 4; ++shelf_level) {
    double x = 3.08;
    for (int k = 0; k < 2; ++k) {
      const auto& item = kShelfItems[shelf_level][k];
      const double z0 = boards[shelf_level][1];
      const Vector3d lo(x, 4.72, z0), hi(x + item.width, 4.98, z0 + item.width * item.aspect);
      const SurfaceMaterial rest = plain(item_colours[(shelf_level + k) % 4]);
      if (textured)
        a.photoBox(lo, hi, kBoxRight, item.file, rest);
      else
        a.box(lo, hi, rest);
      x += item.width + 0.12;
    }
  }
  // Desk by the far wall with a monitor, a cookie box and a notebook.
  std::array<SurfaceMaterial, 6> desk;
  desk.fill(plain(bgr(0.2f, 0.3f, 0.42f)));
  desk[kBoxTop] = textured ? a.fitted("stuff.jpg", 1.6, 0.8) : plain(bgr(0.55f, 0.7f, 0.8f));
  a.object("dining table", [&] {
    a.box({5.0, 0.5, 0.72}, {5.8, 2.1, 0.76}, desk);
    const SurfaceMaterial metal = plain(bgr(0.55f, 0.55f, 0.55f));
    for (double x : {5.03, 5.72})
      for (double y : {0.53, 2.02}) a.box({x, y, 0}, {x + 0.05, y + 0.05, 0.72}, metal);
  });
  std::array<SurfaceMaterial, 6> screen;
  screen.fill(plain(bgr(0.08f, 0.08f, 0.08f)));
  screen[kBoxBack] = textured ? a.fitted("HappyFish.jpg", 0.7, 0.42) : screen[kBoxFront];
  a.object("tv", [&] {
    a.box({5.55, 1.2, 0.76}, {5.65, 1.4, 0.9}, plain(bgr(0.35f, 0.35f, 0.35f)));
    a.box({5.5, 0.95, 0.9}, {5.54, 1.65, 1.32}, screen);
  });
  if (textured) {
    a.photoBox({5.15, 1.75, 0.76}, {5.22, 2.0, 0.93}, kBoxBack, "box.png",
               plain(bgr(0.75f, 0.78f, 0.8f)));
    a.photoBox({5.1, 0.65, 0.76}, {5.4, 0.87, 0.8}, kBoxTop, "ela_original.jpg",
               plain(bgr(0.2f, 0.2f, 0.6f)));
  }
  // Back wall (x = 0), seen only when the camera turns round.
  if (textured) {
    a.wallPicture({0, 2.5, 1.5}, to_x, 0.9, "baboon.jpg");
    a.wallPicture({0, 1.0, 1.5}, to_x, 0.6, "chicky_512.png");
    a.wallPicture({0, 4.0, 1.5}, to_x, 0.6, "home.jpg");
  }

  // People walk two loops between the camera and the furniture.
  Walker::Path near_loop, far_loop;
  near_loop.centre = {3.0, 2.7};
  near_loop.heading = 0.5 * M_PI;
  near_loop.straight = 1.5;
  near_loop.radius = 0.5;
  far_loop.centre = {4.3, 3.1};
  far_loop.heading = -0.5 * M_PI;
  far_loop.straight = 1.6;
  far_loop.radius = 0.4;
  far_loop.start = 1.0;
  addWalkers(a, walkers, {near_loop, far_loop});

  CameraPathSpec& c = setup.camera;
  c.centre = {1.25, 2.6, 1.45};
  c.yaw = 0.0;
  c.pitch = -0.2;
  c.position_extent = {0.3, 0.45, 0.12};
  c.angle_extent = {0.45, 0.14, 0.08};
  return setup;
}

SceneSetup corridor(const std::string& dir, int walkers) {
  SceneSetup setup{Scene("corridor"), CameraPathSpec()};
  Assembler a(setup.scene, dir);
  const double length = 12.0, width = 2.2;
  a.room({0, 0, 0}, {length, width, 2.6}, plain(bgr(0.75f, 0.82f, 0.85f)),
         plain(bgr(0.25f, 0.28f, 0.3f)), plain(bgr(0.85f, 0.85f, 0.85f)));
  const Vector3d to_x(1, 0, 0), to_y(0, 1, 0);
  const SurfaceMaterial frame = plain(kDarkWood);
  const cv::Vec3f* leaves = kPaleLeaves;
  const char* left_pictures[] = {"building.jpg", "leuvenA.jpg", "home.jpg"};
  const char* right_pictures[] = {"fruits.jpg", "squirrel_cls.jpg", "butterfly.jpg"};
  for (int k = 0; k < 3; ++k) {
    a.door({2.6 + 3.0 * k, 0, 0}, to_y, 0.9, 2.05, plain(leaves[k]), frame);
    a.door({4.1 + 3.0 * k, width, 0}, -to_y, 0.9, 2.05, plain(leaves[(k + 1) % 3]), frame);
    a.wallPicture({4.1 + 3.0 * k, 0, 1.55}, to_y, 1.0, left_pictures[k]);
    a.wallPicture({2.6 + 3.0 * k, width, 1.5}, -to_y, 0.8, right_pictures[k]);
  }
  a.wallPicture({length, 1.1, 1.5}, -to_x, 1.4, "graf1.png");
  a.wallPicture({1.2, width, 1.5}, -to_y, 0.5, "sudoku.png");
  a.wallPicture({0, 1.1, 1.5}, to_x, 0.8, "baboon.jpg");

  Walker::Path loop;
  loop.centre = {8.0, 1.1};
  loop.straight = 3.6;
  loop.radius = 0.45;
  addWalkers(a, walkers, {loop});

  CameraPathSpec& c = setup.camera;
  c.centre = {0.9, 1.1, 1.5};
  c.pitch = -0.1;
  c.drift_velocity = {0.25, 0.0, 0.0};
  c.max_drift = 3.5;  // stays 0.8 m short of the walkers' loop
  c.position_extent = {0.2, 0.25, 0.1};
  c.angle_extent = {0.3, 0.12, 0.07};
  return setup;
}

// Pictures and doors along the walls of the ring. Every picture is a different photograph, so
// each stretch of the circuit looks like no other and a return is a recognisable place.
struct WallItem {
  double x, y;  // on the wall plane
  Vector3d facing;
  const char* file;  // nullptr: a door
  double width;      // the picture's outer width
};

void ringWalls(Assembler& a) {
  const Vector3d px(1, 0, 0), py(0, 1, 0);
  const WallItem items[] = {
      // Outer walls, facing into the corridor, counter-clockwise from the start's side.
      {1.0, 0, py, "baboon.jpg", 0.8},
      {2.6, 0, py, nullptr, 0},
      {4.2, 0, py, "building.jpg", 1.2},
      {5.8, 0, py, nullptr, 0},
      {7.0, 0, py, "fruits.jpg", 0.8},
      {8, 1.0, -px, "graf1.png", 1.0},
      {8, 2.6, -px, nullptr, 0},
      {8, 3.9, -px, "leuvenA.jpg", 1.0},
      {8, 5.2, -px, "sudoku.png", 0.6},
      {7.0, 6, -py, "home.jpg", 0.9},
      {5.6, 6, -py, nullptr, 0},
      {4.2, 6, -py, "squirrel_cls.jpg", 1.0},
      {2.8, 6, -py, nullptr, 0},
      {1.2, 6, -py, "butterfly.jpg", 0.8},
      {0, 5.0, px, "starry_night.jpg", 1.0},
      {0, 3.6, px, nullptr, 0},
      {0, 2.3, px, "HappyFish.jpg", 0.9},
      {0, 1.0, px, "chicky_512.png", 0.6},
      // The block's walls, facing out.
      {3.0, 2, -py, "cards.png", 0.7},
      {4.9, 2, -py, "messi5.jpg", 1.0},
      {6, 3.0, px, "aero1.jpg", 1.0},
      {5.0, 4, py, "left.jpg", 0.8},
      {3.0, 4, py, "stuff.jpg", 1.0},
      {2, 3.0, -px, "box_in_scene.png", 0.8}};
  int doors = 0;
  for (const WallItem& item : items) {
    if (item.file) {
      a.wallPicture({item.x, item.y, 1.55}, item.facing, item.width, item.file);
    } else {
      a.door({item.x, item.y, 0}, item.facing, 0.9, 2.05, plain(kPaleLeaves[doors++ % 3]),
             plain(kDarkWood));
    }
  }
}

// A corridor loop: the walls between its sides keep the camera from seeing a place again until
// it comes back round, unlike a room with a pillar, whose far walls stay in view all the way.
SceneSetup ring(const std::string& dir, int walkers) {
  if (walkers > 0) throw std::invalid_argument("the ring scene has no walkers");
  SceneSetup setup{Scene("ring"), CameraPathSpec()};
  Assembler a(setup.scene, dir);
  const double height = 2.6;
  const SurfaceMaterial wall = plain(bgr(0.75f, 0.82f, 0.85f));
  a.room({0, 0, 0}, {8, 6, height}, wall, plain(bgr(0.25f, 0.28f, 0.3f)),
         plain(bgr(0.85f, 0.85f, 0.85f)));
  // Floor to ceiling: nothing is seen over it.
  a.box({2, 2, 0}, {6, 4, height}, plain(bgr(0.7f, 0.78f, 0.86f)));
  ringWalls(a);

  CameraPathSpec& c = setup.camera;
  c.centre = {4.0, 1.0, 1.5};   // the middle of the first side, heading +x
  c.circuit_size = {6.0, 4.0};  // the corridors' centre lines
  c.corner_length = 1.5;        // 36 deg/s at the middle of a turn at 0.38 m/s
  c.pitch = -0.1;
  c.position_extent = {0.2, 0.2, 0.1};
  c.angle_extent = {0.3, 0.12, 0.07};
  c.linear_speed = 0.45;  // the walk alone is 0.38 m/s at 1500 frames
  return setup;
}

}  // namespace

bool parseSceneKind(const std::string& text, SceneKind* kind) {
  if (text == "office") {
    *kind = SceneKind::kOffice;
  } else if (text == "lowtexture") {
    *kind = SceneKind::kLowTexture;
  } else if (text == "corridor") {
    *kind = SceneKind::kCorridor;
  } else if (text == "ring") {
    *kind = SceneKind::kRing;
  } else {
    return false;
  }
  return true;
}

std::string sceneKindName(SceneKind kind) {
  switch (kind) {
    case SceneKind::kOffice:
      return "office";
    case SceneKind::kLowTexture:
      return "lowtexture";
    case SceneKind::kCorridor:
      return "corridor";
    default:
      return "ring";
  }
}

int defaultFrames(SceneKind kind) { return kind == SceneKind::kRing ? 1500 : 300; }

SceneSetup buildScene(SceneKind kind, int walkers, const std::string& texture_dir) {
  if (walkers < 0 || walkers >= Scene::kFirstObjectInstance)
    throw std::invalid_argument("walkers must be in 0.." +
                                std::to_string(Scene::kFirstObjectInstance - 1));
  switch (kind) {
    case SceneKind::kOffice:
      return office(texture_dir, walkers, true);
    case SceneKind::kLowTexture:
      return office(texture_dir, walkers, false);
    case SceneKind::kCorridor:
      return corridor(texture_dir, walkers);
    default:
      return ring(texture_dir, walkers);
  }
}

}  // namespace ply_slam
