#include "ply_slam/features/line_depth_refiner.h"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <vector>

namespace ply_slam {

namespace {

constexpr int kFirstOffsetPx = 2;  // the pixel beside an edge mixes both surfaces (or is a hole)
constexpr int kMinColumns = 3;     // offsets a side's surface must cover to be fitted
constexpr int kMaxPositions = 48;  // along the extent, one per px up to this: the band's cost
constexpr double kMinValidShare = 0.5;  // of a column's pixels, with depth and on the plane
constexpr double kModelSlack = 0.003;   // of Z: two sides of a crease still meet (2D line error)

struct BandSample {
  double s, t, y, w;  // along (from the extent's middle), across, 1/Z, 1/var(1/Z)
};

// Weighted least squares of y = a + b s + c t, accumulated sample by sample.
struct PlaneSums {
  double w = 0, ws = 0, wt = 0, wss = 0, wst = 0, wtt = 0, wy = 0, wsy = 0, wty = 0;
  void add(const BandSample& b) {
    const double ws_ = b.w * b.s, wt_ = b.w * b.t;
    w += b.w;
    ws += ws_;
    wt += wt_;
    wss += ws_ * b.s;
    wst += ws_ * b.t;
    wtt += wt_ * b.t;
    wy += b.w * b.y;
    wsy += ws_ * b.y;
    wty += wt_ * b.y;
  }
  Eigen::Matrix3d information() const {
    Eigen::Matrix3d m;
    m << w, ws, wt, ws, wss, wst, wt, wst, wtt;
    return m;
  }
  Eigen::Vector3d rhs() const { return {wy, wsy, wty}; }
  Eigen::Vector3d rowSum() const { return {w, ws, wt}; }  // the weighted sum of rows
  PlaneSums& operator+=(const PlaneSums& o) {
    w += o.w, ws += o.ws, wt += o.wt, wss += o.wss, wst += o.wst, wtt += o.wtt;
    wy += o.wy, wsy += o.wsy, wty += o.wty;
    return *this;
  }
};

double residual(const BandSample& b, const Eigen::Vector3d& theta) {
  return b.y - theta.x() - theta.y() * b.s - theta.z() * b.t;
}

}  // namespace

LineDepthRefiner::LineDepthRefiner(const LineOptions& params, const PinholeCamera& camera)
    : params_(params), camera_(camera), depth_(camera) {}

LineDepthRefiner::SideFit LineDepthRefiner::fitSide(const Band& band, const cv::Mat& depth_m,
                                                    double side) const {
  SideFit fit;
  const int positions = static_cast<int>(band.raw.size());
  // The band grows a column (the pixels t px off the segment at each position) at a time
  // while the next column continues the plane of those before it (its mean residual within
  // 3 sigma of its own noise and the plane's), so a wide surface gives many depths and a narrow
  // one is not fitted across its far edge. Each sample is placed where the pixel read is, not
  // where it was asked for (at a surface seen at a grazing angle half a pixel is a centimetre of
  // depth); the raw rounding offset maps back unchanged to first order.
  std::vector<BandSample> samples;
  samples.reserve(static_cast<size_t>(positions) * params_.surface_band_px);
  PlaneSums sums;
  int columns = 0;
  // Reads column t; adds it when `checked` is false or it continues the plane so far.
  auto addColumn = [&](int t, bool checked) {
    const size_t first = samples.size();
    const double offset = side * t;
    double weight = 0.0;
    for (int i = 0; i < positions; ++i) {
      Eigen::Vector2d delta;
      const double z = depth_.atRaw(depth_m, band.raw[i] + offset * band.raw_across[i], &delta);
      if (z <= 0.0) continue;
      // var(1/Z) = var(Z) / Z^4 to first order; one weight per column (its depth varies little).
      if (weight == 0.0) weight = z * z * z * z / camera_.depth_noise.variance(z);
      samples.push_back(
          {band.s[i] + delta.dot(band.d), t + side * delta.dot(band.across), 1.0 / z, weight});
    }
    PlaneSums column;
    for (size_t k = first; k < samples.size(); ++k) column.add(samples[k]);
    bool continues = samples.size() - first >= kMinValidShare * positions;
    if (continues && checked) {
      // The column's weighted mean residual and mean row follow from its sums.
      const Eigen::LDLT<Eigen::Matrix3d> solver(sums.information());
      const Eigen::Vector3d theta = solver.solve(sums.rhs());
      const Eigen::Vector3d mean_row = column.rowSum() / column.w;
      const double mean_residual = column.wy / column.w - theta.dot(mean_row);
      const double variance = 1.0 / column.w + mean_row.dot(solver.solve(mean_row));
      continues = std::abs(mean_residual) <= 3.0 * std::sqrt(variance);
    }
    if (!continues) {
      samples.resize(first);
      return false;
    }
    sums += column;
    ++columns;
    return true;
  };
  for (int t = kFirstOffsetPx; t <= params_.surface_band_px; ++t)
    if (!addColumn(t, columns >= kMinColumns)) break;
  // The column next to the segment: a hole or both surfaces at an occluding edge, but the
  // nearest depths of a crease or a painted edge, where it continues the plane.
  if (columns >= kMinColumns) addColumn(1, true);
  if (columns < kMinColumns) return fit;

  // Twice more without the samples off the plane by more than 3 sigma of the sensor: flying
  // pixels at an edge, a strip of another surface. (Where the sensor is noisier than its model
  // says, too few samples stay and the side is not used.)
  Eigen::Matrix3d info = sums.information();
  Eigen::Vector3d theta = info.ldlt().solve(sums.rhs());
  for (int round = 0; round < 2; ++round) {
    const Eigen::Vector3d plane = theta;
    sums = PlaneSums();
    size_t kept = 0;
    for (const BandSample& b : samples) {
      const double r = residual(b, plane);
      if (r * r * b.w >= 9.0) continue;
      sums.add(b);
      ++kept;
    }
    if (kept < kMinValidShare * samples.size()) return fit;
    info = sums.information();
    const Eigen::LDLT<Eigen::Matrix3d> solver(info);
    if (solver.info() != Eigen::Success || !solver.isPositive()) return fit;
    theta = solver.solve(sums.rhs());
  }
  // At the segment (t = 0) the inverse depth is a + b s: positive along the whole extent.
  for (const double s : {band.s.front(), band.s.back()})
    if (theta.x() + theta.y() * s <= 0.0) return fit;
  fit.alpha_beta = theta.head<2>();
  fit.covariance = info.inverse().topLeftCorner<2, 2>();
  fit.ok = true;
  return fit;
}

bool LineDepthRefiner::refine(const LineFeature& segment, const cv::Mat& depth_m,
                              Line3D& line) const {
  if (params_.surface_band_px < kFirstOffsetPx || !line.valid) return false;
  if (!(line.start.z() > 0.0 && line.end.z() > 0.0)) return false;  // not in front: no extent
  CV_Assert(depth_m.type() == CV_32F);
  Band band;
  band.d = segment.direction();
  band.across = Eigen::Vector2d(-band.d.y(), band.d.x());
  const Eigen::Vector2d& d = band.d;
  // The fitted extent along the segment: its ends project onto the segment's line.
  const double s0 = (camera_.project(line.start) - segment.start).dot(d);
  const double s1 = (camera_.project(line.end) - segment.start).dot(d);
  const double s_mid = 0.5 * (s0 + s1);
  const int positions =
      std::clamp(static_cast<int>(std::ceil(std::abs(s1 - s0))) + 1, 2, kMaxPositions);
  band.raw.resize(positions);
  band.raw_across.resize(positions);
  band.s.resize(positions);
  // One px across in raw pixels at either end, in between interpolated (distortion changes
  // it smoothly).
  const Eigen::Vector2d raw_across[2] = {depth_.rawStep(segment.start + s0 * d, band.across),
                                         depth_.rawStep(segment.start + s1 * d, band.across)};
  for (int i = 0; i < positions; ++i) {
    const double f = static_cast<double>(i) / (positions - 1);
    const double s = s0 + (s1 - s0) * f;
    band.s[i] = s - s_mid;
    band.raw[i] = depth_.distort(segment.start + s * d);
    band.raw_across[i] = raw_across[0] * (1.0 - f) + raw_across[1] * f;
  }

  // A side's depth at s on the segment and its variance, to first order from var(1/Z).
  auto depthAt = [&](const SideFit& f, double s, double& variance) {
    const Eigen::Vector2d J(1.0, s - s_mid);
    const double w = f.alpha_beta.dot(J);
    variance = J.dot(f.covariance * J) / (w * w * w * w);
    return 1.0 / w;
  };
  auto agreesWithFit = [&](const SideFit& f) {
    for (const auto& [s, z_fit] : {std::pair{s0, line.start.z()}, std::pair{s1, line.end.z()}}) {
      double variance = 0.0;
      if (std::abs(depthAt(f, s, variance) - z_fit) > camera_.depth_noise.surfaceGap(z_fit))
        return false;
    }
    return true;
  };
  const SideFit left = fitSide(band, depth_m, 1.0);
  const SideFit right = fitSide(band, depth_m, -1.0);

  Eigen::Vector2d ab;
  if (left.ok && right.ok) {
    // Both sides planar: meeting at the segment (a crease, a painted edge) they are one
    // estimate twice; a step between them is an occluding edge, which the nearer side owns.
    int nearer_left = 0, nearer_right = 0;
    bool meet = true;
    for (double s : {s0, s1}) {
      double var_l = 0.0, var_r = 0.0;
      const double z_l = depthAt(left, s, var_l), z_r = depthAt(right, s, var_r);
      const double tolerance = 3.0 * std::sqrt(var_l + var_r) + kModelSlack * std::min(z_l, z_r);
      meet = meet && std::abs(z_l - z_r) <= tolerance;
      nearer_left += z_l < z_r;
      nearer_right += z_r < z_l;
    }
    if (meet) {
      const Eigen::Matrix2d i_l = left.covariance.inverse(), i_r = right.covariance.inverse();
      ab = (i_l + i_r).ldlt().solve(i_l * left.alpha_beta + i_r * right.alpha_beta);
    } else if (nearer_left == 2) {
      ab = left.alpha_beta;
    } else if (nearer_right == 2) {
      ab = right.alpha_beta;
    } else {
      return false;  // crossing surfaces: no owner
    }
  } else if (left.ok || right.ok) {
    // One side: it may be the far side of an occluding edge; only where it agrees with the fit.
    const SideFit& only = left.ok ? left : right;
    if (!agreesWithFit(only)) return false;
    ab = only.alpha_beta;
  } else {
    return false;
  }
  const double w0 = ab.x() + ab.y() * (s0 - s_mid), w1 = ab.x() + ab.y() * (s1 - s_mid);
  if (w0 <= 0.0 || w1 <= 0.0) return false;
  line.start = camera_.backProject(segment.start + s0 * d, 1.0 / w0);
  line.end = camera_.backProject(segment.start + s1 * d, 1.0 / w1);
  return true;
}

}  // namespace ply_slam
