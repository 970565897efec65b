#include "ply_slam/synth/synthetic_sequence.h"

#include <stdexcept>

namespace ply_slam {
namespace {

constexpr double kFirstStamp = 1700000000.0;  // TUM-like epoch stamps

SynthOptions checked(const SynthOptions& o) {
  if (o.frames < 2) throw std::invalid_argument("frames must be >= 2");
  if (o.walkers < 0 || o.walkers >= Scene::kFirstObjectInstance)
    throw std::invalid_argument("walkers must be in 0.." +
                                std::to_string(Scene::kFirstObjectInstance - 1));
  if (!(o.fps > 0.0)) throw std::invalid_argument("fps must be > 0");
  return o;
}

}  // namespace

PinholeCamera syntheticCamera() {
  PinholeCamera c;
  c.fx = c.fy = 525.0;
  c.cx = 319.5;
  c.cy = 239.5;
  c.width = 640;
  c.height = 480;
  c.depth_factor = 5000.0;
  return c;
}

SyntheticSequence::SyntheticSequence(const SynthOptions& options)
    : options_(checked(options)),
      setup_(buildScene(options.scene, options.walkers, options.texture_dir)),
      path_(setup_.camera, options.frames, options.fps, options.loop, options.seed),
      caster_(syntheticCamera()) {}

double SyntheticSequence::stamp(int i) const { return kFirstStamp + time(i); }

RenderedFrame SyntheticSequence::renderExact(int i, bool with_walkers) const {
  const Scene& s = setup_.scene;
  return caster_.render(s, with_walkers ? s.quadsAt(time(i)) : s.staticQuads(), pose(i));
}

RenderedFrame SyntheticSequence::render(int i) const {
  RenderedFrame f = renderExact(i);
  if (options_.noise) noise_.apply(f, options_.seed * 1000003ULL + static_cast<uint64_t>(i));
  return f;
}

PinholeCamera SyntheticSequence::sensorCamera() const {
  PinholeCamera c = caster_.camera();
  const SensorNoiseParams& p = noise_.params();
  if (options_.noise) {
    c.min_depth = p.min_range;
    c.max_depth = p.max_range;
    c.depth_noise = p.depth;
  } else {
    // Exact depth, quantised to 1 / depth_factor and stored up to 65535 units.
    c.min_depth = 0.1;
    c.max_depth = 65535.0 / c.depth_factor;
    c.depth_noise = kExactDepthNoise;
  }
  return c;
}

}  // namespace ply_slam
