#include "tacs_graphs/pipeline/backend_session.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace tacs {
namespace {

using Matrix6d = Eigen::Matrix<double, 6, 6>;

// A wall 2 m ahead of the base (x = 2 in the base frame), facing the robot.
std::vector<WallSegment> wallAhead() {
  WallSegment w;
  w.normal = Eigen::Vector3d(-1.0, 0.0, 0.0);
  w.d = 2.0;
  w.inliers = 200;
  w.endpoints[0] = {2.0, -1.0};
  w.endpoints[1] = {2.0, 1.0};
  w.z_min = -0.5;
  w.z_max = 2.0;
  return {w};
}

PointCloud::Ptr smallCloud() {
  PointCloud::Ptr cloud(new PointCloud);
  for (int i = 0; i < 20; ++i) cloud->push_back(pcl::PointXYZI(2.0f, 0.1f * i, 0.5f, 1.0f));
  return cloud;
}

Matrix6d information() { return Matrix6d::Identity() * 1e4; }

TEST(BackendSession, WallsBeforeTheirKeyframeAreBuffered) {
  BackendSession session{PipelineConfig(), BackendSessionOptions()};
  EXPECT_EQ(session.addWalls(0, {wallAhead(), {}}), BackendSession::Outcome::kBuffered);
  EXPECT_EQ(session.pendingCount(), 1u);
  EXPECT_EQ(session.addKeyframe(0, 1.0, Pose3::Identity(), Matrix6d::Zero(), smallCloud()),
            BackendSession::Outcome::kAdded);
  EXPECT_EQ(session.pendingCount(), 0u);
  EXPECT_EQ(session.sceneGraph().walls.size(), 1u);
  // Walls after their keyframe go straight in.
  EXPECT_EQ(
      session.addKeyframe(1, 2.0, poseFromXyzRpy(0.5, 0, 0, 0, 0, 0), information(), smallCloud()),
      BackendSession::Outcome::kAdded);
  std::vector<WallSegment> nearer = wallAhead();
  nearer[0].d = 1.5;
  for (auto& e : nearer[0].endpoints) e.x() = 1.5;
  EXPECT_EQ(session.addWalls(1, {nearer, {}}), BackendSession::Outcome::kAdded);
  const SceneGraph g = session.sceneGraph();
  ASSERT_EQ(g.walls.size(), 1u);  // the same wall seen twice
  EXPECT_EQ(session.wallObservationCounts().begin()->second, 2u);
  EXPECT_EQ(session.addKeyframe(1, 2.0, Pose3::Identity(), information(), nullptr),
            BackendSession::Outcome::kDuplicate);
}

TEST(BackendSession, LoopsWaitForBothKeyframes) {
  BackendSession session{PipelineConfig(), BackendSessionOptions()};
  session.addKeyframe(0, 1.0, Pose3::Identity(), Matrix6d::Zero(), nullptr);
  LoopEdge loop;
  loop.from = 0;
  loop.to = 1;
  loop.position = Eigen::Vector3d(1.0, 0.0, 0.0);
  EXPECT_EQ(session.addLoop(loop, information()), BackendSession::Outcome::kBuffered);
  session.addKeyframe(1, 2.0, poseFromXyzRpy(1, 0, 0, 0, 0, 0), information(), nullptr);
  EXPECT_EQ(session.pendingCount(), 0u);
  EXPECT_EQ(session.sceneGraph().loops.size(), 1u);
}

// Two facing walls around the base, 2 m ahead and 2 m behind: a corridor across x.
std::vector<WallSegment> facingWalls() {
  std::vector<WallSegment> walls = wallAhead();
  WallSegment behind = walls[0];
  behind.normal = Eigen::Vector3d(1.0, 0.0, 0.0);
  for (auto& e : behind.endpoints) e.x() = -2.0;
  walls.push_back(behind);
  return walls;
}

// The corridor between the walls of facingWalls() as the room segmenter maps it.
MappedRoom corridorBetween(const SceneGraph& graph, uint32_t id) {
  MappedRoom room;
  room.id = id;
  room.room.kind = RoomKind::kCorridor;
  for (const auto& [wall_id, wall] : graph.walls) {
    int& slot = room.room.walls[wall.normal.x() < 0.0 ? 0 : 1];
    if (slot < 0) slot = static_cast<int>(wall_id);  // the first wall of each facing
  }
  room.room.center = Eigen::Vector3d(0.2, 0.0, 0.0);
  room.room.free_space = {{-1.0, 0.0, 0.0}, {1.0, 0.0, 0.0}};
  room.room.keyframe_ids = {0, 1};
  return room;
}

TEST(BackendSession, MappedRoomsBecomeRoomNodesOfTheOptimisedGraph) {
  BackendSession session{PipelineConfig(), BackendSessionOptions()};
  session.addKeyframe(0, 1.0, Pose3::Identity(), Matrix6d::Zero(), nullptr);
  MappedRoom no_walls;
  no_walls.room.walls = {0, 1, -1, -1};
  EXPECT_FALSE(session.setRoom(no_walls));  // the backend holds no such walls yet
  session.addWalls(0, {facingWalls(), {}});
  session.addKeyframe(1, 2.0, poseFromXyzRpy(0.3, 0, 0, 0, 0, 0), information(), nullptr);
  ASSERT_EQ(session.sceneGraph().walls.size(), 2u);
  EXPECT_TRUE(session.setRoom(corridorBetween(session.sceneGraph(), 5)));
  session.optimize();
  const SceneGraph g = session.sceneGraph();
  ASSERT_EQ(g.rooms.size(), 1u);
  EXPECT_EQ(g.rooms.at(5).kind, RoomKind::kCorridor);
  EXPECT_EQ(g.rooms.at(5).wall_ids.size(), 2u);
  // The corridor factor places the centre midway between its walls (x = 0).
  EXPECT_NEAR(g.rooms.at(5).center.x(), 0.0, 0.05);
  EXPECT_EQ(g.keyframes.at(1).room_id, 5);
  EXPECT_EQ(session.journal().at("rooms").size(), 1u);
}

// After a restart the others send again what they had sent (tacs_graphs/Resync): nothing of it
// may count twice.
TEST(BackendSession, WhatIsSentAgainCountsOnce) {
  BackendSession session{PipelineConfig(), BackendSessionOptions()};
  session.addKeyframe(0, 1.0, Pose3::Identity(), Matrix6d::Zero(), nullptr);
  session.addKeyframe(1, 2.0, poseFromXyzRpy(0.3, 0, 0, 0, 0, 0), information(), nullptr);
  EXPECT_EQ(session.firstIncompleteKeyframe(), 0u);  // no walls of keyframe 0 yet
  EXPECT_EQ(session.addWalls(0, {facingWalls(), {}}), BackendSession::Outcome::kAdded);
  EXPECT_EQ(session.addWalls(0, {facingWalls(), {}}), BackendSession::Outcome::kDuplicate);
  EXPECT_EQ(session.wallObservationCounts().begin()->second, 1u);
  EXPECT_EQ(session.addWalls(1, {}), BackendSession::Outcome::kAdded);  // none is an answer too
  EXPECT_EQ(session.firstIncompleteKeyframe(), 2u);

  LoopEdge loop;
  loop.from = 0;
  loop.to = 1;
  loop.position = Eigen::Vector3d(0.3, 0.0, 0.0);
  EXPECT_EQ(session.addLoop(loop, information()), BackendSession::Outcome::kAdded);
  EXPECT_EQ(session.addLoop(loop, information()), BackendSession::Outcome::kDuplicate);
  EXPECT_EQ(session.sceneGraph().loops.size(), 1u);

  const SceneGraph g = session.sceneGraph();
  const std::vector<uint32_t> ids = {g.walls.begin()->first, std::next(g.walls.begin())->first};
  MappedRoom room = corridorBetween(g, 3);
  ASSERT_TRUE(session.setRoom(room, {{ids[0], ids[1]}}));
  ASSERT_TRUE(session.setRoom(room, {{ids[0], ids[1]}}));
  EXPECT_EQ(session.journal().at("rooms").at(0).at("wall_to_wall").size(), 1u);
  // The room segmenter's complete set without room 3: it is gone.
  EXPECT_EQ(session.retainRooms({4}), 1u);
  EXPECT_EQ(session.roomCount(), 0u);
}

TEST(BackendSession, KeyframeIdsThatNeverArrivedAreReported) {
  BackendSession session{PipelineConfig(), BackendSessionOptions()};
  for (uint32_t id : {0u, 1u, 4u}) {
    session.addKeyframe(id, 1.0 + id, poseFromXyzRpy(0.3 * id, 0, 0, 0, 0, 0),
                        id == 0 ? Matrix6d::Zero() : information(), nullptr);
  }
  EXPECT_EQ(session.missingKeyframes(), (std::vector<uint32_t>{2, 3}));
}

TEST(BackendSession, SaveWritesProductsAndRecoverRestoresTheGraph) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / "tacs_backend_session_test").string();
  std::filesystem::remove_all(dir);
  PipelineConfig config;
  MapExportConfig map_config;
  SceneGraph before;
  {
    BackendSession session(config, BackendSessionOptions());
    for (uint32_t id = 0; id < 4; ++id) {
      session.addKeyframe(id, 1.0 + id, poseFromXyzRpy(0.5 * id, 0, 0, 0, 0, 0),
                          id == 0 ? Matrix6d::Zero() : information(), smallCloud());
      session.addWalls(id, {id == 0 ? facingWalls() : wallAhead(), {}});
    }
    MappedRoom room = corridorBetween(session.sceneGraph(), 0);
    room.room.keyframe_ids = {2, 3};
    ASSERT_TRUE(session.setRoom(room));
    session.optimize();
    session.save(dir, map_config);
    before = session.sceneGraph();
  }
  for (const char* name : {"scene_graph.json", "trajectory_tum.txt", "map.pcd", "map.bt",
                           "backend_journal.json", "run.json"}) {
    EXPECT_TRUE(std::filesystem::exists(dir + "/" + name)) << name;
  }
  const nlohmann::json run = nlohmann::json::parse(std::ifstream(dir + "/run.json"));
  EXPECT_EQ(run.at("status"), "complete");
  EXPECT_EQ(run.at("keyframes"), 4);
  BackendSession restarted{config, BackendSessionOptions()};
  EXPECT_EQ(restarted.recover(dir), 4u);
  const SceneGraph after = restarted.sceneGraph();
  ASSERT_EQ(after.keyframes.size(), 4u);
  EXPECT_TRUE(after.keyframes.at(3).pose().isApprox(before.keyframes.at(3).pose(), 1e-6));
  EXPECT_EQ(after.walls.size(), before.walls.size());
  EXPECT_EQ(after.rooms.size(), 1u);
  EXPECT_EQ(after.keyframes.at(3).room_id, 0);
  // The saved map is part of the recovered map, and new keyframes continue the graph.
  EXPECT_GT(restarted.mapCloud(0.1).size(), 0u);
  EXPECT_EQ(
      restarted.addKeyframe(4, 5.0, poseFromXyzRpy(2.0, 0, 0, 0, 0, 0), information(), nullptr),
      BackendSession::Outcome::kAdded);
  std::filesystem::remove_all(dir);
}

TEST(BackendSession, AWallOnASurfaceSeenOverLeavesTheGraphAndStaysOutAfterRecovery) {
  const std::string dir =
      (std::filesystem::temp_directory_path() / "tacs_backend_session_seen_over").string();
  std::filesystem::remove_all(dir);
  PipelineConfig config;
  config.walls.association.min_wall_observations = 1;  // walls seen from one keyframe here
  BackendSession session{config, BackendSessionOptions()};
  session.addKeyframe(0, 1.0, Pose3::Identity(), Matrix6d::Zero(), smallCloud());
  session.addWalls(0, {facingWalls(), {}});
  ASSERT_EQ(session.sceneGraph().walls.size(), 2u);
  // From the next keyframe (buffered until it arrives) the surface ahead was seen over: a
  // cabinet, not a wall.
  EXPECT_EQ(session.addWalls(1, {{}, wallAhead()}), BackendSession::Outcome::kBuffered);
  session.addKeyframe(1, 2.0, Pose3::Identity(), information(), smallCloud());
  // Both stay plane landmarks; only the one behind is a wall.
  const auto walls = [](const SceneGraph& g) {
    std::vector<WallNode> out;
    for (const auto& [id, w] : g.walls) {
      if (w.is_wall) out.push_back(w);
    }
    return out;
  };
  const SceneGraph g = session.sceneGraph();
  EXPECT_EQ(g.walls.size(), 2u);
  ASSERT_EQ(walls(g).size(), 1u);
  EXPECT_GT(walls(g)[0].normal.x(), 0.0);
  session.save(dir, MapExportConfig());
  BackendSession restarted{config, BackendSessionOptions()};
  EXPECT_EQ(restarted.recover(dir), 2u);
  EXPECT_EQ(walls(restarted.sceneGraph()).size(), 1u);
  std::filesystem::remove_all(dir);
}

TEST(BackendSession, RecoverFromMissingFolderThrowsNamingTheFile) {
  BackendSession session{PipelineConfig(), BackendSessionOptions()};
  try {
    session.recover("/nonexistent/tacs");
    FAIL() << "no exception";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("backend_journal.json"), std::string::npos);
  }
}

}  // namespace
}  // namespace tacs
