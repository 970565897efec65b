#pragma once

// Where tests find the default vocabularies that scripts/setup.sh (ply_slam_vocabularies)
// trains after the build: build/vocabulary/{orb,lbd}_k10_l5.voc in the source tree.
#include <gtest/gtest.h>

#include <filesystem>

#include "ply_slam/loop/vocabulary_path.h"
#include "shared_data.h"

// Skips the test when the vocabulary file `path` is missing, with a message saying how to make
// it; fails instead under CI=true (scripts/test.sh always trains them first).
#define PLY_SLAM_REQUIRE_VOCABULARY(path)                                              \
  do {                                                                                 \
    if (!std::filesystem::exists(path)) {                                              \
      if (::ply_slam::test::underCi())                                                 \
        FAIL() << "CI=true but the vocabulary is missing: " << (path);                 \
      GTEST_SKIP() << "vocabulary missing: " << (path)                                 \
                   << " (train it: source scripts/setup.sh && ply_slam_vocabularies)"; \
    }                                                                                  \
  } while (0)
