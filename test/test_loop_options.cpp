// The loop: section reader: defaults when absent, values read, and every bad key (unknown,
// wrong type, out of range) rejected with an error that names it.
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <stdexcept>
#include <string>

#include "ply_slam/loop/loop_options_yaml.h"

namespace ply_slam {
namespace {

// The message of the std::runtime_error that reading `text` throws ("" when none).
std::string errorOf(const std::string& text) {
  try {
    loopOptionsFromYaml(YAML::Load(text));
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(LoopOptionsYaml, AbsentSectionGivesDefaults) {
  const LoopOptions options = loopOptionsFromYaml(YAML::Node());
  EXPECT_DOUBLE_EQ(options.sure_position, 0.95);
  EXPECT_DOUBLE_EQ(options.position_weight, 0.6);
  EXPECT_DOUBLE_EQ(options.point_line_weight, 0.6);
  EXPECT_EQ(options.consistency, 3);
  EXPECT_EQ(options.dynamic_classes.front(), "person");
  EXPECT_DOUBLE_EQ(loopOptionsFromYaml(YAML::Load("~")).iou_epsilon, 1e-6);
}

TEST(LoopOptionsYaml, ReadsValues) {
  const LoopOptions options = loopOptionsFromYaml(
      YAML::Load("{spatial_consistency_threshold: 0.8, min_normalised_score: 0.45, consistency: 4,"
                 " ransac_iterations: 500, ransac_seed: 7, reprojection_px: 3.5,"
                 " dynamic_classes: [person, dog]}"));
  EXPECT_DOUBLE_EQ(options.spatial_consistency_threshold, 0.8);
  EXPECT_DOUBLE_EQ(options.min_normalised_score, 0.45);
  EXPECT_EQ(options.consistency, 4);
  EXPECT_EQ(options.ransac_iterations, 500);
  EXPECT_EQ(options.ransac_seed, 7u);
  EXPECT_DOUBLE_EQ(options.reprojection_px, 3.5);
  EXPECT_EQ(options.dynamic_classes, (std::vector<std::string>{"person", "dog"}));
}

TEST(LoopOptionsYaml, BadKeysAreNamed) {
  EXPECT_NE(errorOf("{sure_positon: 0.9}").find("loop.sure_positon is not a known key"),
            std::string::npos);
  EXPECT_NE(errorOf("{sure_position: 1.5}").find("loop.sure_position must lie in"),
            std::string::npos);
  EXPECT_NE(errorOf("{consistency: 0}").find("loop.consistency"), std::string::npos);
  EXPECT_NE(errorOf("{ransac_iterations: many}").find("loop.ransac_iterations has the wrong type"),
            std::string::npos);
  EXPECT_NE(errorOf("{dynamic_classes: person}").find("loop.dynamic_classes"), std::string::npos);
  EXPECT_NE(errorOf("{dyna_floor: 0.7}").find("loop.dyna_floor"), std::string::npos);
  EXPECT_NE(errorOf("[1, 2]").find("loop"), std::string::npos);
}

}  // namespace
}  // namespace ply_slam
