// TACS free-space segmentation on a synthetic plan (test/common/room_layout.h): doorways between
// collinear walls, the split of the safe graph when the robot goes through a door (eq. 3), and
// the room merging of a re-visited room.
#include <gtest/gtest.h>

#include <algorithm>

#include "common/room_layout.h"
#include "tacs_graphs/rooms/room_segmenter.h"

namespace tacs {
namespace {

struct Drive {
  std::vector<RoomSegmentationResult> steps;  // one per keyframe, then finish()
  std::vector<RoomAssociation> associations;
};

Drive drive(RoomSegmenter* seg, const test::FloorPlan& plan,
            const std::vector<Eigen::Vector2d>& path) {
  const TraversableMap map = plan.map();
  const WallMap walls = plan.wallMap();
  Drive run;
  for (size_t i = 0; i < path.size(); ++i) {
    const Pose3 pose = poseFromXyzRpy(path[i].x(), path[i].y(), 0.0, 0, 0, 0);
    run.steps.push_back(seg->processKeyframe(static_cast<uint32_t>(i), pose, map, walls));
  }
  run.steps.push_back(seg->finish(map, walls));
  for (const auto& s : run.steps) {
    run.associations.insert(run.associations.end(), s.associations.begin(), s.associations.end());
  }
  return run;
}

// Room A, corridor, room B, entering and leaving through the doors at x = 2..3 and 7..8.
std::vector<Eigen::Vector2d> roomACorridorRoomB() {
  return {{1, 1},   {2, 2},     {3, 1},     {4, 2}, {2.5, 3.5}, {2.5, 4.5}, {4, 5},
          {5.5, 5}, {7.5, 4.5}, {7.5, 3.5}, {8, 2}, {6, 1},     {9, 1}};
}

const MappedRoom* roomNear(const RoomSegmenter& seg, double x, double y) {
  for (const auto& [id, r] : seg.rooms()) {
    if ((r.room.center.head<2>() - Eigen::Vector2d(x, y)).norm() < 0.3) return &r;
  }
  return nullptr;
}

bool allInside(const MappedRoom& r, double x0, double x1, double y0, double y1) {
  for (const auto& p : r.room.free_space) {
    if (p.x() < x0 || p.x() > x1 || p.y() < y0 || p.y() > y1) return false;
  }
  return true;
}

TEST(RoomsTacs, FindsDoorwaysBetweenCollinearWalls) {
  const WallMap walls = test::twoRoomsAndCorridor(1.0).wallMap();
  const auto doorways = findDoorways(walls.landmarks(), TacsFreeSpaceConfig{});
  // Two doors, each seen from both sides of the wall.
  ASSERT_EQ(doorways.size(), 4u);
  int left = 0, right = 0;
  for (const auto& d : doorways) {
    EXPECT_NEAR(d.width(), 1.0, 1e-6);
    const Eigen::Vector2d mid = 0.5 * (d.a + d.b);
    EXPECT_NEAR(mid.y(), 4.0, 1e-6);
    left += std::abs(mid.x() - 2.5) < 1e-6;
    right += std::abs(mid.x() - 7.5) < 1e-6;
  }
  EXPECT_EQ(left, 2);
  EXPECT_EQ(right, 2);
  // Openings wider than max_doorway_width are not doorways.
  TacsFreeSpaceConfig narrow;
  narrow.max_doorway_width = 0.9;
  EXPECT_TRUE(findDoorways(walls.landmarks(), narrow).empty());
}

TEST(RoomsTacs, SplitsTwoRoomsAndCorridorAtTheDoors) {
  RoomSegmenter seg{RoomsConfig{}};
  const Drive run = drive(&seg, test::twoRoomsAndCorridor(1.0), roomACorridorRoomB());
  // Nothing is emitted while the robot stays in room A; room A when it reaches the corridor.
  for (int i = 0; i < 5; ++i) EXPECT_TRUE(run.steps[i].observations.empty()) << i;
  ASSERT_EQ(run.steps[5].observations.size(), 1u);
  EXPECT_GT(run.steps[5].doorways, 0u);
  ASSERT_EQ(seg.rooms().size(), 3u);
  for (const auto& a : run.associations) EXPECT_TRUE(a.created);

  const MappedRoom* a = roomNear(seg, 2.5, 2.0);
  const MappedRoom* b = roomNear(seg, 7.5, 2.0);
  ASSERT_TRUE(a && b);
  EXPECT_EQ(a->room.kind, RoomKind::kRoom);
  EXPECT_EQ(b->room.kind, RoomKind::kRoom);
  EXPECT_TRUE(allInside(*a, 0, 5, 0, 4));
  EXPECT_TRUE(allInside(*b, 5, 10, 0, 4));
  EXPECT_EQ(a->room.keyframe_ids, (std::vector<uint32_t>{0, 1, 2, 3, 4}));
  EXPECT_EQ(b->room.keyframe_ids, (std::vector<uint32_t>{9, 10, 11, 12}));
  // The corridor has open ends: one pair of facing walls, centred between them.
  const MappedRoom* corridor = nullptr;
  for (const auto& [id, r] : seg.rooms()) {
    if (r.room.kind == RoomKind::kCorridor) corridor = &r;
  }
  ASSERT_TRUE(corridor);
  EXPECT_TRUE(corridor->room.hasYPair());
  EXPECT_NEAR(corridor->room.center.y(), 5.0, 0.05);
  EXPECT_TRUE(allInside(*corridor, -2, 12, 4, 6));
}

TEST(RoomsTacs, WritesRoomsAndKeyframeRoomIdsIntoTheSceneGraph) {
  RoomSegmenter seg{RoomsConfig{}};
  drive(&seg, test::twoRoomsAndCorridor(1.0), roomACorridorRoomB());
  SceneGraph graph;
  for (uint32_t k = 0; k < 14; ++k) graph.keyframes[k].id = k;
  seg.writeTo(&graph);
  ASSERT_EQ(graph.rooms.size(), 3u);
  const MappedRoom* a = roomNear(seg, 2.5, 2.0);
  ASSERT_TRUE(a);
  const RoomNode& node = graph.rooms.at(a->id);
  EXPECT_EQ(node.wall_ids.size(), 4u);
  EXPECT_EQ(node.free_space.size(), a->room.free_space.size());
  EXPECT_EQ(graph.keyframes.at(0).room_id, static_cast<int>(a->id));
  EXPECT_EQ(graph.keyframes.at(13).room_id, -1);  // not a keyframe of any room
}

TEST(RoomsTacs, WideOpeningSplitsOnlyThroughTheDoorwayCut) {
  // A 2 m opening (a gap in a half wall): the safe graph alone passes through it.
  const auto plan = test::twoRoomsAndCorridor(2.0);
  const std::vector<Eigen::Vector2d> path = {{1, 1}, {3, 2}, {3, 3.5}, {3, 4.5}, {5, 5}, {6, 5}};
  RoomSegmenter with_cut{RoomsConfig{}};
  drive(&with_cut, plan, path);
  EXPECT_EQ(with_cut.rooms().size(), 2u);

  RoomsConfig no_cut;
  no_cut.tacs.max_doorway_width = 1.5;
  RoomSegmenter without{no_cut};
  const Drive run = drive(&without, plan, path);
  // One region spanning the room and the corridor.
  size_t observations = 0;
  for (const auto& s : run.steps) observations += s.observations.size() + s.rejected.size();
  EXPECT_EQ(observations, 1u);
  for (const auto& [id, r] : without.rooms()) EXPECT_FALSE(allInside(r, 0, 5, 0, 4));
}

TEST(RoomsTacs, DoorwayMappedAfterTheRobotPassedSplitsTheAccumulatedKeyframes) {
  // A 2 m opening the safe graph passes through; its jambs (the y = 4 wall's faces west of x = 7)
  // are mapped only once the robot is in the corridor, as when a door's wall is long on its far
  // side only.
  const test::FloorPlan plan = test::twoRoomsAndCorridor(2.0);
  test::FloorPlan without_jambs = plan;
  auto& faces = without_jambs.faces;
  faces.erase(std::remove_if(faces.begin(), faces.end(),
                             [](const WallSegment& f) {
                               return std::abs(f.endpoints[0].y() - 4.0) < 1e-9 &&
                                      std::abs(f.endpoints[1].y() - 4.0) < 1e-9 &&
                                      std::max(f.endpoints[0].x(), f.endpoints[1].x()) <= 7.0 &&
                                      std::min(f.endpoints[0].x(), f.endpoints[1].x()) >= 0.0;
                             }),
              faces.end());
  ASSERT_EQ(faces.size(), plan.faces.size() - 4);
  const TraversableMap map = plan.map();
  const WallMap early = without_jambs.wallMap(), late = plan.wallMap();
  TacsFreeSpace tacs{TacsFreeSpaceConfig{}};
  const std::vector<Eigen::Vector3d> path = {{1, 1, 0},   {3, 2, 0}, {3, 3.5, 0},
                                             {3, 4.6, 0}, {5, 5, 0}, {6, 5, 0}};
  for (uint32_t k = 0; k < 5; ++k) {
    const auto step = tacs.step(k, path[k], map, early.landmarks());
    EXPECT_TRUE(step.finished.empty()) << k;  // one component: room A and the corridor
  }
  const auto step = tacs.step(5, path[5], map, late.landmarks());
  ASSERT_EQ(step.finished.size(), 1u);
  EXPECT_EQ(step.finished[0].keyframe_ids, (std::vector<uint32_t>{0, 1, 2}));
  for (const auto& p : step.finished[0].points) EXPECT_LT(p.y(), 4.0);
  const auto corridor = tacs.flush(map, late.landmarks());
  ASSERT_TRUE(corridor);
  EXPECT_EQ(corridor->keyframe_ids, (std::vector<uint32_t>{3, 4, 5}));
  EXPECT_EQ(tacs.accumulatedKeyframes(), 0u);
}

TEST(RoomsTacs, NarrowDoorSplitsTheSafeGraphAndHoldsTheKeyframeInIt) {
  RoomsConfig config;
  config.tacs.max_doorway_width = 0.6;  // no doorway cut: only the clearance of eq. 1
  config.tacs.robot_search_radius = 0.25;
  RoomSegmenter seg{config};
  const std::vector<Eigen::Vector2d> path = {{1, 1}, {2, 2}, {2.35, 4.0}, {2.35, 4.6}, {4, 5}};
  const Drive run = drive(&seg, test::twoRoomsAndCorridor(0.7), path);
  EXPECT_TRUE(run.steps[1].robot_inside);
  EXPECT_FALSE(run.steps[2].robot_inside);  // in the 0.7 m door: no safe node
  EXPECT_TRUE(run.steps[2].observations.empty());
  ASSERT_EQ(run.steps[3].observations.size(), 1u);  // room A, on the first corridor keyframe
  EXPECT_EQ(run.steps[3].observations[0].keyframe_ids, (std::vector<uint32_t>{0, 1}));
  EXPECT_EQ(seg.rooms().size(), 2u);
}

TEST(RoomsTacs, RevisitedRoomIsMergedAndReported) {
  RoomSegmenter seg{RoomsConfig{}};
  const std::vector<Eigen::Vector2d> path = {{1, 1},     {3, 2},     {2.5, 3.5}, {2.5, 4.5},
                                             {4, 5},     {2.5, 4.5}, {2.5, 3.5}, {4, 1},
                                             {2.5, 3.5}, {2.5, 4.5}, {1, 5}};
  const Drive run = drive(&seg, test::twoRoomsAndCorridor(1.0), path);
  // Room A twice (the second time associated), the corridor twice (associated too).
  ASSERT_EQ(run.associations.size(), 4u);
  EXPECT_TRUE(run.associations[0].created);
  EXPECT_TRUE(run.associations[1].created);
  EXPECT_FALSE(run.associations[2].created);
  EXPECT_EQ(run.associations[2].room_id, run.associations[0].room_id);
  EXPECT_FALSE(run.associations[3].created);
  EXPECT_EQ(run.associations[3].room_id, run.associations[1].room_id);
  ASSERT_EQ(seg.rooms().size(), 2u);
  const MappedRoom& a = seg.rooms().at(run.associations[0].room_id);
  EXPECT_EQ(a.observations, 2u);
  EXPECT_EQ(a.room.keyframe_ids, (std::vector<uint32_t>{0, 1, 2, 6, 7, 8}));
}

// An L of two corridors 2.4 m wide: along x (y 0..2.4, x 0..10) and along y (x 7.6..10, y up to
// 14). A region of the x corridor's keyframes also holds most of the y corridor (one component),
// so no facing pair bounds 60 % of it; near the robot's path it is the x corridor.
test::FloorPlan cornerOfTwoCorridors() {
  test::FloorPlan p;
  p.lo = {0.0, 0.0};
  p.hi = {10.0, 14.0};
  p.wall({0, 0}, {10, 0}, 1);        // south, seen from the north
  p.wall({0, 2.4}, {7.6, 2.4}, -1);  // north of the x corridor, seen from the south
  p.wall({10, 0}, {10, 14}, 1);      // east, seen from the west
  p.wall({7.6, 2.4}, {7.6, 14}, 1);  // west of the y corridor, seen from the east
  p.voids = {{{0, 2.4}, {7.6, 14}}};
  return p;
}

TEST(RoomsTacs, ACornerRegionIsExtractedNearThePath) {
  const std::vector<Eigen::Vector2d> path = {{1, 1.2}, {2, 1.2}, {3, 1.2}, {4, 1.2}};
  RoomsConfig config;
  config.tacs.path_retry_radius = 0.0;
  RoomSegmenter off{config};
  const Drive rejected = drive(&off, cornerOfTwoCorridors(), path);
  EXPECT_TRUE(rejected.associations.empty());
  ASSERT_EQ(rejected.steps.back().rejected.size(), 1u);

  config.tacs.path_retry_radius = 4.0;
  RoomSegmenter seg{config};
  const Drive run = drive(&seg, cornerOfTwoCorridors(), path);
  ASSERT_EQ(run.associations.size(), 1u);
  const RoomObservation& o = run.steps.back().observations.at(0);
  EXPECT_EQ(o.kind, RoomKind::kCorridor);
  EXPECT_NEAR(o.center.y(), 1.2, 0.1);  // between the x corridor's walls
  EXPECT_EQ(o.keyframe_ids, (std::vector<uint32_t>{0, 1, 2, 3}));
}

TEST(RoomsTacs, LongStaysAreReportedPeriodically) {
  RoomsConfig config;
  config.tacs.max_keyframes_per_observation = 4;
  RoomSegmenter seg{config};
  std::vector<Eigen::Vector2d> path;
  for (int i = 0; i < 9; ++i) path.emplace_back(1.0 + 0.4 * i, 1.0 + 0.2 * (i % 3));
  const Drive run = drive(&seg, test::twoRoomsAndCorridor(1.0), path);
  ASSERT_EQ(run.associations.size(), 3u);  // at keyframes 3 and 7, and the rest at finish()
  EXPECT_TRUE(run.associations[0].created);
  EXPECT_FALSE(run.associations[1].created);
  EXPECT_FALSE(run.associations[2].created);
  EXPECT_EQ(seg.rooms().size(), 1u);
}

}  // namespace
}  // namespace tacs
