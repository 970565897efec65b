// PinholeCamera, DepthNoiseModel and MeasuredPointNoise: projection round trips, hand-computed
// values and the exact image borders, so that a swapped fx/fy, cx/cy or an off-by-one border fails.
#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/core.hpp>

#include "ply_slam/common/measured_point_noise.h"
#include "ply_slam/common/pinhole_camera.h"

namespace ply_slam {
namespace {

// TUM fr1 intrinsics; fx != fy and cx, cy off-centre so that swaps show.
PinholeCamera makeFr1Camera() {
  PinholeCamera camera;
  camera.fx = 517.3;
  camera.fy = 516.5;
  camera.cx = 318.6;
  camera.cy = 255.3;
  camera.width = 640;
  camera.height = 480;
  return camera;
}

TEST(PinholeCamera, ProjectOfBackProjectReturnsThePixelOverAGrid) {
  const PinholeCamera camera = makeFr1Camera();
  int checked = 0;
  // Includes pixels outside the image and sub-pixel positions: the model is unbounded.
  for (double u = -20.5; u <= 660.0; u += 37.25) {
    for (double v = -10.25; v <= 500.0; v += 29.5) {
      for (double z : {0.1, 0.5, 1.0, 2.7, 8.0, 25.0}) {
        const Eigen::Vector2d uv(u, v);
        const Eigen::Vector3d p = camera.backProject(uv, z);
        EXPECT_DOUBLE_EQ(p.z(), z);
        EXPECT_LT((camera.project(p) - uv).norm(), 1e-9) << "u " << u << " v " << v << " z " << z;
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 1000);
}

TEST(PinholeCamera, KnownProjectionAndBackProjection) {
  const PinholeCamera camera = makeFr1Camera();
  // The principal point is the optical axis at any depth.
  const Eigen::Vector3d axis = camera.backProject({318.6, 255.3}, 2.0);
  EXPECT_NEAR(axis.x(), 0.0, 1e-12);
  EXPECT_NEAR(axis.y(), 0.0, 1e-12);
  // (0.2, -0.1, 2) m: u = 517.3 * 0.1 + 318.6 = 370.33, v = 516.5 * -0.05 + 255.3 = 229.475.
  const Eigen::Vector2d uv = camera.project({0.2, -0.1, 2.0});
  EXPECT_NEAR(uv.x(), 370.33, 1e-9);
  EXPECT_NEAR(uv.y(), 229.475, 1e-9);
  // Pixel (0, 0) at 1 m: x = -318.6 / 517.3, y = -255.3 / 516.5.
  const Eigen::Vector3d corner = camera.backProject({0.0, 0.0}, 1.0);
  EXPECT_NEAR(corner.x(), -318.6 / 517.3, 1e-12);
  EXPECT_NEAR(corner.y(), -255.3 / 516.5, 1e-12);

  const cv::Matx33d K = camera.K();
  EXPECT_EQ(K(0, 0), 517.3);
  EXPECT_EQ(K(1, 1), 516.5);
  EXPECT_EQ(K(0, 2), 318.6);
  EXPECT_EQ(K(1, 2), 255.3);
  EXPECT_EQ(K(2, 2), 1.0);
  EXPECT_EQ(K(0, 1), 0.0);
  EXPECT_EQ(K(1, 0), 0.0);
}

TEST(DepthNoiseModel, VarianceIsTheQuadratic) {
  DepthNoiseModel model;
  // Default: the Kinect-class model of config/tum_fr1.yaml, 2.5e-5 Z^2 + 1e-5.
  EXPECT_NEAR(model.variance(3.0), 2.5e-5 * 9.0 + 1.0e-5, 1e-15);

  model.alpha = 6.25e-6;
  model.beta = 0.0;
  model.gamma = 1.0e-6;
  // Another set of coefficients: 6.25e-6 Z^2 + 1e-6.
  EXPECT_NEAR(model.variance(0.0), 1.0e-6, 1e-18);
  EXPECT_NEAR(model.variance(1.0), 7.25e-6, 1e-18);
  EXPECT_NEAR(model.variance(2.0), 26.0e-6, 1e-18);
  EXPECT_NEAR(model.variance(4.0), 101.0e-6, 1e-18);

  // Every term on its own, with distinct magnitudes so that a swapped term shows.
  model = DepthNoiseModel{2.0, 0.0, 0.0};
  EXPECT_DOUBLE_EQ(model.variance(3.0), 18.0);
  model = DepthNoiseModel{0.0, 5.0, 0.0};
  EXPECT_DOUBLE_EQ(model.variance(3.0), 15.0);
  model = DepthNoiseModel{0.0, 0.0, 7.0};
  EXPECT_DOUBLE_EQ(model.variance(3.0), 7.0);
  model = DepthNoiseModel{1e-3, 2e-3, 3e-4};
  EXPECT_NEAR(model.variance(1.5), 1e-3 * 2.25 + 2e-3 * 1.5 + 3e-4, 1e-15);
}

TEST(PinholeCamera, InImageBorders) {
  const PinholeCamera camera = makeFr1Camera();
  // Without a border: [0, width) x [0, height).
  EXPECT_TRUE(camera.inImage({0.0, 0.0}));
  EXPECT_TRUE(camera.inImage({639.999, 479.999}));
  EXPECT_FALSE(camera.inImage({640.0, 100.0}));
  EXPECT_FALSE(camera.inImage({100.0, 480.0}));
  EXPECT_FALSE(camera.inImage({-1e-6, 100.0}));
  EXPECT_FALSE(camera.inImage({100.0, -1e-6}));
  EXPECT_TRUE(camera.inImage({320.0, 240.0}));

  // With a 10 px border: [10, width - 10) x [10, height - 10).
  EXPECT_TRUE(camera.inImage({10.0, 10.0}, 10.0));
  EXPECT_FALSE(camera.inImage({9.999, 100.0}, 10.0));
  EXPECT_FALSE(camera.inImage({100.0, 9.999}, 10.0));
  EXPECT_TRUE(camera.inImage({629.999, 469.999}, 10.0));
  EXPECT_FALSE(camera.inImage({630.0, 100.0}, 10.0));
  EXPECT_FALSE(camera.inImage({100.0, 470.0}, 10.0));
}

TEST(PinholeCamera, ValidDepthIsTheClosedRange) {
  PinholeCamera camera = makeFr1Camera();
  camera.min_depth = 0.3;
  camera.max_depth = 6.0;
  EXPECT_TRUE(camera.validDepth(0.3));
  EXPECT_TRUE(camera.validDepth(6.0));
  EXPECT_TRUE(camera.validDepth(2.0));
  EXPECT_FALSE(camera.validDepth(0.299));
  EXPECT_FALSE(camera.validDepth(6.001));
  EXPECT_FALSE(camera.validDepth(0.0));
  EXPECT_FALSE(camera.validDepth(std::nan("")));
}

TEST(PinholeCamera, HasDistortion) {
  PinholeCamera camera = makeFr1Camera();
  EXPECT_FALSE(camera.hasDistortion());  // empty

  camera.distortion = cv::Mat::zeros(1, 5, CV_64F);
  EXPECT_FALSE(camera.hasDistortion());  // all zero: rectified

  for (int i = 0; i < 5; ++i) {
    camera.distortion = cv::Mat::zeros(1, 5, CV_64F);
    camera.distortion.at<double>(0, i) = 1e-4;
    EXPECT_TRUE(camera.hasDistortion()) << "coefficient " << i;
  }
  camera.distortion = (cv::Mat_<double>(1, 5) << 0.2624, -0.9531, -0.0054, 0.0026, 1.1633);
  EXPECT_TRUE(camera.hasDistortion());
  camera.distortion = (cv::Mat_<double>(1, 4) << 0.0, 0.0, 0.0, -0.01);
  EXPECT_TRUE(camera.hasDistortion());
}

// The variance along a direction, written out for speed, is the covariance's dᵀ Σ d.
TEST(MeasuredPointNoise, VarianceAlongIsTheCovarianceProjected) {
  const PinholeCamera camera = makeFr1Camera();
  const MeasuredPointNoise noise(camera, 1.5);
  for (const Eigen::Vector3d& p :
       {Eigen::Vector3d(0.3, -0.2, 1.2), Eigen::Vector3d(-1.0, 0.8, 4.5)})
    for (const Eigen::Vector3d& d :
         {Eigen::Vector3d(1, 0, 0), Eigen::Vector3d(0, 0, 1), Eigen::Vector3d(1, -2, 0.5)}) {
      const Eigen::Vector3d u = d.normalized();
      const double expected = u.dot(noise.covariance(p) * u);
      EXPECT_NEAR(noise.varianceAlong(p, u), expected, 1e-12 * expected) << p.transpose();
    }
}

// On a sloping surface the depth follows the pixel: Σ is J diag(σ², σ², σ_Z²) Jᵀ with J the
// derivative of P(u, v, ε) = backProject((u, v), Z0 + s·(u - u0, v - v0) + ε), by differences.
TEST(MeasuredPointNoise, ASlopeCarriesThePixelErrorIntoTheDepth) {
  const PinholeCamera camera = makeFr1Camera();
  const double sigma = 0.8;
  const MeasuredPointNoise noise(camera, sigma);
  const Eigen::Vector3d p(0.8, -0.3, 4.0);
  const Eigen::Vector2d uv0 = camera.project(p), slope(0.04, -0.01);
  auto point = [&](double u, double v, double e) {
    return camera.backProject(Eigen::Vector2d(u, v),
                              p.z() + slope.dot(Eigen::Vector2d(u, v) - uv0) + e);
  };
  const double h = 1e-4;
  Eigen::Matrix3d J;
  J.col(0) = (point(uv0.x() + h, uv0.y(), 0) - point(uv0.x() - h, uv0.y(), 0)) / (2 * h);
  J.col(1) = (point(uv0.x(), uv0.y() + h, 0) - point(uv0.x(), uv0.y() - h, 0)) / (2 * h);
  J.col(2) = (point(uv0.x(), uv0.y(), h) - point(uv0.x(), uv0.y(), -h)) / (2 * h);
  const Eigen::Vector3d lambda(sigma * sigma, sigma * sigma, camera.depth_noise.variance(p.z()));
  const Eigen::Matrix3d expected = J * lambda.asDiagonal() * J.transpose();
  EXPECT_LT((noise.covariance(p, slope) - expected).cwiseAbs().maxCoeff(), 1e-9);
  // Along the ray 4 cm per px adds more than the Kinect's own depth noise at 4 m (2 cm).
  const Eigen::Vector3d ray = p.normalized();
  EXPECT_NEAR(noise.varianceAlong(p, ray, slope), ray.dot(expected * ray), 1e-9);
  EXPECT_GT(noise.varianceAlong(p, ray, slope), 2 * noise.varianceAlong(p, ray));
}

}  // namespace
}  // namespace ply_slam
