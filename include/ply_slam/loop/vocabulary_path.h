#pragma once

#include <string>

#include "ply_slam/loop/descriptor_kind.h"

namespace ply_slam {

// The default vocabulary of a kind: build/vocabulary/<kind>_k10_l5.voc in the package source
// folder, where scripts/setup.sh (ply_slam_vocabularies) trains it after every build.
std::string defaultVocabularyPath(DescriptorKind kind);

// The file a configured vocabulary path (loop.orb_vocabulary / loop.lbd_vocabulary) names:
// "" = the default; a relative path from the package source folder (configs travel with the
// package, not with the folder a tool is started in); an absolute path as it is.
std::string vocabularyPath(const std::string& configured, DescriptorKind kind);

}  // namespace ply_slam
