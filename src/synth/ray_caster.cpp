#include "ply_slam/synth/ray_caster.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <opencv2/core/utility.hpp>

namespace ply_slam {
namespace {

constexpr int kTile = 16;
// Tolerance on the quad's (a, b) range: a ray exactly on the edge shared by two quads must
// not slip through both by rounding and show the wall behind.
constexpr float kEdgeSlack = 1e-6f;

// A quad in the camera frame, in float, with everything the inner loop needs.
struct PreparedQuad {
  Eigen::Vector3f o, uu, vv, n;  // origin, u / |u|^2, v / |v|^2, u x v
  float n_dot_o = 0.0f;
  float inv_n_norm = 0.0f;
  float len_u = 0.0f, len_v = 0.0f;
  float shade = 1.0f;
  const Texture* texture = nullptr;
  float s0 = 0.0f, t0 = 0.0f, ds = 0.0f, dt = 0.0f;  // texel = s0 + metres * ds
  float lod_texels_per_metre = 0.0f;
  bool repeat = false;
  cv::Vec3f colour;
  uint8_t instance = 0;
};

struct Hit {
  int k = -1;
  float t = FLT_MAX;  // = depth, the rays have d.z = 1
  float a = 0.0f, b = 0.0f;
};

inline void intersect(const PreparedQuad& q, int k, float dx, float dy, float near, Hit& best) {
  const float nd = q.n.x() * dx + q.n.y() * dy + q.n.z();
  const float t = q.n_dot_o / nd;
  if (!(t > near && t < best.t)) return;  // also rejects NaN (ray in the quad's plane)
  const float px = t * dx - q.o.x(), py = t * dy - q.o.y(), pz = t - q.o.z();
  const float a = px * q.uu.x() + py * q.uu.y() + pz * q.uu.z();
  if (a < -kEdgeSlack || a > 1.0f + kEdgeSlack) return;
  const float b = px * q.vv.x() + py * q.vv.y() + pz * q.vv.z();
  if (b < -kEdgeSlack || b > 1.0f + kEdgeSlack) return;
  best.k = k;
  best.t = t;
  best.a = a;
  best.b = b;
}

// Shaded colour (BGR, [0, 1]) of a hit on q by ray (dx, dy, 1).
cv::Vec3f shadeHit(const PreparedQuad& q, float dx, float dy, const Hit& hit, float inv_focal) {
  cv::Vec3f c = q.colour;
  if (q.texture) {
    const float s = q.s0 + hit.a * q.len_u * q.ds;
    const float t = q.t0 + hit.b * q.len_v * q.dt;
    // Pixel footprint on the surface: distance / focal, stretched by the slant. The square
    // root of the slant is a compromise between blur and aliasing (no anisotropic filter).
    const float ray_len = std::sqrt(dx * dx + dy * dy + 1.0f);
    const float cos_slant =
        std::abs(q.n.x() * dx + q.n.y() * dy + q.n.z()) * q.inv_n_norm / ray_len;
    const float metres = hit.t * ray_len * inv_focal / std::sqrt(std::max(cos_slant, 1e-3f));
    const float lod = std::log2(std::max(metres * q.lod_texels_per_metre, 1e-6f));
    c = q.texture->sample(s, t, lod, q.repeat).mul(q.colour);
  }
  return c * q.shade;
}

inline cv::Vec3b toBgr8(const cv::Vec3f& c) {
  return {cv::saturate_cast<uchar>(c[0] * 255.0f + 0.5f),
          cv::saturate_cast<uchar>(c[1] * 255.0f + 0.5f),
          cv::saturate_cast<uchar>(c[2] * 255.0f + 0.5f)};
}

// Pixel bounds of the quad's outline clipped to z >= near; false when nothing is in front.
bool projectedBounds(const std::array<Eigen::Vector3d, 4>& corners, double near,
                     const PinholeCamera& cam, int* x0, int* x1, int* y0, int* y1) {
  // Sutherland-Hodgman against the near plane.
  Eigen::Vector3d poly[8];
  int n = 0;
  for (int i = 0; i < 4; ++i) {
    const Eigen::Vector3d& p = corners[i];
    const Eigen::Vector3d& q = corners[(i + 1) % 4];
    const bool p_in = p.z() >= near, q_in = q.z() >= near;
    if (p_in) poly[n++] = p;
    if (p_in != q_in) poly[n++] = p + (q - p) * ((near - p.z()) / (q.z() - p.z()));
  }
  if (n == 0) return false;
  double umin = DBL_MAX, umax = -DBL_MAX, vmin = DBL_MAX, vmax = -DBL_MAX;
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d uv = cam.project(poly[i]);
    umin = std::min(umin, uv.x());
    umax = std::max(umax, uv.x());
    vmin = std::min(vmin, uv.y());
    vmax = std::max(vmax, uv.y());
  }
  // One pixel of margin: the anti-aliasing rays reach half a pixel beyond the centre.
  *x0 = static_cast<int>(std::max(std::floor(umin) - 1.0, 0.0));
  *y0 = static_cast<int>(std::max(std::floor(vmin) - 1.0, 0.0));
  *x1 = static_cast<int>(std::min(std::ceil(umax) + 1.0, cam.width - 1.0));
  *y1 = static_cast<int>(std::min(std::ceil(vmax) + 1.0, cam.height - 1.0));
  return *x0 <= *x1 && *y0 <= *y1;
}

// The quads of one view in the camera frame, binned into kTile x kTile pixel tiles.
struct PreparedView {
  const PinholeCamera& cam;
  float near, inv_focal;
  int tiles_x, tiles_y;
  std::vector<PreparedQuad> quads;
  std::vector<std::vector<int>> tiles;  // per tile, the quads whose image bounds reach it
};

PreparedQuad prepareQuad(const Scene& scene, const Quad& quad, const Eigen::Isometry3d& T_cw,
                         const Eigen::Vector3d& centre) {
  PreparedQuad q{};
  const Eigen::Vector3d o = T_cw * quad.origin;
  const Eigen::Vector3d u = T_cw.linear() * quad.axis_u;
  const Eigen::Vector3d v = T_cw.linear() * quad.axis_v;
  const Eigen::Vector3d n = u.cross(v);
  q.o = o.cast<float>();
  q.uu = (u / u.squaredNorm()).cast<float>();
  q.vv = (v / v.squaredNorm()).cast<float>();
  q.n = n.cast<float>();
  q.n_dot_o = static_cast<float>(n.dot(o));
  q.inv_n_norm = static_cast<float>(1.0 / n.norm());
  q.len_u = static_cast<float>(quad.axis_u.norm());
  q.len_v = static_cast<float>(quad.axis_v.norm());
  // Two-sided: shade with the normal on the camera's side.
  Eigen::Vector3d n_world = quad.axis_u.cross(quad.axis_v).normalized();
  if (n_world.dot(centre - quad.origin) < 0.0) n_world = -n_world;
  q.shade = static_cast<float>(scene.lighting().shade(n_world));
  const SurfaceMaterial& m = quad.material;
  q.colour = m.colour;
  q.instance = static_cast<uint8_t>(quad.instance);
  if (m.texture >= 0) {
    q.texture = &scene.textures().at(m.texture);
    q.s0 = static_cast<float>(m.texel_origin.x());
    q.t0 = static_cast<float>(m.texel_origin.y());
    q.ds = static_cast<float>(m.texels_per_metre.x());
    q.dt = static_cast<float>(m.texels_per_metre.y());
    q.lod_texels_per_metre =
        static_cast<float>(std::sqrt(m.texels_per_metre.x() * m.texels_per_metre.y()));
    q.repeat = m.repeat;
  }
  return q;
}

PreparedView prepareView(const Scene& scene, const std::vector<Quad>& quads,
                         const Eigen::Isometry3d& T_wc, const PinholeCamera& cam, double near) {
  const int tiles_x = (cam.width + kTile - 1) / kTile, tiles_y = (cam.height + kTile - 1) / kTile;
  PreparedView view{cam,
                    static_cast<float>(near),
                    static_cast<float>(1.0 / std::sqrt(cam.fx * cam.fy)),
                    tiles_x,
                    tiles_y,
                    std::vector<PreparedQuad>(quads.size()),
                    std::vector<std::vector<int>>(tiles_x * tiles_y)};
  const Eigen::Isometry3d T_cw = T_wc.inverse();
  for (size_t k = 0; k < quads.size(); ++k) {
    view.quads[k] = prepareQuad(scene, quads[k], T_cw, T_wc.translation());
    std::array<Eigen::Vector3d, 4> corners;
    for (int c = 0; c < 4; ++c) corners[c] = T_cw * quads[k].corner(c);
    int x0, x1, y0, y1;
    if (!projectedBounds(corners, near, cam, &x0, &x1, &y0, &y1)) continue;
    for (int ty = y0 / kTile; ty <= y1 / kTile; ++ty)
      for (int tx = x0 / kTile; tx <= x1 / kTile; ++tx)
        view.tiles[ty * tiles_x + tx].push_back(static_cast<int>(k));
  }
  return view;
}

// One ray through each pixel centre: colour, depth, instance and surface of the nearest hit.
RenderedFrame castPrimaryRays(const PreparedView& view) {
  const PinholeCamera& cam = view.cam;
  const int W = cam.width, H = cam.height, tiles_x = view.tiles_x, tiles_y = view.tiles_y;
  const float near = view.near, inv_focal = view.inv_focal;
  const std::vector<PreparedQuad>& prepared = view.quads;
  const std::vector<std::vector<int>>& tiles = view.tiles;
  // Ray directions with z = 1, so the ray parameter is the depth.
  std::vector<float> ray_x(W), ray_y(H);
  for (int x = 0; x < W; ++x) ray_x[x] = static_cast<float>((x - cam.cx) / cam.fx);
  for (int y = 0; y < H; ++y) ray_y[y] = static_cast<float>((y - cam.cy) / cam.fy);

  RenderedFrame f;
  f.rgb.create(H, W, CV_8UC3);
  f.depth.create(H, W, CV_32FC1);
  f.instance.create(H, W, CV_8UC1);
  f.surface.create(H, W, CV_32SC1);
  f.surface_coords.create(H, W, CV_32FC2);

  cv::parallel_for_(cv::Range(0, tiles_y), [&](const cv::Range& range) {
    for (int ty = range.start; ty < range.end; ++ty) {
      const int y_end = std::min(H, (ty + 1) * kTile);
      for (int tx = 0; tx < tiles_x; ++tx) {
        const std::vector<int>& list = tiles[ty * tiles_x + tx];
        const int x_end = std::min(W, (tx + 1) * kTile);
        for (int y = ty * kTile; y < y_end; ++y) {
          const float dy = ray_y[y];
          cv::Vec3b* rgb = f.rgb.ptr<cv::Vec3b>(y);
          float* depth = f.depth.ptr<float>(y);
          uint8_t* instance = f.instance.ptr<uint8_t>(y);
          int* surface = f.surface.ptr<int>(y);
          cv::Vec2f* coords = f.surface_coords.ptr<cv::Vec2f>(y);
          for (int x = tx * kTile; x < x_end; ++x) {
            const float dx = ray_x[x];
            Hit hit;
            for (int k : list) intersect(prepared[k], k, dx, dy, near, hit);
            if (hit.k < 0) {
              rgb[x] = cv::Vec3b(0, 0, 0);
              depth[x] = 0.0f;
              instance[x] = 0;
              surface[x] = -1;
              coords[x] = cv::Vec2f(0.0f, 0.0f);
              continue;
            }
            const PreparedQuad& q = prepared[hit.k];
            rgb[x] = toBgr8(shadeHit(q, dx, dy, hit, inv_focal));
            depth[x] = hit.t;
            instance[x] = q.instance;
            surface[x] = hit.k;
            coords[x] = cv::Vec2f(hit.a * q.len_u, hit.b * q.len_v);
          }
        }
      }
    }
  });

  return f;
}

void antialiasEdges(const PreparedView& view, RenderedFrame& f) {
  const PinholeCamera& cam = view.cam;
  const int W = cam.width, H = cam.height, tiles_x = view.tiles_x;
  const float near = view.near, inv_focal = view.inv_focal;
  const std::vector<PreparedQuad>& prepared = view.quads;
  const std::vector<std::vector<int>>& tiles = view.tiles;
  // Silhouettes and quad borders: average the colour of 4 rotated-grid sub-pixel rays so that
  // edges fall between pixels as in a camera image, not on a staircase.
  static const float kSub[4][2] = {
      {-0.125f, -0.375f}, {0.375f, -0.125f}, {0.125f, 0.375f}, {-0.375f, 0.125f}};
  const cv::Mat surface = f.surface.clone();
  cv::parallel_for_(cv::Range(0, H), [&](const cv::Range& range) {
    for (int y = range.start; y < range.end; ++y) {
      const int* row = surface.ptr<int>(y);
      const int* up = surface.ptr<int>(std::max(y - 1, 0));
      const int* down = surface.ptr<int>(std::min(y + 1, H - 1));
      cv::Vec3b* rgb = f.rgb.ptr<cv::Vec3b>(y);
      for (int x = 0; x < W; ++x) {
        const int s = row[x];
        if (row[std::max(x - 1, 0)] == s && row[std::min(x + 1, W - 1)] == s && up[x] == s &&
            down[x] == s)
          continue;
        const std::vector<int>& list = tiles[(y / kTile) * tiles_x + x / kTile];
        cv::Vec3f sum(0.0f, 0.0f, 0.0f);
        for (const auto& o : kSub) {
          const float dx = static_cast<float>((x + o[0] - cam.cx) / cam.fx);
          const float dy = static_cast<float>((y + o[1] - cam.cy) / cam.fy);
          Hit hit;
          for (int k : list) intersect(prepared[k], k, dx, dy, near, hit);
          if (hit.k >= 0) sum += shadeHit(prepared[hit.k], dx, dy, hit, inv_focal);
        }
        rgb[x] = toBgr8(sum * 0.25f);
      }
    }
  });
}

}  // namespace

RayCaster::RayCaster(const PinholeCamera& camera, double near) : camera_(camera), near_(near) {}

RenderedFrame RayCaster::render(const Scene& scene, const std::vector<Quad>& quads,
                                const Eigen::Isometry3d& T_wc, bool antialias) const {
  const PreparedView view = prepareView(scene, quads, T_wc, camera_, near_);
  RenderedFrame f = castPrimaryRays(view);
  if (antialias) antialiasEdges(view, f);
  return f;
}

RayHit RayCaster::cast(const std::vector<Quad>& quads, const Eigen::Isometry3d& T_wc,
                       const Eigen::Vector2d& uv) const {
  const Eigen::Vector3d d = T_wc.linear() * camera_.backProject(uv, 1.0);  // world, z_c = 1
  const Eigen::Vector3d c = T_wc.translation();
  RayHit best;
  double best_t = DBL_MAX;
  for (size_t k = 0; k < quads.size(); ++k) {
    const Quad& q = quads[k];
    const Eigen::Vector3d n = q.axis_u.cross(q.axis_v);
    const double t = n.dot(q.origin - c) / n.dot(d);
    if (!(t > near_ && t < best_t)) continue;
    const Eigen::Vector3d p = c + t * d - q.origin;
    const double a = p.dot(q.axis_u) / q.axis_u.squaredNorm();
    const double b = p.dot(q.axis_v) / q.axis_v.squaredNorm();
    if (a < 0.0 || a > 1.0 || b < 0.0 || b > 1.0) continue;
    best_t = t;
    best.surface = static_cast<int>(k);
    best.depth = t;
    best.coords = {a * q.axis_u.norm(), b * q.axis_v.norm()};
    best.world = c + t * d;
  }
  return best;
}

}  // namespace ply_slam
