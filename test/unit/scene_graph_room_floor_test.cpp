// Room floors (scene_graph/room_floor.h): the free space grown to the room's own walls, never
// across a wall, each cell to the nearest room.
#include <gtest/gtest.h>

#include <set>
#include <utility>

#include "tacs_graphs/scene_graph/room_floor.h"

namespace tacs {
namespace {

// A wall on the segment a-b whose normal faces `inside`.
WallNode wall(uint32_t id, Eigen::Vector2d a, Eigen::Vector2d b, Eigen::Vector2d inside) {
  WallNode w;
  w.id = id;
  const Eigen::Vector2d t = (b - a).normalized();
  Eigen::Vector2d n(-t.y(), t.x());
  if (n.dot(inside - a) < 0) n = -n;
  w.normal = Eigen::Vector3d(n.x(), n.y(), 0.0);
  w.d = -n.dot(a);
  w.endpoints = {a, b};
  w.z_range = {0.0, 3.0};
  return w;
}

// Free-space points every 0.1 m over [x0,x1] x [y0,y1], leaving out the box `hole`.
std::vector<Eigen::Vector2d> freeSpace(double x0, double x1, double y0, double y1,
                                       Eigen::Vector4d hole = Eigen::Vector4d::Zero()) {
  std::vector<Eigen::Vector2d> out;
  for (double x = x0; x <= x1 + 1e-9; x += 0.1) {
    for (double y = y0; y <= y1 + 1e-9; y += 0.1) {
      if (x > hole[0] && x < hole[1] && y > hole[2] && y < hole[3]) continue;
      out.emplace_back(x, y);
    }
  }
  return out;
}

using Cells = std::set<std::pair<int, int>>;
Cells cellsOf(const std::vector<Eigen::Vector2i>& v) {
  Cells out;
  for (const auto& c : v) out.insert({c.x(), c.y()});
  return out;
}
Cells rectangle(int x0, int x1, int y0, int y1) {  // cells [x0, x1) x [y0, y1)
  Cells out;
  for (int x = x0; x < x1; ++x) {
    for (int y = y0; y < y1; ++y) out.insert({x, y});
  }
  return out;
}
double dice(const Cells& a, const Cells& b) {
  size_t both = 0;
  for (const auto& c : a) both += b.count(c);
  return 2.0 * both / static_cast<double>(a.size() + b.size());
}

TEST(RoomFloor, GrowsTheFreeSpaceToTheRoomsWallsAroundFurniture) {
  // A 4 x 5 m room; its free space keeps 0.4 m from the walls and leaves out a 1.2 m desk.
  SceneGraph g;
  const Eigen::Vector2d mid(2.0, 2.5);
  g.walls[0] = wall(0, {0, 0}, {4, 0}, mid);
  g.walls[1] = wall(1, {4, 0}, {4, 5}, mid);
  g.walls[2] = wall(2, {4, 5}, {0, 5}, mid);
  g.walls[3] = wall(3, {0, 5}, {0, 0}, mid);
  RoomNode room;
  room.id = 7;
  room.wall_ids = {0, 1, 2, 3};
  room.free_space = freeSpace(0.45, 3.55, 0.45, 4.55, {1.0, 2.2, 1.0, 2.2});
  g.rooms[7] = room;

  const auto floors = roomFloors(g, {});
  ASSERT_EQ(floors.size(), 1u);
  const Cells floor = cellsOf(floors.at(7));
  const Cells truth = rectangle(0, 40, 0, 50);
  EXPECT_GT(dice(floor, truth), 0.95);
  for (const auto& [x, y] : floor) {  // nothing beyond the walls (their own cells aside)
    EXPECT_TRUE(x >= -1 && x <= 40 && y >= -1 && y <= 50) << x << ", " << y;
  }
  // The free space alone covers far less of the room.
  const auto bare = roomFloors(g, {0.1, 0.0, 0.0});
  EXPECT_LT(dice(cellsOf(bare.at(7)), truth), 0.9);
}

TEST(RoomFloor, NeverCrossesAWallAndGivesADoorwayToTheNearestRoom) {
  // Two 4 x 4 m rooms side by side; the wall between them at x = 4 has a 1 m door at y in [1.5,
  // 2.5], drawn as two wall pieces.
  SceneGraph g;
  const Eigen::Vector2d a(2, 2), b(6, 2);
  g.walls[0] = wall(0, {0, 0}, {8, 0}, a);
  g.walls[1] = wall(1, {8, 4}, {0, 4}, a);
  g.walls[2] = wall(2, {0, 0}, {0, 4}, a);
  g.walls[3] = wall(3, {8, 0}, {8, 4}, b);
  g.walls[4] = wall(4, {4, 0}, {4, 1.5}, a);
  g.walls[5] = wall(5, {4, 2.5}, {4, 4}, a);
  RoomNode left, right;
  left.id = 1, right.id = 2;
  left.wall_ids = {0, 1, 2, 4, 5};
  right.wall_ids = {0, 1, 3, 4, 5};
  left.free_space = freeSpace(0.45, 3.55, 0.45, 3.55);
  right.free_space = freeSpace(4.45, 7.55, 0.45, 3.55);
  g.rooms[1] = left, g.rooms[2] = right;

  const auto floors = roomFloors(g, {});
  const Cells l = cellsOf(floors.at(1)), r = cellsOf(floors.at(2));
  for (const auto& c : l) EXPECT_EQ(r.count(c), 0u) << "a cell in both rooms";
  // The left room keeps to x < 4 (its side of the shared wall), the right one to x >= 4.
  for (const auto& [x, y] : l) EXPECT_LE(x, 40);
  for (const auto& [x, y] : r) EXPECT_GE(x, 39);
  EXPECT_GT(dice(l, rectangle(0, 40, 0, 40)), 0.95);
  EXPECT_GT(dice(r, rectangle(40, 80, 0, 40)), 0.95);
}

TEST(RoomFloor, ReachesNoFurtherThanConfiguredWhereNoWallBoundsIt) {
  // A corridor bounded by two walls only: along its open ends the floor stops at `reach_m`.
  SceneGraph g;
  const Eigen::Vector2d mid(5, 1);
  g.walls[0] = wall(0, {0, 0}, {10, 0}, mid);
  g.walls[1] = wall(1, {10, 2}, {0, 2}, mid);
  RoomNode corridor;
  corridor.id = 3;
  corridor.wall_ids = {0, 1};
  corridor.free_space = freeSpace(2.0, 8.0, 0.5, 1.5);
  g.rooms[3] = corridor;
  RoomFloorConfig config;
  config.reach_m = 1.0;
  const Cells floor = cellsOf(roomFloors(g, config).at(3));
  int min_x = 1000, max_x = -1000;
  for (const auto& [x, y] : floor) min_x = std::min(min_x, x), max_x = std::max(max_x, x);
  EXPECT_NEAR(min_x, 10, 1);  // 2.0 m - 1.0 m
  EXPECT_NEAR(max_x, 90, 1);  // 8.0 m + 1.0 m
  // A room with no free space has an empty floor; a bad configuration is refused.
  g.rooms[4].id = 4;
  EXPECT_TRUE(roomFloors(g, config).at(4).empty());
  config.cell_m = 0.0;
  EXPECT_THROW(roomFloors(g, config), std::invalid_argument);
}

}  // namespace
}  // namespace tacs
