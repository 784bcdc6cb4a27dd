// Keyframe clouds kept per place over long runs (common/keyframe_retention.h).
#include "tacs_graphs/common/keyframe_retention.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "tacs_graphs/common/config.h"

namespace tacs {
namespace {

// A keyframe every 0.5 m around a 20 m x 10 m rectangle (120 per lap), lap after lap.
Eigen::Vector3d lapPosition(uint32_t id) {
  const double s = std::fmod(0.5 * id, 60.0);
  if (s < 20.0) return {s, 0.0, 0.0};
  if (s < 30.0) return {20.0, s - 20.0, 0.0};
  if (s < 50.0) return {50.0 - s, 10.0, 0.0};
  return {0.0, 60.0 - s, 0.0};
}

struct LapRun {
  size_t kept_after_lap[6] = {};
  std::map<uint32_t, bool> released;
};

LapRun driveLaps(const KeyframeRetentionConfig& config, int laps) {
  KeyframeRetention retention(config);
  LapRun run;
  for (uint32_t id = 0; id < static_cast<uint32_t>(120 * laps); ++id) {
    if (const auto released = retention.add(id, lapPosition)) {
      EXPECT_LT(*released, id) << "only aged clouds are released";
      EXPECT_FALSE(run.released[*released]) << "released twice";
      run.released[*released] = true;
    }
    if ((id + 1) % 120 == 0) run.kept_after_lap[(id + 1) / 120] = retention.keptCount();
  }
  return run;
}

TEST(KeyframeRetention, KeepsEveryCloudOfTheFirstPass) {
  const LapRun run = driveLaps(KeyframeRetentionConfig(), 1);
  EXPECT_TRUE(run.released.empty());
  EXPECT_EQ(run.kept_after_lap[1], 120u);
}

TEST(KeyframeRetention, StopsGrowingOnceThePlacesHoldEnoughClouds) {
  const KeyframeRetentionConfig config;  // 8 clouds within 1 m: about two passes at 0.5 m spacing
  const LapRun run = driveLaps(config, 5);
  // Laps 3-5 add keyframes at places that hold two passes already: the count stays flat.
  EXPECT_GT(run.kept_after_lap[2], 200u);
  EXPECT_LE(run.kept_after_lap[5], run.kept_after_lap[3] + 1);
  EXPECT_LE(run.kept_after_lap[5], 2 * 120u + config.min_age_keyframes + 5);
  // The first lap's clouds anchor the places: none of them is released.
  for (const auto& [id, released] : run.released) EXPECT_GE(id, 120u);
}

TEST(KeyframeRetention, ZeroKeepsEveryCloud) {
  KeyframeRetentionConfig config;
  config.max_keyframes_per_place = 0;
  const LapRun run = driveLaps(config, 3);
  EXPECT_TRUE(run.released.empty());
  EXPECT_EQ(run.kept_after_lap[3], 360u);
}

TEST(KeyframeRetention, RejectsBadSettingsNamingTheKey) {
  KeyframeRetentionConfig config;
  config.place_radius_m = 0.0;
  try {
    config.validate("map_export.cloud_retention.");
    FAIL() << "no error";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("map_export.cloud_retention.place_radius_m"),
              std::string::npos);
  }
}

}  // namespace
}  // namespace tacs
