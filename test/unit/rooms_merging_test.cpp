// Room merging (paper Sec. III-C): overlap of free space plus centre distance along the axes
// orthogonal to the walls; wall-to-wall pairs (eq. 4); the S-Graphs+ centre-distance baseline.
#include <gtest/gtest.h>

#include "tacs_graphs/rooms/room_map.h"

namespace tacs {
namespace {

// A y-direction corridor (walls facing +-x: x+ id xp, x- id xm) over [x0,x1] x [y0,y1].
RoomObservation yCorridor(double x0, double x1, double y0, double y1, int xp, int xm) {
  RoomObservation o;
  o.kind = RoomKind::kCorridor;
  o.walls = {xp, xm, -1, -1};
  for (double x = x0; x <= x1; x += 0.2) {
    for (double y = y0; y <= y1; y += 0.2) o.free_space.emplace_back(x, y, 0.0);
  }
  o.center = Eigen::Vector3d(0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.0);
  return o;
}

RoomObservation xCorridor(double x0, double x1, double y0, double y1, int yp, int ym) {
  RoomObservation o = yCorridor(x0, x1, y0, y1, -1, -1);
  o.walls = {-1, -1, yp, ym};
  return o;
}

const std::map<uint32_t, WallLandmark> kNoWalls;

// A wall at x = `x` facing +x (sign 1) or -x (sign -1), along y in [0, 16].
WallLandmark xWall(uint32_t id, double x, int sign) {
  WallLandmark w;
  w.id = id;
  w.normal = Eigen::Vector3d(sign, 0, 0);
  w.d = -sign * x;
  w.endpoints[0] = {x, sign > 0 ? 16.0 : 0.0};
  w.endpoints[1] = {x, sign > 0 ? 0.0 : 16.0};
  return w;
}

TEST(RoomsMerging, OverlappingCorridorCloseAcrossIsMergedWithWallPairs) {
  RoomMap map;
  const std::map<uint32_t, WallLandmark> walls = {
      {1, xWall(1, -0.4, 1)}, {2, xWall(2, 2.4, -1)}, {7, xWall(7, 2.6, -1)}};
  const auto first = map.addObservation(yCorridor(0, 2, 0, 10, 1, 2), walls);
  EXPECT_TRUE(first.created);
  // Seen again further along, 0.3 m off across, with a new landmark for the x- wall.
  RoomObservation again = yCorridor(0.3, 2.3, 6, 16, 1, 7);
  again.keyframe_ids = {40, 41};
  const auto second = map.addObservation(again, walls);
  EXPECT_FALSE(second.created);
  EXPECT_EQ(second.room_id, first.room_id);
  ASSERT_EQ(second.wall_to_wall.size(), 1u);
  EXPECT_EQ(second.wall_to_wall[0], std::make_pair(2u, 7u));
  ASSERT_EQ(map.rooms().size(), 1u);
  const MappedRoom& r = map.rooms().at(first.room_id);
  EXPECT_EQ(r.observations, 2u);
  EXPECT_EQ(r.room.keyframe_ids, (std::vector<uint32_t>{40, 41}));
  // The free space is the union: it now reaches y = 16.
  double max_y = 0;
  for (const auto& p : r.room.free_space) max_y = std::max(max_y, p.y());
  EXPECT_NEAR(max_y, 16.0, 0.2);
}

TEST(RoomsMerging, WallsFarApartAreNotTied) {
  RoomMap map;
  const std::map<uint32_t, WallLandmark> walls = {
      {1, xWall(1, -0.4, 1)}, {2, xWall(2, 2.4, -1)}, {8, xWall(8, 3.9, -1)}};
  map.addObservation(yCorridor(0, 2, 0, 10, 1, 2), walls);
  // The same corridor, its x- wall taken 1.5 m further (a face behind an opening): merged, but
  // the two x- walls are different walls and get no wall-to-wall edge.
  RoomObservation again = yCorridor(0, 2, 0, 10, 1, 8);
  again.center.x() += 0.75;
  const auto second = map.addObservation(again, walls);
  EXPECT_FALSE(second.created);
  EXPECT_TRUE(second.wall_to_wall.empty());
}

TEST(RoomsMerging, DisjointPiecesBetweenTheSameWallsAreOneCorridor) {
  RoomMap map;
  const auto first = map.addObservation(yCorridor(0, 2, 0, 10, 1, 2), kNoWalls);
  const auto second = map.addObservation(yCorridor(0, 2, 20, 30, 1, 2), kNoWalls);
  EXPECT_FALSE(second.created);
  EXPECT_EQ(second.room_id, first.room_id);
}

TEST(RoomsMerging, PiecesOfOneWallPlaneMergeWhenTheViewsTouchOrNoWallSeparatesThem) {
  // y walls at y = 0 (facing +y) and y = 4 (facing -y), each in two landmarks (x < 5, x > 5).
  const auto yWall = [](uint32_t id, double y, int sign, double x0, double x1) {
    WallLandmark w;
    w.id = id;
    w.normal = Eigen::Vector3d(0, sign, 0);
    w.d = -sign * y;
    w.endpoints[0] = {sign > 0 ? x0 : x1, y};
    w.endpoints[1] = {sign > 0 ? x1 : x0, y};
    return w;
  };
  const std::map<uint32_t, WallLandmark> walls = {{1, yWall(1, 0, 1, 0, 5)},
                                                  {2, yWall(2, 4, -1, 0, 5)},
                                                  {3, yWall(3, 0, 1, 5.5, 10)},
                                                  {4, yWall(4, 4, -1, 5.5, 10)}};
  // Two rooms in a row: the same wall planes, no shared free space, a partition wall at x = 5.3.
  auto with_partition = walls;
  with_partition[5] = xWall(5, 5.3, -1);
  RoomMap row;
  row.addObservation(xCorridor(0, 5, 0.4, 3.6, 1, 2), with_partition);
  EXPECT_TRUE(row.addObservation(xCorridor(5.6, 10, 0.4, 3.6, 3, 4), with_partition).created);
  // Without a wall between them they are one corridor walked in two pieces (its walls broken
  // by a doorway on either side): merged, the wall pieces tied.
  RoomMap corridor;
  corridor.addObservation(xCorridor(0, 5, 0.4, 3.6, 1, 2), walls);
  const auto continued = corridor.addObservation(xCorridor(5.6, 10, 0.4, 3.6, 3, 4), walls);
  EXPECT_FALSE(continued.created);
  EXPECT_EQ(continued.wall_to_wall.size(), 2u);
  // Two views of one hall that touch: merged, the wall pieces tied.
  RoomMap hall;
  hall.addObservation(xCorridor(0, 5, 0.4, 3.6, 1, 2), walls);
  const auto second = hall.addObservation(xCorridor(4.6, 10, 0.4, 3.6, 3, 4), walls);
  EXPECT_FALSE(second.created);
  EXPECT_EQ(second.wall_to_wall.size(), 2u);
}

TEST(RoomsMerging, FarAcrossOrDisjointOrPerpendicularStaysApart) {
  RoomMap map;
  map.addObservation(yCorridor(0, 2, 0, 10, 1, 2), kNoWalls);
  // Overlapping but 1.5 m apart across the corridor.
  EXPECT_TRUE(map.addObservation(yCorridor(1.5, 3.5, 0, 10, 3, 4), kNoWalls).created);
  // Same axis, no shared free space, other walls.
  EXPECT_TRUE(map.addObservation(yCorridor(0, 2, 20, 30, 8, 9), kNoWalls).created);
  // A perpendicular corridor crossing at a junction: no common axis.
  EXPECT_TRUE(map.addObservation(xCorridor(-5, 7, 4, 6, 5, 6), kNoWalls).created);
  EXPECT_EQ(map.rooms().size(), 4u);
}

// A wall at y = `y` facing +y (sign 1) or -y (sign -1), along x in [-10, 16].
WallLandmark yWall(uint32_t id, double y, int sign) {
  WallLandmark w;
  w.id = id;
  w.normal = Eigen::Vector3d(0, sign, 0);
  w.d = -sign * y;
  w.endpoints[0] = {sign > 0 ? -10.0 : 16.0, y};
  w.endpoints[1] = {sign > 0 ? 16.0 : -10.0, y};
  return w;
}

TEST(RoomsMerging, PerpendicularStripsAroundATableCloseIntoOneRoom) {
  // A 6 x 4.4 m meeting room whose table (x 1.5..4.5, y 1.5..3) splits its floor: the south
  // strip pairs only the west and east walls, the west strip only the south and north walls.
  const std::map<uint32_t, WallLandmark> walls = {
      {1, xWall(1, 0.0, 1)}, {2, xWall(2, 6.0, -1)}, {3, yWall(3, 0.0, 1)}, {4, yWall(4, 4.4, -1)}};
  RoomMap map;
  const auto south = map.addObservation(yCorridor(0.2, 5.8, 0.2, 1.4, 1, 2), walls);
  const auto west = map.addObservation(xCorridor(0.2, 1.4, 0.2, 4.2, 3, 4), walls);
  EXPECT_FALSE(west.created);
  EXPECT_EQ(west.room_id, south.room_id);
  ASSERT_EQ(map.rooms().size(), 1u);
  const RoomObservation& room = map.rooms().at(south.room_id).room;
  EXPECT_EQ(room.kind, RoomKind::kRoom);
  EXPECT_EQ(room.walls, (std::array<int, 4>{1, 2, 3, 4}));
  // Corridors crossing at a junction reach beyond each other's walls: they stay apart.
  RoomMap junction;
  const std::map<uint32_t, WallLandmark> corridors = {{1, xWall(1, -0.4, 1)},
                                                      {2, xWall(2, 2.4, -1)},
                                                      {3, yWall(3, 3.6, 1)},
                                                      {4, yWall(4, 6.4, -1)}};
  junction.addObservation(yCorridor(0, 2, 0, 16, 1, 2), corridors);
  EXPECT_TRUE(junction.addObservation(xCorridor(-5, 7, 4, 6, 3, 4), corridors).created);
}

TEST(RoomsMerging, NeighboursInARowSharingFrontAndBackWallsStayApart) {
  // Offices side by side share the corridor wall and the back wall (one landmark each, across
  // the doors). A partial view of the second office bounded by those two walls only must not
  // join the first office: their free space never touches.
  RoomMap map;
  RoomObservation office = xCorridor(0, 4, 0, 4, 1, 2);
  office.kind = RoomKind::kRoom;
  office.walls = {10, 11, 1, 2};
  const auto first = map.addObservation(office, kNoWalls);
  const auto second = map.addObservation(xCorridor(4.4, 8, 0, 4, 1, 2), kNoWalls);
  EXPECT_TRUE(second.created);
  EXPECT_NE(second.room_id, first.room_id);
}

TEST(RoomsMerging, MappedRoomsMergeWhenOneComesToLieInsideTheOther) {
  // A hall first seen as a strip along its bottom side (an x-direction corridor), then from its
  // left side (a y-direction corridor: perpendicular, so apart), then the left view grows over
  // most of the hall and the bottom strip lies inside it: one room, the larger keeps its id.
  RoomMap map;
  RoomObservation bottom = xCorridor(0, 20, 0, 3, 3, 4);
  bottom.keyframe_ids = {1, 2};
  const auto strip = map.addObservation(bottom, kNoWalls);
  const auto side = map.addObservation(yCorridor(0, 3, 0, 12, 1, 2), kNoWalls);
  ASSERT_TRUE(side.created);
  ASSERT_EQ(map.rooms().size(), 2u);
  RoomObservation most = yCorridor(0, 20, 0.5, 12, 1, 2);
  most.keyframe_ids = {90};
  const auto grown = map.addObservation(most, kNoWalls);
  EXPECT_FALSE(grown.created);
  EXPECT_EQ(grown.room_id, side.room_id);
  EXPECT_EQ(grown.absorbed, (std::vector<uint32_t>{strip.room_id}));
  ASSERT_EQ(map.rooms().size(), 1u);
  const MappedRoom& hall = map.rooms().at(side.room_id);
  EXPECT_EQ(hall.room.keyframe_ids, (std::vector<uint32_t>{1, 2, 90}));
  EXPECT_EQ(hall.observations, 3u);
  // A room merely touching the hall stays apart.
  EXPECT_TRUE(map.addObservation(yCorridor(20.2, 24, 0, 12, 5, 6), kNoWalls).created);
  EXPECT_EQ(map.rooms().size(), 2u);
}

// A four-wall room over [x0,x1] x [y0,y1] with wall ids {base, base+1, base+2, base+3}.
RoomObservation room(double x0, double x1, double y0, double y1, int base) {
  RoomObservation o = yCorridor(x0, x1, y0, y1, base, base + 1);
  o.kind = RoomKind::kRoom;
  o.walls = {base, base + 1, base + 2, base + 3};
  return o;
}

TEST(RoomsMerging, TwoLegsOfAnOpenFloorWithNoWallBetweenAreOneRoom) {
  // An L-shaped open floor seen from its main part, then from its leg: different walls and
  // centres, 5/8 of the leg's view inside the main one (under nested_overlap).
  const RoomObservation main_part = room(0, 20, 0, 10, 1);
  const RoomObservation leg = room(10, 20, 0, 16, 11);
  WallLandmark across;  // a plane between the two views' centres (10, 5) and (15, 8)
  across.id = 30;
  across.normal = Eigen::Vector3d(0, 1, 0);
  across.d = -6.5;
  across.endpoints[0] = {0.0, 6.5};
  across.endpoints[1] = {20.0, 6.5};
  const std::map<uint32_t, WallLandmark> with_plane = {{30, across}};
  {
    RoomMap map;
    const auto a = map.addObservation(main_part, kNoWalls);
    const auto b = map.addObservation(leg, kNoWalls);
    EXPECT_FALSE(b.created);
    EXPECT_EQ(b.room_id, a.room_id);
  }
  {  // The plane is free-standing furniture: it bounds no room, so it separates nothing.
    RoomMap map;
    map.addObservation(main_part, with_plane, &kNoWalls);
    EXPECT_FALSE(map.addObservation(leg, with_plane, &kNoWalls).created);
  }
  {  // A wall between them: two rooms.
    RoomMap map;
    map.addObservation(main_part, with_plane);
    EXPECT_TRUE(map.addObservation(leg, with_plane).created);
    EXPECT_EQ(map.rooms().size(), 2u);
  }
  {  // Below open_overlap they stay apart even with no wall between.
    RoomMergingConfig config;
    config.open_overlap = 0.7;
    RoomMap map(config);
    map.addObservation(main_part, kNoWalls);
    EXPECT_TRUE(map.addObservation(leg, kNoWalls).created);
  }
}

TEST(RoomsMerging, AViewSpanningTwoRoomsAWallSeparatesIsToldApart) {
  // A corridor (y 0..2) and a room beside it (y 2.2..10) with their wall y = 2.1 between them
  // (a door in it further along); a view holding both is no room of its own.
  RoomMap map;
  map.addObservation(xCorridor(0, 20, 0, 2, 3, 4), kNoWalls);
  map.addObservation(xCorridor(4, 12, 2.2, 10, 5, 6), kNoWalls);
  WallLandmark between;
  between.id = 9;
  between.normal = Eigen::Vector3d(0, -1, 0);
  between.d = 2.1;
  between.endpoints[0] = {0.0, 2.1};
  between.endpoints[1] = {16.0, 2.1};
  const std::map<uint32_t, WallLandmark> walls = {{9, between}};
  const RoomObservation both = xCorridor(0, 20, 0, 10, 3, 6);
  EXPECT_TRUE(map.spansSeparateRooms(both, walls));
  // Without the wall the two are views of one hall; a view of one of them is no problem.
  EXPECT_FALSE(map.spansSeparateRooms(both, kNoWalls));
  EXPECT_FALSE(map.spansSeparateRooms(xCorridor(0, 20, 0, 2.5, 3, 4), walls));
}

TEST(RoomsMerging, CorridorReDetectedAsRoomBecomesARoom) {
  RoomMap map;
  const auto first = map.addObservation(yCorridor(0, 4, 0, 4, 1, 2), kNoWalls);
  RoomObservation room = yCorridor(0, 4, 0, 4, 1, 2);
  room.kind = RoomKind::kRoom;
  room.walls = {1, 2, 3, 4};
  const auto second = map.addObservation(room, kNoWalls);
  EXPECT_FALSE(second.created);
  EXPECT_TRUE(second.wall_to_wall.empty());
  const MappedRoom& r = map.rooms().at(first.room_id);
  EXPECT_EQ(r.room.kind, RoomKind::kRoom);
  EXPECT_EQ(r.room.walls, (std::array<int, 4>{1, 2, 3, 4}));
}

TEST(RoomsMerging, BaselineAssociatesByCentreDistanceOnly) {
  RoomMap map;
  map.addByCenterDistance(yCorridor(0, 2, 0, 10, 1, 2), kNoWalls, 1.0);
  // No shared free space but centres 0.8 m apart: one room for the baseline...
  const auto near = map.addByCenterDistance(yCorridor(0.8, 2.8, 0, 10, 1, 2), kNoWalls, 1.0);
  EXPECT_FALSE(near.created);
  // ...while 1.2 m is a new room even over the same free space.
  EXPECT_TRUE(map.addByCenterDistance(yCorridor(0, 2, 1.2, 11.2, 1, 2), kNoWalls, 1.0).created);
  EXPECT_EQ(map.rooms().size(), 2u);
}

TEST(RoomsMerging, FollowsWallsFoldedIntoOthers) {
  RoomMap map;
  std::map<uint32_t, WallLandmark> walls;
  WallLandmark w;
  w.id = 9;
  w.normal = Eigen::Vector3d(-1, 0, 0);
  w.d = 2.0;  // x = 2, facing -x
  w.endpoints[0] = {2, 10};
  w.endpoints[1] = {2, 0};
  walls[9] = w;
  const auto a = map.addObservation(yCorridor(0, 2, 0, 10, -1, 9), walls);
  // Landmark 9 folded into 12 (same plane, 5 cm off).
  walls.erase(9);
  w.id = 12;
  w.d = 2.05;
  walls[12] = w;
  map.refreshWalls(walls);
  EXPECT_EQ(map.rooms().at(a.room_id).room.walls[1], 12);
}

}  // namespace
}  // namespace tacs
