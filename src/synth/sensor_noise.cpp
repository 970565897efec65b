#include "ply_slam/synth/sensor_noise.h"

#include <algorithm>
#include <cmath>
#include <opencv2/imgproc.hpp>

namespace ply_slam {

void SensorNoise::apply(RenderedFrame& frame, uint64_t seed) const {
  const SensorNoiseParams& p = params_;
  cv::RNG rng(seed * 6364136223846793005ULL + 1442695040888963407ULL);

  // Depth: holes first (on the exact depth), then noise on what is left.
  const cv::Mat exact = frame.depth.clone();
  cv::Mat gauss(exact.size(), CV_32FC1);
  rng.fill(gauss, cv::RNG::NORMAL, 0.0, 1.0);
  const int W = exact.cols, H = exact.rows;
  for (int y = 0; y < H; ++y) {
    const float* row = exact.ptr<float>(y);
    const float* up = exact.ptr<float>(std::max(y - 1, 0));
    const float* down = exact.ptr<float>(std::min(y + 1, H - 1));
    const float* g = gauss.ptr<float>(y);
    float* out = frame.depth.ptr<float>(y);
    for (int x = 0; x < W; ++x) {
      const double z = row[x];
      if (z < p.min_range || z > p.max_range) {
        out[x] = 0.0f;
        continue;
      }
      const double jump = p.edge_jump + p.edge_jump_per_metre * z;
      const double n[4] = {row[std::max(x - 1, 0)], row[std::min(x + 1, W - 1)], up[x], down[x]};
      bool edge = false;
      for (double zn : n) edge = edge || std::abs(zn - z) > jump;
      if (edge) {
        out[x] = 0.0f;
        continue;
      }
      out[x] = static_cast<float>(z + std::sqrt(p.depth.variance(z)) * g[x]);
    }
  }

  // Colour: optics blur, then sensor noise.
  cv::Mat blurred;
  cv::GaussianBlur(frame.rgb, blurred, cv::Size(5, 5), p.blur_sigma);
  cv::Mat noise(blurred.size(), CV_16SC3);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, p.rgb_sigma);
  cv::Mat rgb16;
  blurred.convertTo(rgb16, CV_16SC3);
  rgb16 += noise;
  rgb16.convertTo(frame.rgb, CV_8UC3);
}

}  // namespace ply_slam
