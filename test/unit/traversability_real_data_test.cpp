// TraversabilityMapper on the real PCL room scans: a furnished room seen by a dense real scanner,
// with its noise, clutter and no ground truth but a flat floor.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/room_scans.h"
#include "tacs_graphs/traversability/traversability_mapper.h"

namespace tacs {
namespace {

// The floor height: the most common height 1-1.6 m below the sensor, in 1 cm bins.
double floorHeight(const PointCloud& cloud) {
  std::vector<int> bins(60, 0);
  for (const auto& p : cloud.points) {
    if (p.z > -1.6f && p.z < -1.0f) ++bins[static_cast<int>((p.z + 1.6f) * 100.0f)];
  }
  const int mode = static_cast<int>(std::max_element(bins.begin(), bins.end()) - bins.begin());
  return -1.6 + (mode + 0.5) / 100.0;
}

class TraversabilityRealData : public ::testing::TestWithParam<const char*> {};

TEST_P(TraversabilityRealData, FindsTheFloorOfTheRoom) {
  TACS_DATA_SET_OR_SKIP(dir, test::kRoomScansSet);
  const PointCloud cloud = test::loadRoomScan(dir, GetParam());
  ASSERT_GT(cloud.size(), 100000u);
  TraversabilityConfig config;
  config.robot_floor_z = floorHeight(cloud);  // the scans are in the sensor frame
  const TraversabilityResult result = TraversabilityMapper(config).process(cloud);
  EXPECT_TRUE(result.warning.empty()) << result.warning;
  EXPECT_GE(result.graph.root, 0);
  EXPECT_GT(result.graph.countTraversable(), 150u);

  // The real floor is rough: points within 12 cm of its height are floor.
  constexpr double kFloorBand = 0.12;
  size_t floor = 0, in_band = 0;
  for (const auto& p : cloud.points) {
    if (std::abs(p.x) > config.max_range || std::abs(p.y) > config.max_range ||
        std::hypot(p.x, p.y) < config.min_range) {
      continue;
    }
    floor += std::abs(p.z - config.robot_floor_z) < kFloorBand;
  }
  for (const auto& p : result.ground->points) {
    in_band += std::abs(p.z - config.robot_floor_z) < kFloorBand;
  }
  // Every ground point in the band is one of the floor points of the grid.
  const double precision = static_cast<double>(in_band) / result.ground->size();
  const double recall = static_cast<double>(in_band) / floor;
  std::printf("[real ground] %s: floor z %.2f, precision %.3f recall %.3f\n", GetParam(),
              config.robot_floor_z, precision, recall);
  EXPECT_GE(precision, 0.9);
  EXPECT_GE(recall, 0.85);
}

INSTANTIATE_TEST_SUITE_P(RoomScans, TraversabilityRealData,
                         ::testing::Values("room_scan1.pcd", "room_scan2.pcd"));

}  // namespace
}  // namespace tacs
