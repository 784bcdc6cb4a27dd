// Dominant axes of the building and the x+/x-/y+/y- classification of walls.
#include <gtest/gtest.h>

#include <cmath>

#include "common/synthetic_walls.h"
#include "tacs_graphs/walls/dominant_axes.h"
#include "tacs_graphs/walls/wall_extractor.h"

namespace tacs {
namespace {

constexpr double kDeg = M_PI / 180.0;

Eigen::Vector3d horizontalNormal(double angle) { return {std::cos(angle), std::sin(angle), 0}; }

TEST(DominantAxes, RecoveredAtThirtyDegreesFromExtractedWalls) {
  test::SyntheticScene scene;
  scene.boxRoom(-3.0, 5.0, -2.0, 4.0, -0.8, 1.8);
  scene.wall({-2.0, 1.0}, {-1.0, 2.0}, -0.8, 1.8);  // a short diagonal full-height partition
  scene.transform(poseFromXyzRpy(0, 0, 0, 0, 0, 30 * kDeg));
  const auto walls = WallExtractor(WallExtractionConfig{}).extract(scene.cloud).walls;
  ASSERT_GE(walls.size(), 4u);
  const DominantAxes axes = estimateDominantAxes(walls);
  EXPECT_TRUE(axes.valid);
  EXPECT_NEAR(axes.yaw, 30 * kDeg, 0.5 * kDeg);
  EXPECT_GT(axes.agreement, 0.9);
  EXPECT_LT(axes.agreement, 1.0);  // the diagonal face does not agree

  // Rotated back into the building frame, the room walls are x+/x-/y+/y- as if aligned.
  int counts[4] = {0, 0, 0, 0};
  for (const auto& w : walls) {
    if (w.length() > 5.0) ++counts[static_cast<int>(classifyWall(w.normal, axes))];
  }
  for (int c : counts) EXPECT_EQ(c, 1);
  // Wall x = -3 of the room faces +x (towards the sensor inside the room).
  EXPECT_EQ(classifyWall(horizontalNormal(30 * kDeg), axes), WallDirection::kXPlus);
  EXPECT_EQ(classifyWall(horizontalNormal(210 * kDeg), axes), WallDirection::kXMinus);
  EXPECT_EQ(classifyWall(horizontalNormal(120 * kDeg), axes), WallDirection::kYPlus);
  EXPECT_EQ(classifyWall(horizontalNormal(-60 * kDeg), axes), WallDirection::kYMinus);
}

TEST(DominantAxes, FoldsAnglesModuloNinetyDegreesAndWrapsAtFortyFive) {
  // Normals at 44 and -46 deg (= 44 mod 90) with noise around them: yaw near +-45 either way.
  std::vector<Eigen::Vector3d> normals = {horizontalNormal(44.5 * kDeg),
                                          horizontalNormal(-45.5 * kDeg),
                                          horizontalNormal(134.5 * kDeg)};
  const DominantAxes axes = estimateDominantAxes(normals, {4.0, 4.0, 4.0});
  ASSERT_TRUE(axes.valid);
  EXPECT_NEAR(std::abs(axes.yaw), 45 * kDeg, 1 * kDeg);
  EXPECT_NEAR(axes.agreement, 1.0, 1e-9);
  // -60 deg is the same set of axes as +30 deg.
  const DominantAxes a = estimateDominantAxes({horizontalNormal(-60 * kDeg)}, {5.0});
  EXPECT_NEAR(a.yaw, 30 * kDeg, 1e-6);
}

TEST(DominantAxes, InvalidWithTooLittleWallAndIgnoresHorizontalPlanes) {
  const DominantAxes a = estimateDominantAxes({horizontalNormal(20 * kDeg)}, {1.0});
  EXPECT_FALSE(a.valid);
  EXPECT_EQ(a.yaw, 0.0);
  const DominantAxes b = estimateDominantAxes({Eigen::Vector3d::UnitZ()}, {50.0});
  EXPECT_FALSE(b.valid);
  EXPECT_EQ(b.support, 0.0);
  // Without axes (yaw 0) classification follows the frame's own axes.
  EXPECT_EQ(classifyWall({-0.9, 0.3, 0}, a), WallDirection::kXMinus);
  EXPECT_STREQ(toString(WallDirection::kYPlus), "y+");
}

TEST(DominantAxes, LongWallsOutweighManyShortOnes) {
  std::vector<Eigen::Vector3d> normals;
  std::vector<double> weights;
  for (int i = 0; i < 6; ++i) {  // 6 short walls at 10 deg, 0.5 m each
    normals.push_back(horizontalNormal(10 * kDeg));
    weights.push_back(0.5);
  }
  normals.push_back(horizontalNormal(-20 * kDeg));  // two long walls at -20 / 70 deg
  weights.push_back(8.0);
  normals.push_back(horizontalNormal(70 * kDeg));
  weights.push_back(6.0);
  const DominantAxes axes = estimateDominantAxes(normals, weights);
  EXPECT_NEAR(axes.yaw, -20 * kDeg, 0.5 * kDeg);
  EXPECT_NEAR(axes.support, 14.0, 1e-9);
}

}  // namespace
}  // namespace tacs
