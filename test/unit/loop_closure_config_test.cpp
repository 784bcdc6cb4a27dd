// Validation of the loop_closure configuration section.
#include <gtest/gtest.h>

#include <string>

#include "tacs_graphs/common/config.h"
#include "tacs_graphs/loop_closure/loop_detector.h"
#include "tacs_graphs/pipeline/pipeline_config.h"

namespace tacs {
namespace {

// The ConfigError message of validate(), or "" when valid.
std::string errorOf(const LoopClosureConfig& c) {
  try {
    c.validate();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(LoopClosureConfig, DefaultsFollowThePaper) {
  const LoopClosureConfig c;
  EXPECT_EQ(errorOf(c), "");
  EXPECT_EQ(c.method, LoopMethod::kCosg);
  EXPECT_DOUBLE_EQ(c.cosg.d_loop_m, 5.0);  // d_th^loop of Sec. III-D
  EXPECT_LT(c.cosg.s_fine, c.cosg.s_coarse);
  EXPECT_DOUBLE_EQ(c.distance.distance_threshold_m, 3.0);
}

TEST(LoopClosureConfig, InvalidValuesNameTheField) {
  auto expectError = [](const LoopClosureConfig& c, const std::string& field) {
    const std::string error = errorOf(c);
    EXPECT_NE(error.find(field), std::string::npos) << "got: '" << error << "'";
  };
  LoopClosureConfig c;
  c.cosg.s_fine = 0.9;  // above s_coarse: not a relaxation
  expectError(c, "loop_closure.cosg.s_fine");
  c = LoopClosureConfig();
  c.cosg.fine_correspondence_schedule_m.clear();
  expectError(c, "loop_closure.cosg.fine_correspondence_schedule_m");
  c = LoopClosureConfig();
  c.cosg.d_loop_m = 0.0;
  expectError(c, "loop_closure.cosg.d_loop_m");
  c = LoopClosureConfig();
  c.distance.fitness_threshold = -1.0;
  expectError(c, "loop_closure.distance.fitness_threshold_m2");
  c = LoopClosureConfig();
  c.registration.tilt_information_scale = 0.0;  // a singular information
  expectError(c, "loop_closure.registration.tilt_information_scale");
  c = LoopClosureConfig();
  c.registration.submap_length_m = -1.0;
  expectError(c, "loop_closure.registration.submap_length_m");
  c = LoopClosureConfig();
  c.registration.submap_voxel_m = 0.0;
  expectError(c, "loop_closure.registration.submap_voxel_m");
  c = LoopClosureConfig();
  c.registration.score_max_normal_z = 1.5;
  expectError(c, "loop_closure.registration.score_max_normal_z");
  EXPECT_THROW(LoopDetector{c}, ConfigError);
}

TEST(LoopClosureConfig, IsReadFromThePipelineSection) {
  const nlohmann::json j = {
      {"loop_closure",
       {{"method", "distance"},
        {"distance", {{"distance_threshold_m", 1.0}}},
        {"cosg", {{"fine_correspondence_schedule_m", {3.0, 1.0}}, {"s_coarse", 0.8}}}}}};
  PipelineConfig config;
  std::vector<std::string> unknown;
  configFromJson(j, "test", &config, &unknown);
  EXPECT_TRUE(unknown.empty());
  EXPECT_EQ(config.loop_closure.method, LoopMethod::kDistance);
  EXPECT_DOUBLE_EQ(config.loop_closure.distance.distance_threshold_m, 1.0);
  EXPECT_EQ(config.loop_closure.cosg.fine_correspondence_schedule_m,
            (std::vector<double>{3.0, 1.0}));
  EXPECT_DOUBLE_EQ(config.loop_closure.cosg.s_coarse, 0.8);
  const nlohmann::json bad = {{"loop_closure", {{"cosg", {{"s_coarse", 0.1}}}}}};
  try {
    configFromJson(bad, "test", &config, &unknown);
    FAIL() << "s_fine above s_coarse must be rejected";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("loop_closure.cosg.s_fine"), std::string::npos);
  }
}

}  // namespace
}  // namespace tacs
