#include "ply_slam/loop/vocabulary_identity.h"

#include <filesystem>

#include "ply_slam/loop/vocabulary_file.h"
#include "ply_slam/loop/vocabulary_path.h"

namespace ply_slam {

MapVocabulary vocabularyIdentity(const BinaryVocabulary& vocabulary, const std::string& path) {
  return {std::filesystem::path(path).filename().string(),
          VocabularyFile::checksum(vocabulary.data()), vocabulary.numWords()};
}

MapVocabulary configuredVocabularyIdentity(const std::string& configured, DescriptorKind kind) {
  const std::string path = vocabularyPath(configured, kind);
  return vocabularyIdentity(BinaryVocabulary::load(path, kind), path);
}

}  // namespace ply_slam
