#include "ply_slam/semantic/dynamic_classes.h"

#include <set>

namespace ply_slam {

bool isActiveDynamicClass(const std::string& class_name) {
  static const std::set<std::string> kActive = {
      "person", "bicycle", "car",   "motorcycle", "bus", "train",    "truck", "boat",  "bird",
      "cat",    "dog",     "horse", "sheep",      "cow", "elephant", "bear",  "zebra", "giraffe"};
  return kActive.count(class_name) > 0;
}

}  // namespace ply_slam
