#include "ply_slam/synth/scene.h"

#include <stdexcept>

namespace ply_slam {

void Scene::setBounds(const Eigen::Vector3d& min, const Eigen::Vector3d& max) {
  bounds_min_ = min;
  bounds_max_ = max;
}

int Scene::addTexture(const Texture& texture) {
  textures_.push_back(texture);
  return static_cast<int>(textures_.size()) - 1;
}

void Scene::addQuads(const std::vector<Quad>& quads) {
  quads_.insert(quads_.end(), quads.begin(), quads.end());
}

void Scene::addLines(const std::vector<Segment3>& lines) {
  lines_.insert(lines_.end(), lines.begin(), lines.end());
}

int Scene::labelObject(std::size_t first_quad, const std::string& class_name) {
  const int id = kFirstObjectInstance + static_cast<int>(object_classes_.size());
  if (id > 255) throw std::length_error("more labelled objects than 8-bit masks can hold");
  for (std::size_t k = first_quad; k < quads_.size(); ++k) quads_[k].instance = id;
  object_classes_[id] = class_name;
  return id;
}

std::vector<Quad> Scene::quadsAt(double t) const {
  std::vector<Quad> quads = quads_;
  for (const Walker& w : walkers_) {
    const std::vector<Quad> body = w.quads(t);
    quads.insert(quads.end(), body.begin(), body.end());
  }
  return quads;
}

}  // namespace ply_slam
