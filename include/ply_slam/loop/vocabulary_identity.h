#pragma once

#include <string>

#include "ply_slam/loop/binary_vocabulary.h"
#include "ply_slam/loop/descriptor_kind.h"
#include "ply_slam/map/map_file_contents.h"

namespace ply_slam {

// What a map file records of a vocabulary: the name of the file at `path` and what names its
// content (the checksum its file ends with, its number of words).
MapVocabulary vocabularyIdentity(const BinaryVocabulary& vocabulary, const std::string& path);
// The identity of the vocabulary a configured path names (vocabularyPath), read from its file
// for a system that does not use it otherwise. Throws std::runtime_error naming a missing or
// bad file.
MapVocabulary configuredVocabularyIdentity(const std::string& configured, DescriptorKind kind);

}  // namespace ply_slam
