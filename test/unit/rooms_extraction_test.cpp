// Room extraction (paper Sec. III-B-3): the walls bounding a free-space region, four-wall rooms
// and corridors, centres midway between the walls, and buildings not aligned with the map axes.
#include <gtest/gtest.h>

#include "common/room_layout.h"
#include "tacs_graphs/rooms/room_extraction.h"

namespace tacs {
namespace {

std::vector<Eigen::Vector3d> grid(double x0, double x1, double y0, double y1,
                                  const Pose3& T = Pose3::Identity()) {
  std::vector<Eigen::Vector3d> out;
  for (double x = x0; x <= x1 + 1e-9; x += 0.2) {
    for (double y = y0; y <= y1 + 1e-9; y += 0.2) out.push_back(T * Eigen::Vector3d(x, y, 0));
  }
  return out;
}

// The landmark's wall line coordinate along the map axis `axis` (0: x, 1: y).
double wallAt(const WallMap& walls, int id, int axis) {
  return walls.landmarks().at(static_cast<uint32_t>(id)).midpoint()[axis];
}

TEST(RoomsExtraction, FourWallRoomIsBoundedByItsWalls) {
  const WallMap walls = test::twoRoomsAndCorridor().wallMap();
  const DominantAxes axes = estimateDominantAxes(walls);
  const auto res =
      extractRoom(grid(0.5, 4.5, 0.5, 3.5), walls.landmarks(), axes, RoomExtractionConfig{});
  ASSERT_TRUE(res.found) << res.reason;
  EXPECT_EQ(res.room.kind, RoomKind::kRoom);
  EXPECT_NEAR(wallAt(walls, res.room.walls[0], 0), 0.0, 1e-6);  // x+
  EXPECT_NEAR(wallAt(walls, res.room.walls[1], 0), 5.0, 1e-6);  // x-
  EXPECT_NEAR(wallAt(walls, res.room.walls[2], 1), 0.0, 1e-6);  // y+
  EXPECT_NEAR(wallAt(walls, res.room.walls[3], 1), 4.0, 1e-6);  // y-
  EXPECT_NEAR(res.room.center.x(), 2.5, 1e-6);
  EXPECT_NEAR(res.room.center.y(), 2.0, 1e-6);
  EXPECT_EQ(res.room.wallPairs().size(), 2u);
  for (int n : res.adjacent_points) EXPECT_GT(n, 0);
}

TEST(RoomsExtraction, FreeSpaceThatLeakedThroughADoorStaysOutOfTheRoom) {
  // The room's region ran on through its door into the corridor beyond its y = 4 wall.
  const WallMap walls = test::twoRoomsAndCorridor().wallMap();
  const DominantAxes axes = estimateDominantAxes(walls);
  const std::vector<Eigen::Vector3d> inside = grid(0.5, 4.5, 0.5, 3.5);
  std::vector<Eigen::Vector3d> region = inside;
  for (const auto& p : grid(1.5, 3.1, 4.5, 5.3)) region.push_back(p);
  const std::vector<Doorway> doorways = findDoorways(walls.landmarks(), TacsFreeSpaceConfig{});
  const auto res = extractRoom(region, walls.landmarks(), axes, RoomExtractionConfig{}, doorways);
  ASSERT_TRUE(res.found) << res.reason;
  EXPECT_EQ(res.room.kind, RoomKind::kRoom);
  EXPECT_EQ(res.room.free_space.size(), inside.size());
  for (const auto& p : res.room.free_space) EXPECT_LE(p.y(), 4.3);
  // Space beside the ends of the room's walls (an L-shaped room's leg) is not behind them.
  std::vector<Eigen::Vector3d> with_leg = inside;
  const std::vector<Eigen::Vector3d> leg = grid(-1.5, -0.7, 4.5, 5.3);
  with_leg.insert(with_leg.end(), leg.begin(), leg.end());
  EXPECT_EQ(
      extractRoom(with_leg, walls.landmarks(), axes, RoomExtractionConfig{}).room.free_space.size(),
      with_leg.size());
  // A negative margin keeps the whole region.
  RoomExtractionConfig keep;
  keep.outside_margin = -1.0;
  EXPECT_EQ(extractRoom(region, walls.landmarks(), axes, keep, doorways).room.free_space.size(),
            region.size());
}

TEST(RoomsExtraction, CorridorWithOpenEndsHasOnePair) {
  const WallMap walls = test::twoRoomsAndCorridor().wallMap();
  const auto res = extractRoom(grid(-1.6, 11.6, 4.4, 5.6), walls.landmarks(),
                               estimateDominantAxes(walls), RoomExtractionConfig{});
  ASSERT_TRUE(res.found) << res.reason;
  EXPECT_EQ(res.room.kind, RoomKind::kCorridor);
  EXPECT_FALSE(res.room.hasXPair());  // the walls of the rooms' ends only touch the corridor
  ASSERT_TRUE(res.room.hasYPair());
  EXPECT_NEAR(res.room.center.y(), 5.0, 1e-6);
  EXPECT_NEAR(res.room.center.x(), 5.0, 0.05);  // along the corridor: its free-space centre
}

TEST(RoomsExtraction, RejectsSmallOrUnboundedRegions) {
  const WallMap walls = test::twoRoomsAndCorridor().wallMap();
  const DominantAxes axes = estimateDominantAxes(walls);
  EXPECT_FALSE(extractRoom(grid(2, 2.4, 2, 2.4), walls.landmarks(), axes, {}).found);
  // Free space far from every wall.
  EXPECT_FALSE(extractRoom(grid(20, 24, 20, 24), walls.landmarks(), axes, {}).found);
}

TEST(RoomsExtraction, RotatedBuildingGivesTheSameRoom) {
  const Pose3 T = poseFromXyzRpy(3.0, -2.0, 0.0, 0, 0, 30.0 * M_PI / 180.0);
  test::FloorPlan plan = test::twoRoomsAndCorridor();
  for (auto& f : plan.faces) f = transformWall(f, T);
  const WallMap walls = plan.wallMap();
  const DominantAxes axes = estimateDominantAxes(walls);
  ASSERT_TRUE(axes.valid);
  const auto res = extractRoom(grid(0.5, 4.5, 0.5, 3.5, T), walls.landmarks(), axes, {});
  ASSERT_TRUE(res.found) << res.reason;
  EXPECT_EQ(res.room.kind, RoomKind::kRoom);
  EXPECT_LT((res.room.center - T * Eigen::Vector3d(2.5, 2.0, 0)).head<2>().norm(), 1e-6);
}

}  // namespace
}  // namespace tacs
