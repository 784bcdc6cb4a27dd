// Wall extraction on synthetic rooms: planes, extents, gap splitting, horizontal planes.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "common/synthetic_walls.h"
#include "tacs_graphs/common/config.h"
#include "tacs_graphs/pipeline/pipeline_config.h"
#include "tacs_graphs/walls/wall_extractor.h"

namespace tacs {
namespace {

constexpr double kDeg = M_PI / 180.0;

// The walls whose plane matches (normal within 3 deg, d within 5 cm).
std::vector<WallSegment> matching(const std::vector<WallSegment>& walls,
                                  const Eigen::Vector3d& normal, double d) {
  std::vector<WallSegment> out;
  for (const auto& w : walls) {
    if (w.normal.dot(normal) > std::cos(3 * kDeg) && std::abs(w.d - d) < 0.05) out.push_back(w);
  }
  return out;
}

// True if the segment covers [a, b] up to `tol` at both ends (in either order).
bool spans(const WallSegment& w, const Eigen::Vector2d& a, const Eigen::Vector2d& b, double tol) {
  const bool same = (w.endpoints[0] - a).norm() < tol && (w.endpoints[1] - b).norm() < tol;
  const bool swapped = (w.endpoints[0] - b).norm() < tol && (w.endpoints[1] - a).norm() < tol;
  return same || swapped;
}

// Box room x in [-3, 5], y in [-2, 4], floor z = -0.8, ceiling z = 1.8, sensor at the origin.
test::SyntheticScene boxRoomScene() {
  test::SyntheticScene scene;
  scene.boxRoom(-3.0, 5.0, -2.0, 4.0, -0.8, 1.8);
  return scene;
}

TEST(WallExtraction, BoxRoomWallsHavePlanesFacingTheSensorAndTheirExtents) {
  const auto scene = boxRoomScene();
  const WallExtractor extractor{WallExtractionConfig{}};
  const auto result = extractor.extract(scene.cloud);
  EXPECT_EQ(result.input_points, scene.cloud.size());
  ASSERT_EQ(result.walls.size(), 4u);
  struct Expected {
    Eigen::Vector3d n;
    double d;
    Eigen::Vector2d a, b;
  };
  const Expected expected[] = {{{1, 0, 0}, 3.0, {-3, -2}, {-3, 4}},
                               {{-1, 0, 0}, 5.0, {5, -2}, {5, 4}},
                               {{0, 1, 0}, 2.0, {-3, -2}, {5, -2}},
                               {{0, -1, 0}, 4.0, {-3, 4}, {5, 4}}};
  for (const auto& e : expected) {
    SCOPED_TRACE(e.n.transpose());
    const auto found = matching(result.walls, e.n, e.d);
    ASSERT_EQ(found.size(), 1u);
    EXPECT_GE(found[0].d, 0.0);
    EXPECT_NEAR(found[0].normal.norm(), 1.0, 1e-9);
    EXPECT_TRUE(spans(found[0], e.a, e.b, 0.2))
        << found[0].endpoints[0].transpose() << " / " << found[0].endpoints[1].transpose();
    EXPECT_NEAR(found[0].z_min, -0.8, 0.15);
    EXPECT_NEAR(found[0].z_max, 1.8, 0.15);
    EXPECT_GT(found[0].inliers, 500u);
    // Endpoints are ordered along the wall axis z x n.
    EXPECT_GT(wallAxis(found[0].normal).dot(found[0].endpoints[1] - found[0].endpoints[0]), 0.0);
  }
}

TEST(WallExtraction, FloorAndCeilingAreReportedAsHorizontal) {
  const auto scene = boxRoomScene();
  const auto result = WallExtractor(WallExtractionConfig{}).extract(scene.cloud);
  ASSERT_GE(result.horizontal.size(), 2u);
  const auto floor = matching(result.horizontal, {0, 0, 1}, 0.8);
  const auto ceiling = matching(result.horizontal, {0, 0, -1}, 1.8);
  ASSERT_EQ(floor.size(), 1u);
  ASSERT_EQ(ceiling.size(), 1u);
  EXPECT_NEAR(floor[0].endpoints[0].x(), -3.0, 0.15);
  EXPECT_NEAR(floor[0].endpoints[1].y(), 4.0, 0.15);
  for (const auto& w : result.walls) EXPECT_LT(std::abs(w.normal.z()), 0.1);
}

TEST(WallExtraction, CollinearWallsFiveMetresApartAreSeparateSegments) {
  test::SyntheticScene scene;
  scene.wall({-7, 3}, {-1, 3}, -0.8, 1.5);
  scene.wall({4, 3}, {9, 3}, -0.8, 1.5);
  scene.slab(-7, 9, -3, 3, -0.8);
  WallExtractionConfig cfg;
  const auto result = WallExtractor(cfg).extract(scene.cloud);
  const auto found = matching(result.walls, {0, -1, 0}, 3.0);
  ASSERT_EQ(found.size(), 2u);
  const bool first_left = found[0].midpoint().x() < found[1].midpoint().x();
  const WallSegment& left = first_left ? found[0] : found[1];
  const WallSegment& right = first_left ? found[1] : found[0];
  EXPECT_TRUE(spans(left, {-7, 3}, {-1, 3}, 0.2));
  EXPECT_TRUE(spans(right, {4, 3}, {9, 3}, 0.2));
  // With a max_gap larger than the gap, the two become one segment.
  cfg.max_gap = 6.0;
  const auto joined = matching(WallExtractor(cfg).extract(scene.cloud).walls, {0, -1, 0}, 3.0);
  ASSERT_EQ(joined.size(), 1u);
  EXPECT_NEAR(joined[0].length(), 16.0, 0.3);
}

TEST(WallExtraction, TwoRoomsWithADoorGiveTwoSegmentsOnTheDoorWall) {
  test::SyntheticScene scene;
  scene.twoRoomsWithDoor();
  // Sensor in the left room at (2, 2.5, 0.6): express the cloud relative to it.
  scene.transform(poseFromXyzRpy(-2.0, -2.5, -0.6, 0, 0, 0));
  const auto result = WallExtractor(WallExtractionConfig{}).extract(scene.cloud);
  const auto door_wall = matching(result.walls, {-1, 0, 0}, 3.0);
  ASSERT_EQ(door_wall.size(), 2u);
  double covered = 0.0;
  for (const auto& w : door_wall) covered += w.length();
  EXPECT_NEAR(covered, 3.0, 0.3);  // 1 m + 2 m, the door is left out
}

TEST(WallExtraction, FloorAndCeilingLinesDoNotBridgeADoorway) {
  // A wall y = 3 with a 1.2 m doorway at x 0..1.2, and strips of floor and ceiling along its
  // line (as a LiDAR sees them through the doorway when the rest of the floor is out of view):
  // those strips are inliers of the wall's plane and would join the pieces on both sides.
  test::SyntheticScene scene;
  scene.wall({-6, 3}, {0, 3}, -0.8, 2.0);
  scene.wall({1.2, 3}, {7, 3}, -0.8, 2.0);
  scene.slab(-6, 7, 2.95, 3.05, -0.8);
  scene.slab(-6, 7, 2.95, 3.05, 2.0);
  WallExtractionConfig cfg;
  const auto pieces = matching(WallExtractor(cfg).extract(scene.cloud).walls, {0, -1, 0}, 3.0);
  ASSERT_EQ(pieces.size(), 2u);
  for (const auto& w : pieces) {
    const double near_end = w.midpoint().x() < 0.6
                                ? std::max(w.endpoints[0].x(), w.endpoints[1].x())
                                : std::min(w.endpoints[0].x(), w.endpoints[1].x());
    EXPECT_NEAR(near_end, w.midpoint().x() < 0.6 ? 0.0 : 1.2, 0.1);  // the doorway stays open
  }
  cfg.edge_band = 0.0;  // every inlier bridges: one segment across the doorway
  const auto joined = matching(WallExtractor(cfg).extract(scene.cloud).walls, {0, -1, 0}, 3.0);
  ASSERT_EQ(joined.size(), 1u);
  EXPECT_NEAR(joined[0].length(), 13.0, 0.3);
}

// Keeps the points seen below `max_elevation_deg` from the origin, as a LiDAR's upper beam does.
void cropAboveElevation(PointCloud* cloud, double max_elevation_deg) {
  PointCloud kept;
  for (const auto& p : cloud->points) {
    if (std::atan2(p.z, std::hypot(p.x, p.y)) <= max_elevation_deg * kDeg) kept.push_back(p);
  }
  *cloud = kept;
}

TEST(WallExtraction, LowSurfacesTheBeamsPassedOverAreNoWalls) {
  // A cabinet face 2 m in front of the sensor, 0.8 m tall (its top level with the sensor): the
  // beams above it reach the room's walls, so it is furniture.
  auto scene = boxRoomScene();
  scene.wall({2, -1}, {2, 1.5}, -0.8, 0.0);
  cropAboveElevation(&scene.cloud, 15.0);  // a VLP-16's upper beam
  WallExtractionConfig cfg;
  const auto result = WallExtractor(cfg).extract(scene.cloud);
  EXPECT_TRUE(matching(result.walls, {-1, 0, 0}, 2.0).empty());
  EXPECT_EQ(matching(result.seen_over, {-1, 0, 0}, 2.0).size(), 1u);  // reported apart
  // The room's walls stay although their tops are cut by the field of view (at 3 m the upper
  // beam meets the wall 0.8 m above the sensor, below min_wall_top).
  EXPECT_EQ(matching(result.walls, {1, 0, 0}, 3.0).size(), 1u);
  EXPECT_EQ(matching(result.walls, {0, 1, 0}, 2.0).size(), 1u);
  EXPECT_EQ(matching(result.walls, {0, -1, 0}, 4.0).size(), 1u);
  // Without the test (and the seen-over test, which the rays over the cabinet also pass) the
  // cabinet is a wall.
  cfg.min_wall_top = 0.0;
  cfg.seen_over_min_points = 0;
  EXPECT_EQ(matching(WallExtractor(cfg).extract(scene.cloud).walls, {-1, 0, 0}, 2.0).size(), 1u);
}

TEST(WallExtraction, ACabinetInFrontOfAWallIsSeenOver) {
  // A cabinet face at x = 4.5 that stands on the floor and reaches 1.2 m above the sensor (above
  // min_wall_top), 0.5 m in front of the room's wall x = 5: rays over it reach the wall behind.
  auto scene = boxRoomScene();
  scene.wall({4.5, -1.5}, {4.5, 1.0}, -0.8, 1.2);
  WallExtractionConfig cfg;
  const auto result = WallExtractor(cfg).extract(scene.cloud);
  EXPECT_TRUE(matching(result.walls, {-1, 0, 0}, 4.5).empty());
  EXPECT_EQ(matching(result.seen_over, {-1, 0, 0}, 4.5).size(), 1u);
  EXPECT_EQ(matching(result.walls, {-1, 0, 0}, 5.0).size(), 1u);  // the wall behind stays
  EXPECT_TRUE(matching(result.seen_over, {-1, 0, 0}, 5.0).empty());
  EXPECT_EQ(matching(result.walls, {1, 0, 0}, 3.0).size(), 1u);
  // The wall behind spans it, so the on-wall test drops it as well; without both it is a wall.
  cfg.seen_over_min_points = 0;
  EXPECT_TRUE(matching(WallExtractor(cfg).extract(scene.cloud).walls, {-1, 0, 0}, 4.5).empty());
  cfg.on_wall_max_depth = 0.0;
  EXPECT_EQ(matching(WallExtractor(cfg).extract(scene.cloud).walls, {-1, 0, 0}, 4.5).size(), 1u);
}

TEST(WallExtraction, AWallUnderWallCabinetsIsNotSeenOver) {
  // Wall cabinets 0.45 m deep hang on the wall x = 5 from 0.5 m below the sensor upwards: the
  // wall below them tops out low, but the rays above it end on the cabinets, so it is neither a
  // wall of this scan nor a surface seen over (which would mark the wall for good).
  test::SyntheticScene scene;
  scene.wall({5, -2}, {5, 4}, -0.8, -0.5);
  scene.wall({4.55, -2}, {4.55, 4}, -0.5, 0.3);  // cabinet fronts
  scene.slab(-1, 5, -2, 4, -0.8);
  cropAboveElevation(&scene.cloud, 15.0);
  const auto result = WallExtractor(WallExtractionConfig{}).extract(scene.cloud);
  EXPECT_TRUE(matching(result.walls, {-1, 0, 0}, 5.0).empty());
  EXPECT_TRUE(matching(result.seen_over, {-1, 0, 0}, 5.0).empty());
}

TEST(WallExtraction, ABeamHangingFromTheCeilingIsNoWallForASensorCarriedHigh) {
  // A hall seen from 2 m above its floor (z = -2): a beam face y = 3 hangs from the ceiling
  // (z 3.5..4.5) and runs into the wall x = 4.5. Its plane also takes in the floor along its line,
  // the strip where it crosses that wall and a few stray returns between: none of them is its
  // face, so its bottom stays 3.5 m above the sensor.
  test::SyntheticScene scene;
  scene.boxRoom(-6, 4.5, -5, 8, -2.0, 6.0);
  scene.wall({-4, 3}, {4.5, 3}, 3.5, 4.5);
  for (double z = -1.9; z < 3.5; z += 0.5) scene.add({-2.0 + z, 3.0, z});  // dust, a cable
  WallExtractionConfig cfg;
  cfg.seen_over_min_points = 0;  // rays over the beam reach the ceiling: judged by its bottom only
  cfg.max_wall_bottom = 1.5;
  const auto result = WallExtractor(cfg).extract(scene.cloud);
  EXPECT_TRUE(matching(result.walls, {0, -1, 0}, 3.0).empty());
  EXPECT_EQ(matching(result.walls, {-1, 0, 0}, 4.5).size(), 1u);  // the wall it runs into
  EXPECT_EQ(matching(result.walls, {1, 0, 0}, 6.0).size(), 1u);
  // Without the test the beam is a wall.
  cfg.max_wall_bottom = 0.0;
  EXPECT_EQ(matching(WallExtractor(cfg).extract(scene.cloud).walls, {0, -1, 0}, 3.0).size(), 1u);
}

TEST(WallExtraction, AClosedDoorOnAWallIsNoWall) {
  // The wall x = 5 with a 1.1 m door opening (y 0.5..1.6) under a lintel, closed by a door leaf
  // 8 cm in front of the wall: the leaf is flanked by the wall's pieces (and spanned by the
  // plane's run over the lintel), so only the wall is reported, at its own plane.
  test::SyntheticScene scene;
  scene.wall({-3, -2}, {5, -2}, -0.8, 1.8);
  scene.wall({5, 4}, {-3, 4}, -0.8, 1.8);
  scene.wall({-3, 4}, {-3, -2}, -0.8, 1.8);
  scene.wall({5, -2}, {5, 0.5}, -0.8, 1.8);
  scene.wall({5, 1.6}, {5, 4}, -0.8, 1.8);
  scene.wall({5, 0.5}, {5, 1.6}, 1.3, 1.8);  // lintel
  scene.slab(-3, 5, -2, 4, -0.8);
  scene.slab(-3, 5, -2, 4, 1.8);
  scene.wall({4.92, 0.5}, {4.92, 1.6}, -0.8, 1.3);  // door leaf
  WallExtractionConfig cfg;
  const auto walls = WallExtractor(cfg).extract(scene.cloud).walls;
  EXPECT_EQ(matching(walls, {-1, 0, 0}, 5.0).size(), 1u);
  for (const auto& w : walls) {
    const bool leaf = w.normal.x() < -0.99 && std::abs(w.d - 4.92) < 0.03;
    EXPECT_FALSE(leaf) << "door leaf reported at d = " << w.d;
  }
  // Switched off, the leaf is a wall segment of its own.
  cfg.on_wall_max_depth = 0.0;
  const auto off = WallExtractor(cfg).extract(scene.cloud).walls;
  const bool leaf_reported = std::any_of(off.begin(), off.end(), [](const WallSegment& w) {
    return w.normal.x() < -0.99 && std::abs(w.d - 4.92) < 0.03;
  });
  EXPECT_TRUE(leaf_reported);
}

TEST(WallExtraction, AWallBetweenTwoRecessedDoorsStays) {
  // Wall x = 4.7 (y 0..3) between two doors recessed 0.3 m (x = 5, y -1..0 and 3..4): flanked at
  // both ends by surfaces behind it that are shorter together than it is, so it is a wall.
  test::SyntheticScene scene;
  scene.wall({4.7, 0}, {4.7, 3}, -0.8, 1.8);
  scene.wall({5, -1}, {5, 0}, -0.8, 1.8);
  scene.wall({5, 3}, {5, 4}, -0.8, 1.8);
  scene.slab(-1, 5, -1, 4, -0.8);
  const auto walls = WallExtractor(WallExtractionConfig{}).extract(scene.cloud).walls;
  EXPECT_EQ(matching(walls, {-1, 0, 0}, 4.7).size(), 1u);
}

TEST(WallExtraction, AHalfWallInLineWithAWallIsCutOffIt) {
  // The line x = 5 holds a full-height wall (y -2..1) and, in line with it, a half wall (y 1..4,
  // up to the sensor's height) with a hall behind it (wall x = 9): one plane, one run of inliers.
  // Rays over the half wall reach the hall, so only the full-height wall remains.
  test::SyntheticScene scene;
  scene.wall({5, -2}, {5, 1}, -0.8, 1.8);
  scene.wall({5, 1}, {5, 4}, -0.8, 0.0);
  scene.wall({9, -2}, {9, 6}, -0.8, 1.8);
  scene.slab(-1, 9, -2, 6, -0.8);
  const auto result = WallExtractor(WallExtractionConfig{}).extract(scene.cloud);
  const auto walls = matching(result.walls, {-1, 0, 0}, 5.0);
  ASSERT_EQ(walls.size(), 1u);
  // The half wall is reported as seen over.
  const auto half = matching(result.seen_over, {-1, 0, 0}, 5.0);
  ASSERT_EQ(half.size(), 1u);
  EXPECT_TRUE(spans(half[0], {5, 1}, {5, 4}, 0.55))
      << half[0].endpoints[0].transpose() << " / " << half[0].endpoints[1].transpose();
  // The cut falls on the stretches of max_gap (0.5 m): the one holding the joint stays.
  EXPECT_TRUE(spans(walls[0], {5, -2}, {5, 1}, 0.55))
      << walls[0].endpoints[0].transpose() << " / " << walls[0].endpoints[1].transpose();
}

TEST(WallExtraction, RotatedRoomGivesRotatedNormals) {
  auto scene = boxRoomScene();
  const double yaw = 30 * kDeg;
  scene.transform(poseFromXyzRpy(0, 0, 0, 0, 0, yaw));
  const auto result = WallExtractor(WallExtractionConfig{}).extract(scene.cloud);
  ASSERT_EQ(result.walls.size(), 4u);
  const Eigen::Vector3d nx(std::cos(yaw), std::sin(yaw), 0.0);
  EXPECT_EQ(matching(result.walls, nx, 3.0).size(), 1u);
  EXPECT_EQ(matching(result.walls, -nx, 5.0).size(), 1u);
}

TEST(WallExtraction, TinyPiecesAreRejectedAndOutputIsDeterministic) {
  test::SyntheticScene scene;
  scene.wall({-2, 3}, {2, 3}, -0.5, 1.5);
  scene.wall({4, -1}, {4, -0.6}, -0.5, 1.5);  // 0.4 m: below min_wall_length
  scene.slab(-3, 5, -3, 3, -0.5);
  const WallExtractor extractor{WallExtractionConfig{}};
  const auto a = extractor.extract(scene.cloud);
  const auto b = extractor.extract(scene.cloud);
  ASSERT_EQ(a.walls.size(), 1u);
  EXPECT_NEAR(a.walls[0].length(), 4.0, 0.2);
  ASSERT_EQ(b.walls.size(), a.walls.size());
  EXPECT_EQ(a.walls[0].inliers, b.walls[0].inliers);
  EXPECT_EQ(a.walls[0].normal, b.walls[0].normal);
}

TEST(WallExtraction, ConfigValidationNamesTheField) {
  WallExtractionConfig cfg;
  cfg.max_gap = -1.0;
  try {
    cfg.validate();
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("walls.extraction.max_gap_m"), std::string::npos);
  }
  EXPECT_THROW(WallExtractor{cfg}, ConfigError);
  EXPECT_NO_THROW(WallExtractionConfig{}.validate());
}

TEST(WallExtraction, PipelineConfigReadsTheWallsSection) {
  const auto j = parseYamlAsJson(
      "walls:\n  extraction:\n    max_gap_m: 0.8\n  association:\n    max_gap_m: 0.4\n"
      "  axes:\n    window_deg: 5.0\n    typo: 1\n",
      "test.yaml");
  PipelineConfig cfg;
  std::vector<std::string> unknown;
  configFromJson(j, "test.yaml", &cfg, &unknown);
  EXPECT_DOUBLE_EQ(cfg.walls.extraction.max_gap, 0.8);
  EXPECT_DOUBLE_EQ(cfg.walls.association.max_gap, 0.4);
  EXPECT_DOUBLE_EQ(cfg.walls.axes.window_deg, 5.0);
  ASSERT_EQ(unknown.size(), 1u);
  EXPECT_EQ(unknown[0], "walls.axes.typo");
  const auto bad = parseYamlAsJson("walls:\n  association:\n    max_plane_distance_m: -1\n", "b");
  EXPECT_THROW(configFromJson(bad, "b", &cfg, &unknown), ConfigError);
}

TEST(WallExtraction, AKeyWithoutItsUnitIsRejectedNamingTheNewKey) {
  const auto old = parseYamlAsJson("walls:\n  extraction:\n    max_gap: 0.8\n", "old.yaml");
  PipelineConfig cfg;
  std::vector<std::string> unknown;
  try {
    configFromJson(old, "old.yaml", &cfg, &unknown);
    FAIL() << "the old key was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("walls.extraction.max_gap_m"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace tacs
