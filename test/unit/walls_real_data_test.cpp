// Wall extraction on a real indoor scan (data set pcl_room_scans, see README "Test data").
#include <gtest/gtest.h>

#include <cmath>

#include "common/room_scans.h"
#include "tacs_graphs/walls/dominant_axes.h"
#include "tacs_graphs/walls/wall_extractor.h"

namespace tacs {
namespace {

using test::kRoomScansSet;
using test::loadRoomScan;

TEST(WallsRealData, RoomScanMainWallsAreFoundAndPerpendicular) {
  TACS_DATA_SET_OR_SKIP(dir, kRoomScansSet);
  const PointCloud cloud = loadRoomScan(dir, "room_scan1.pcd");
  ASSERT_GT(cloud.size(), 100000u);
  const auto result = WallExtractor(WallExtractionConfig{}).extract(cloud);
  std::vector<WallSegment> main;
  for (const auto& w : result.walls) {
    EXPECT_LT(std::abs(w.normal.z()), 0.2);
    EXPECT_GE(w.d, 0.0);
    if (w.length() > 2.0) main.push_back(w);
  }
  ASSERT_GE(main.size(), 3u);
  // Every main wall is parallel or perpendicular to another main wall (Manhattan room), and
  // both families are present.
  int parallel_pairs = 0, perpendicular_pairs = 0;
  for (size_t i = 0; i < main.size(); ++i) {
    for (size_t j = i + 1; j < main.size(); ++j) {
      const double c = std::abs(
          main[i].normal.head<2>().normalized().dot(main[j].normal.head<2>().normalized()));
      if (c > std::cos(5.0 * M_PI / 180.0)) ++parallel_pairs;
      if (c < std::sin(5.0 * M_PI / 180.0)) ++perpendicular_pairs;
    }
  }
  EXPECT_GE(parallel_pairs, 1);
  EXPECT_GE(perpendicular_pairs, 2);
  // The two longest walls are the opposite long sides of the room, 4 to 5 m apart.
  const WallSegment& a = main[0];
  const WallSegment* opposite = nullptr;
  for (const auto& w : main) {
    if (w.normal.dot(a.normal) < -0.99 && (!opposite || w.length() > opposite->length())) {
      opposite = &w;
    }
  }
  ASSERT_NE(opposite, nullptr);
  EXPECT_GT(a.length(), 8.0);
  EXPECT_GT(opposite->length(), 8.0);
  EXPECT_NEAR(a.d + opposite->d, 4.5, 0.5);
  // Floor about 1.3 m below and ceiling about 1.7 m above the sensor.
  bool floor = false, ceiling = false;
  for (const auto& h : result.horizontal) {
    floor |= h.normal.z() > 0.99 && std::abs(h.d - 1.3) < 0.1 && h.inliers > 1000;
    ceiling |= h.normal.z() < -0.99 && std::abs(h.d - 1.65) < 0.1 && h.inliers > 1000;
  }
  EXPECT_TRUE(floor);
  EXPECT_TRUE(ceiling);
  // The room's axes agree with the scanner frame here (within a few degrees).
  const DominantAxes axes = estimateDominantAxes(result.walls);
  EXPECT_TRUE(axes.valid);
  EXPECT_LT(std::abs(axes.yaw), 3.0 * M_PI / 180.0);
}

}  // namespace
}  // namespace tacs
