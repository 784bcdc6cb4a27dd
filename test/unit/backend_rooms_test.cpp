// Rooms in the backend: room and corridor factors on wall landmarks, the optimised centre in the
// scene graph, keyframe room ids, and wall-to-wall edges of room merging.
#include <gtest/gtest.h>

#include "tacs_graphs/backend/backend.h"
#include "tacs_graphs/walls/wall_segment.h"

namespace tacs {
namespace {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

WallSegment face(Eigen::Vector3d n, double d, Eigen::Vector2d a, Eigen::Vector2d b) {
  WallSegment w;
  w.normal = n;
  w.d = d;
  w.endpoints[0] = a;
  w.endpoints[1] = b;
  w.z_max = 2.5;
  w.inliers = 500;
  return w;
}

// An 8 x 6 m room seen from three keyframes; returns the landmark ids x+, x-, y+, y-.
std::vector<uint32_t> buildRoom(Backend* backend) {
  const std::vector<WallSegment> walls = {
      face({1, 0, 0}, 0.0, {0, 6}, {0, 0}), face({-1, 0, 0}, 8.0, {8, 0}, {8, 6}),
      face({0, 1, 0}, 0.0, {0, 0}, {8, 0}), face({0, -1, 0}, 6.0, {8, 6}, {0, 6})};
  std::vector<uint32_t> ids;
  for (uint32_t k = 0; k < 3; ++k) {
    const Pose3 T = poseFromXyzRpy(2.0 + 1.5 * k, 3.0, 0, 0, 0, 0);
    backend->addKeyframe(k, k, T, Matrix6d::Identity() * 100);
    std::vector<WallSegment> seen;
    for (const auto& w : walls) seen.push_back(transformWall(w, T.inverse()));
    ids = backend->addWallObservations(k, seen);
  }
  return ids;
}

MappedRoom roomOn(const std::vector<uint32_t>& ids, bool corridor) {
  MappedRoom r;
  r.id = 3;
  r.room.kind = corridor ? RoomKind::kCorridor : RoomKind::kRoom;
  r.room.walls = {static_cast<int>(ids[0]), static_cast<int>(ids[1]), -1, -1};
  if (!corridor)
    r.room.walls = {static_cast<int>(ids[0]), static_cast<int>(ids[1]), static_cast<int>(ids[2]),
                    static_cast<int>(ids[3])};
  r.room.center = Eigen::Vector3d(3.0, 2.0, 0.0);  // deliberately off: the optimiser centres it
  r.room.free_space = {{2, 2, 0}, {6, 4, 0}};
  r.room.keyframe_ids = {0, 1};
  return r;
}

TEST(BackendRooms, FourWallRoomIsCentredBetweenItsWalls) {
  Backend backend{BackendConfig(), WallAssociationConfig()};
  const auto ids = buildRoom(&backend);
  ASSERT_EQ(ids.size(), 4u);
  ASSERT_TRUE(backend.setRoom(roomOn(ids, false)));
  backend.optimize();
  const SceneGraph g = backend.sceneGraph();
  ASSERT_EQ(g.rooms.size(), 1u);
  const RoomNode& room = g.rooms.at(3);
  EXPECT_EQ(room.kind, RoomKind::kRoom);
  EXPECT_NEAR(room.center.x(), 4.0, 0.01);
  EXPECT_NEAR(room.center.y(), 3.0, 0.01);
  EXPECT_EQ(room.wall_ids.size(), 4u);
  EXPECT_EQ(room.free_space.size(), 2u);
  EXPECT_EQ(g.keyframes.at(0).room_id, 3);
  EXPECT_EQ(g.keyframes.at(1).room_id, 3);
  EXPECT_EQ(g.keyframes.at(2).room_id, -1);
}

TEST(BackendRooms, CorridorIsAnchoredAlongItsWalls) {
  Backend backend{BackendConfig(), WallAssociationConfig()};
  const auto ids = buildRoom(&backend);
  ASSERT_TRUE(backend.setRoom(roomOn(ids, true)));
  backend.optimize();
  const RoomNode& c = backend.sceneGraph().rooms.at(3);
  EXPECT_EQ(c.kind, RoomKind::kCorridor);
  EXPECT_NEAR(c.center.x(), 4.0, 0.01);  // midway between the x walls
  EXPECT_NEAR(c.center.y(), 3.0, 0.05);  // the free-space centre along them
}

TEST(BackendRooms, RemovedRoomLeavesTheGraphAndItsKeyframes) {
  Backend backend{BackendConfig(), WallAssociationConfig()};
  const auto ids = buildRoom(&backend);
  MappedRoom corridor = roomOn(ids, true);
  corridor.id = 5;
  ASSERT_TRUE(backend.setRoom(roomOn(ids, false)));
  ASSERT_TRUE(backend.setRoom(corridor));
  backend.removeRoom(5);  // merged into room 3
  backend.optimize();
  const SceneGraph g = backend.sceneGraph();
  EXPECT_EQ(backend.roomCount(), 1u);
  ASSERT_EQ(g.rooms.count(5), 0u);
  EXPECT_EQ(g.keyframes.at(0).room_id, 3);
  EXPECT_NEAR(g.rooms.at(3).center.x(), 4.0, 0.01);
}

TEST(BackendRooms, RejectsUnknownWallsAndDuplicateWallToWallEdges) {
  Backend backend{BackendConfig(), WallAssociationConfig()};
  const auto ids = buildRoom(&backend);
  MappedRoom bad = roomOn({100, 101, 102, 103}, false);
  EXPECT_FALSE(backend.setRoom(bad));
  EXPECT_EQ(backend.roomCount(), 0u);
  EXPECT_TRUE(backend.addWallToWall(ids[0], ids[2]));
  EXPECT_FALSE(backend.addWallToWall(ids[2], ids[0]));  // the same edge again
  EXPECT_FALSE(backend.addWallToWall(ids[0], ids[0]));
  EXPECT_FALSE(backend.addWallToWall(ids[0], 100));
}

}  // namespace
}  // namespace tacs
