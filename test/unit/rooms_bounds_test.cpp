// Which planes bound rooms (rooms/room_bounds.h): walls and planes anchored to them do,
// free-standing furniture (rack rows in an open-plan hall) does not.
#include <gtest/gtest.h>

#include "tacs_graphs/rooms/room_bounds.h"
#include "tacs_graphs/rooms/room_extraction.h"
#include "tacs_graphs/rooms/room_map.h"
#include "tacs_graphs/walls/dominant_axes.h"

namespace tacs {
namespace {

// A vertical face from a to b (xy) whose normal is `normal` (xy, unit).
WallLandmark face(uint32_t id, Eigen::Vector2d a, Eigen::Vector2d b, Eigen::Vector2d normal,
                  double top = 2.5) {
  WallLandmark w;
  w.id = id;
  w.normal = Eigen::Vector3d(normal.x(), normal.y(), 0.0);
  w.d = -normal.dot(a);
  const Eigen::Vector2d axis = wallAxis(w.normal);
  w.endpoints[0] = (b - a).dot(axis) > 0 ? a : b;
  w.endpoints[1] = (b - a).dot(axis) > 0 ? b : a;
  w.z_max = top;
  w.mean_top = top;
  w.observations = 5;
  return w;
}

// A 20 x 10 m hall with 8 m walls (0-3, facing in), a row of 2.5 m racks from x 5 to 15 whose
// faces at y 4 and y 6.5 face the aisle between them (4, 5), an office partition meeting the
// west wall (6) and a second partition meeting that one (7). The walls are the hall's four faces
// and rack face 4, which was never seen over (its top gives it away).
WallMap hall(double wall_top = 8.0, double rack_top = 2.5) {
  const Eigen::Vector2d px(1, 0), py(0, 1);
  std::map<uint32_t, WallLandmark> lm;
  lm[0] = face(0, {0, 0}, {20, 0}, py, wall_top);
  lm[1] = face(1, {0, 10}, {20, 10}, -py, wall_top);
  lm[2] = face(2, {0, 0}, {0, 10}, px, wall_top);
  lm[3] = face(3, {20, 0}, {20, 10}, -px, wall_top);
  lm[4] = face(4, {5, 4}, {15, 4}, py, rack_top);
  lm[5] = face(5, {5, 6.5}, {15, 6.5}, -py, rack_top);
  lm[6] = face(6, {0.1, 8}, {3, 8}, -py);
  lm[7] = face(7, {3.2, 8}, {3.2, 10}, px);
  WallMap map;
  map.setLandmarks(std::move(lm), std::set<uint32_t>{0, 1, 2, 3, 4});
  return map;
}

std::vector<Eigen::Vector3d> grid(double x0, double x1, double y0, double y1) {
  std::vector<Eigen::Vector3d> out;
  for (double x = x0; x <= x1 + 1e-9; x += 0.2) {
    for (double y = y0; y <= y1 + 1e-9; y += 0.2) out.emplace_back(x, y, 0.0);
  }
  return out;
}

TEST(RoomBoundingPlanes, FreeStandingFacesBoundNoRoomAnchoredOnesDo) {
  const auto bounding = roomBoundingPlanes(hall(), 0.5, 1.5, 0.0);
  for (uint32_t id : {0u, 1u, 2u, 3u}) EXPECT_EQ(bounding.count(id), 1u) << "wall " << id;
  EXPECT_EQ(bounding.count(4), 0u) << "rack face, wall-shaped but 5.5 m lower than the walls";
  EXPECT_EQ(bounding.count(5), 0u) << "rack face";
  EXPECT_EQ(bounding.count(6), 1u) << "partition meeting the west wall";
  EXPECT_EQ(bounding.count(7), 1u) << "partition meeting the anchored partition";
}

TEST(RoomBoundingPlanes, AWallShapedPlaneWithinTheTopMarginIsAWall) {
  EXPECT_EQ(roomBoundingPlanes(hall(), 0.5, 6.0, 0.0).count(4), 1u);
}

TEST(RoomBoundingPlanes, APlaneBelowTheTopShareOfTheTallestWallsIsFurniture) {
  // Under a 3 m ceiling the 1.6 m rack face 4 (a cubicle partition's height) passes the 1.5 m
  // margin, not the 0.75 share.
  const WallMap map = hall(3.0, 1.6);
  EXPECT_EQ(roomBoundingPlanes(map, 0.5, 1.5, 0.0).count(4), 1u);
  const auto bounding = roomBoundingPlanes(map, 0.5, 1.5, 0.75);
  EXPECT_EQ(bounding.count(4), 0u);
  for (uint32_t id : {0u, 1u, 2u, 3u, 6u, 7u}) EXPECT_EQ(bounding.count(id), 1u) << id;
}

TEST(RoomExtraction, ACorridorReportsTheDistanceOfItsFacingPair) {
  // The hall's two long walls, 10 m apart, are the only facing pair around a region between the
  // rack rows and the east wall: a corridor 10 m wide (RoomSegmenter compares it with
  // rooms.extraction.max_corridor_width_m).
  const WallMap map = hall();
  const DominantAxes axes = estimateDominantAxes(map);
  std::map<uint32_t, WallLandmark> long_walls;
  for (uint32_t id : {0u, 1u}) long_walls.emplace(id, map.landmarks().at(id));
  const RoomExtractionResult wide = extractRoom(grid(15.5, 19.0, 0.2, 9.8), long_walls, axes, {});
  ASSERT_TRUE(wide.found) << wide.reason;
  EXPECT_EQ(wide.room.kind, RoomKind::kCorridor);
  EXPECT_NEAR(wide.corridor_width, 10.0, 1e-6);
  // A four-wall room has none.
  EXPECT_EQ(extractRoom(grid(0.2, 19.8, 0.2, 9.8), roomBoundingPlanes(map, 0.5, 1.5, 0.0), axes, {})
                .corridor_width,
            0.0);
}

TEST(RoomBoundingPlanes, AShortPlaneUpAHighCeilingDoesNotSetTheWallsTop) {
  // A 2 m face reaching 12 m (a column up to a skylight) is no measure of the 8 m walls' top.
  WallMap map = hall();
  std::map<uint32_t, WallLandmark> lm = map.landmarks();
  lm[11] = face(11, {10, 9}, {12, 9}, Eigen::Vector2d(0, -1), 12.0);
  map.setLandmarks(lm, std::set<uint32_t>{0, 1, 2, 3, 4, 11});
  const auto bounding = roomBoundingPlanes(map, 0.5, 1.5, 0.75);
  for (uint32_t id : {0u, 1u, 2u, 3u, 6u, 7u}) EXPECT_EQ(bounding.count(id), 1u) << id;
  EXPECT_EQ(bounding.count(4), 0u);
}

TEST(RoomBoundingPlanes, ZeroAnchorDistanceKeepsEveryPlane) {
  const WallMap map = hall();
  EXPECT_EQ(roomBoundingPlanes(map, 0.0, 1.5, 0.0).size(), map.landmarks().size());
  // A plane further than the anchor distance from every anchored one stays loose.
  EXPECT_EQ(roomBoundingPlanes(map, 0.05, 1.5, 0.0).count(6), 0u);
}

TEST(RoomBoundingPlanes, AnAisleBetweenFreeStandingRacksIsNoCorridorOfItsOwn) {
  const WallMap map = hall();
  const DominantAxes axes = estimateDominantAxes(map);
  ASSERT_TRUE(axes.valid);
  const auto aisle = grid(5.0, 15.0, 4.2, 6.3);
  // Every plane may bound: the two rack faces make the aisle a corridor.
  const RoomExtractionResult with_racks = extractRoom(aisle, map.landmarks(), axes, {});
  ASSERT_TRUE(with_racks.found) << with_racks.reason;
  EXPECT_EQ(with_racks.room.kind, RoomKind::kCorridor);
  // Racks bound nothing: the aisle alone is bounded by no facing walls, so it makes no room; the
  // hall's region around it does, bounded by the hall's walls.
  const auto bounding = roomBoundingPlanes(map, 0.5, 1.5, 0.0);
  EXPECT_FALSE(extractRoom(aisle, bounding, axes, {}).found);
  std::vector<Eigen::Vector3d> hall_floor;
  for (const auto& p : grid(0.2, 19.8, 0.2, 9.8)) {
    const bool in_racks = p.x() >= 5.0 && p.x() <= 15.0 && p.y() > 3.9 && p.y() < 4.2;
    if (!in_racks) hall_floor.push_back(p);
  }
  const RoomExtractionResult whole = extractRoom(hall_floor, bounding, axes, {});
  ASSERT_TRUE(whole.found) << whole.reason;
  EXPECT_EQ(whole.room.kind, RoomKind::kRoom);
  EXPECT_NEAR(whole.room.center.x(), 10.0, 1e-6);
  EXPECT_NEAR(whole.room.center.y(), 5.0, 1e-6);
}

TEST(RoomMapAddUnbounded, AnAisleJoinsTheHallItOpensInto) {
  const WallMap map = hall();
  const DominantAxes axes = estimateDominantAxes(map);
  const auto bounding = roomBoundingPlanes(map, 0.5, 1.5, 0.0);
  // The hall mapped from its open floor west of the racks.
  RoomExtractionResult west = extractRoom(grid(0.2, 9.0, 0.2, 9.8), bounding, axes, {});
  ASSERT_TRUE(west.found) << west.reason;
  west.room.keyframe_ids = {1, 2};
  RoomMap rooms;
  const RoomAssociation created = rooms.addObservation(west.room, map.landmarks());
  ASSERT_TRUE(created.created);
  const size_t cells_before = rooms.rooms().at(created.room_id).cells.size();
  // An aisle region reaching back into that floor: half of it lies in the mapped hall.
  RoomObservation aisle;
  aisle.free_space = grid(1.0, 15.0, 4.2, 6.3);
  aisle.keyframe_ids = {3};
  const auto joined = rooms.addUnbounded(aisle, map.landmarks(), bounding);
  ASSERT_TRUE(joined.has_value());
  EXPECT_EQ(joined->room_id, created.room_id);
  EXPECT_FALSE(joined->created);
  const MappedRoom& hall_room = rooms.rooms().at(created.room_id);
  EXPECT_GT(hall_room.cells.size(), cells_before);
  EXPECT_EQ(hall_room.room.walls, west.room.walls);  // the aisle brings no walls
  EXPECT_EQ(hall_room.room.keyframe_ids, (std::vector<uint32_t>{1, 2, 3}));
  // A region mostly outside every mapped room joins none.
  RoomObservation far;
  far.free_space = grid(12.0, 19.8, 0.2, 3.0);
  EXPECT_FALSE(rooms.addUnbounded(far, map.landmarks(), bounding).has_value());
}

TEST(RoomMapAddUnbounded, ARegionAlongAWallOfTheRoomJoinsItThoughItsPairsEncloseLittle) {
  // An L-shaped hall: mapped from its west part (x 0..8, closed above y = 6 by a storeroom's
  // wall at x = 8), then a wide region east of it between the south wall and the storeroom's.
  const Eigen::Vector2d px(1, 0), py(0, 1);
  WallMap map = hall();
  std::map<uint32_t, WallLandmark> lm = map.landmarks();
  lm[8] = face(8, {8, 6}, {8, 10}, -px, 8.0);
  lm[9] = face(9, {8, 6}, {20, 6}, -py, 8.0);
  map.setLandmarks(lm, std::set<uint32_t>{0, 1, 2, 3, 8, 9});
  RoomObservation west;
  west.kind = RoomKind::kRoom;
  west.walls = {2, 8, 0, 1};  // x+, x-, y+, y-
  west.free_space = grid(0.2, 7.8, 0.2, 9.8);
  west.keyframe_ids = {1};
  RoomMap rooms;
  const RoomAssociation created = rooms.addObservation(west, map.landmarks());
  RoomObservation east;
  east.kind = RoomKind::kCorridor;
  east.free_space = grid(8.0, 19.8, 0.2, 5.8);
  east.keyframe_ids = {2};
  // Without a shared wall the west room's pairs (x 0..8) enclose too little of it.
  EXPECT_FALSE(rooms.addUnbounded(east, map.landmarks(), {}).has_value());
  east.walls = {-1, -1, 0, 9};  // the south wall is the west room's too
  // ... unless a wall stands between the two (a room behind the hall's wall shares it too).
  const auto bounding = roomBoundingPlanes(map, 0.5, 1.5, 0.0);  // the racks bound nothing
  std::map<uint32_t, WallLandmark> separated = bounding;
  separated[10] = face(10, {9, 0}, {9, 6}, px, 8.0);
  EXPECT_FALSE(rooms.addUnbounded(east, map.landmarks(), separated).has_value());
  const auto joined = rooms.addUnbounded(east, map.landmarks(), bounding);
  ASSERT_TRUE(joined.has_value());
  EXPECT_EQ(joined->room_id, created.room_id);
  EXPECT_EQ(rooms.rooms().at(created.room_id).room.walls, west.walls);
}

TEST(RoomMapAddUnbounded, TheAisleInFrontOfAnOfficeDoorIsNotTheOffice) {
  // An office (x 8..12, y 15..20) seen as a corridor: a desk hid its back wall, so only its side
  // walls pair. Its front wall has a 1 m door (x 9.5..10.5). The aisle in front of the door lies
  // between the side walls, but the office reaches it only through the door.
  const Eigen::Vector2d px(1, 0), py(0, 1);
  std::map<uint32_t, WallLandmark> lm;
  lm[0] = face(0, {8, 15}, {8, 20}, px);
  lm[1] = face(1, {12, 15}, {12, 20}, -px);
  lm[2] = face(2, {8, 15}, {9.5, 15}, py);
  lm[3] = face(3, {10.5, 15}, {12, 15}, py);
  RoomObservation office;
  office.kind = RoomKind::kCorridor;
  office.walls = {0, 1, -1, -1};
  office.free_space = grid(8.2, 11.8, 15.2, 19.8);
  office.keyframe_ids = {1};
  RoomMap rooms;
  const RoomAssociation created = rooms.addObservation(office, lm);
  ASSERT_TRUE(created.created);
  RoomObservation aisle;
  aisle.free_space = grid(8.4, 11.6, 13.0, 14.8);
  aisle.keyframe_ids = {2};
  const std::vector<Doorway> doorways = findDoorways(lm, TacsFreeSpaceConfig{});
  ASSERT_EQ(doorways.size(), 1u);
  EXPECT_FALSE(rooms.addUnbounded(aisle, lm, lm, doorways).has_value());
  // The trap: with the door unknown, the side walls enclose the aisle and it joins the office.
  const auto joined = rooms.addUnbounded(aisle, lm, lm, {});
  ASSERT_TRUE(joined.has_value());
  EXPECT_EQ(joined->room_id, created.room_id);
}

TEST(WallMapMirror, IsWallFollowsTheSceneGraphsFlag) {
  SceneGraph graph;
  WallNode wall;
  wall.normal = Eigen::Vector3d::UnitX();
  wall.endpoints[0] = Eigen::Vector2d(0, 0);
  wall.endpoints[1] = Eigen::Vector2d(0, 5);
  wall.z_range = {0.0, 2.5};
  graph.walls[1] = wall;
  wall.is_wall = false;  // e.g. seen over: the mirror cannot tell, it has no seen-over surfaces
  graph.walls[2] = wall;
  graph.walls[3] = wall;  // no wall yet: seen from one keyframe only
  const WallMap mirror = wallMapFromSceneGraph(graph, {{1, 5}, {2, 5}, {3, 1}});
  EXPECT_TRUE(mirror.isWall(1));
  EXPECT_FALSE(mirror.isWall(2));
  EXPECT_FALSE(mirror.isWall(3));
  EXPECT_FALSE(mirror.isWall(4));  // unknown
  // Long and observed enough, yet no wall: furniture. Observed too little: shaped like a wall.
  EXPECT_TRUE(mirror.hasWallShape(1));
  EXPECT_FALSE(mirror.hasWallShape(2));
  EXPECT_TRUE(mirror.hasWallShape(3));
}

}  // namespace
}  // namespace tacs
