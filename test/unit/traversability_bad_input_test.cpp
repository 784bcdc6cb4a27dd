// TraversabilityMapper on bad input: empty scans, scans without ground, a tilted sensor, NaNs.
#include <gtest/gtest.h>

#include <limits>

#include "common/traversability_scene.h"

namespace tacs {
namespace {

TEST(TraversabilityBadInput, EmptyScan) {
  const TraversabilityResult r = TraversabilityMapper(TraversabilityConfig{}).process(PointCloud{});
  EXPECT_NE(r.warning.find("empty scan"), std::string::npos) << r.warning;
  EXPECT_TRUE(r.graph.nodes.empty());
  EXPECT_EQ(r.graph.root, -1);
  EXPECT_EQ(r.ground_points + r.nonground_points, 0u);
  ASSERT_TRUE(r.ground && r.obstacles);
}

TEST(TraversabilityBadInput, NonFinitePointsOnly) {
  PointCloud cloud;
  pcl::PointXYZI p;
  p.x = std::numeric_limits<float>::quiet_NaN();
  p.y = p.z = 1.0f;
  cloud.push_back(p);
  p.x = std::numeric_limits<float>::infinity();
  cloud.push_back(p);
  const TraversabilityResult r = TraversabilityMapper(TraversabilityConfig{}).process(cloud);
  EXPECT_NE(r.warning.find("empty scan"), std::string::npos) << r.warning;
}

TEST(TraversabilityBadInput, NoGround) {
  // A room without a floor (the robot over a void): walls and a ceiling only.
  test::Scene scene;
  scene.add(-4, -3, 2.7, 6, 3, 2.8, false);
  scene.add(-4.15, -3, -3, -4, 3, 2.7, false);
  scene.add(6, -3, -3, 6.15, 3, 2.7, false);
  scene.add(-4, -3.15, -3, 6, -3, 2.7, false);
  scene.add(-4, 3, -3, 6, 3.15, 2.7, false);
  const test::ScanRun run = test::runAt(scene, 0.0, 0.0, 0.0);
  const TraversabilityResult& r = run.result;
  EXPECT_NE(r.warning.find("no traversable ground under the robot"), std::string::npos)
      << r.warning;
  EXPECT_EQ(r.graph.root, -1);
  EXPECT_EQ(r.graph.countTraversable(), 0u);
  EXPECT_TRUE(r.graph.edges.empty());
  EXPECT_GT(r.obstacles->size(), 0u);
}

TEST(TraversabilityBadInput, TiltedSensorIsReported) {
  // The base frame rolled by 10 deg: the scan is not gravity-aligned.
  const test::ScanRun run = test::runAt(test::testScene(), 2.5, 1.5, 0.0, 10.0 * M_PI / 180.0);
  EXPECT_NE(run.result.warning.find("tilts"), std::string::npos) << run.result.warning;
  // A level scan of the same place does not warn.
  const test::ScanRun level = test::runAt(test::testScene(), 2.5, 1.5, 0.0);
  EXPECT_TRUE(level.result.warning.empty()) << level.result.warning;
}

}  // namespace
}  // namespace tacs
