#pragma once

#include <Eigen/Core>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "ply_slam/synth/lighting.h"
#include "ply_slam/synth/quad.h"
#include "ply_slam/synth/segment3.h"
#include "ply_slam/synth/texture.h"
#include "ply_slam/synth/walker.h"

namespace ply_slam {

// Everything the ray caster draws: textures, static quads, walkers, and the ground truth
// that comes with them (the static 3D line segments and the instance classes).
class Scene {
 public:
  explicit Scene(std::string name = "") : name_(std::move(name)) {}

  const std::string& name() const { return name_; }
  const Lighting& lighting() const { return lighting_; }
  // The room's inner walls (axis-aligned).
  void setBounds(const Eigen::Vector3d& min, const Eigen::Vector3d& max);
  const Eigen::Vector3d& boundsMin() const { return bounds_min_; }
  const Eigen::Vector3d& boundsMax() const { return bounds_max_; }

  int addTexture(const Texture& texture);
  void addQuad(const Quad& quad) { quads_.push_back(quad); }
  void addQuads(const std::vector<Quad>& quads);
  void addLine(const Segment3& line) { lines_.push_back(line); }
  void addLines(const std::vector<Segment3>& lines);
  void addWalker(const Walker& walker) { walkers_.push_back(walker); }
  // Makes the static quads from index `first_quad` on one object of a COCO class: they get a new
  // instance id (from kFirstObjectInstance up), so the masks and instances.txt hold the object as
  // a segmenter would report it. Returns the id.
  int labelObject(std::size_t first_quad, const std::string& class_name);

  const std::vector<Texture>& textures() const { return textures_; }
  const std::vector<Quad>& staticQuads() const { return quads_; }
  const std::vector<Segment3>& lines() const { return lines_; }
  const std::vector<Walker>& walkers() const { return walkers_; }
  const std::map<int, std::string>& objectClasses() const { return object_classes_; }
  // Walkers take ids 1..kFirstObjectInstance-1, the labelled static objects the ids above.
  static constexpr int kFirstObjectInstance = 101;
  // Static quads followed by every walker's quads at time t (s).
  std::vector<Quad> quadsAt(double t) const;

 private:
  std::string name_;
  Lighting lighting_;
  Eigen::Vector3d bounds_min_ = Eigen::Vector3d::Zero();
  Eigen::Vector3d bounds_max_ = Eigen::Vector3d::Zero();
  std::vector<Texture> textures_;
  std::vector<Quad> quads_;
  std::vector<Segment3> lines_;
  std::vector<Walker> walkers_;
  std::map<int, std::string> object_classes_;
};

}  // namespace ply_slam
