#include "ply_slam/loop/vocabulary_path.h"

#include <filesystem>

namespace ply_slam {
namespace {

// The catkin workspace links the package into its source space: resolve the link so that
// paths point into the repository itself.
std::filesystem::path sourceDir() {
  return std::filesystem::weakly_canonical(std::filesystem::path(PLY_SLAM_SOURCE_DIR));
}

}  // namespace

std::string defaultVocabularyPath(DescriptorKind kind) {
  return (sourceDir() / "build" / "vocabulary" / (descriptorKindName(kind) + "_k10_l5.voc"))
      .string();
}

std::string vocabularyPath(const std::string& configured, DescriptorKind kind) {
  if (configured.empty()) return defaultVocabularyPath(kind);
  const std::filesystem::path path(configured);
  return path.is_absolute() ? configured : (sourceDir() / path).string();
}

}  // namespace ply_slam
