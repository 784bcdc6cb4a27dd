#include "tacs_graphs/pipeline/room_segmentation_session.h"

#include <gtest/gtest.h>

namespace tacs {
namespace {

// A small flat traversable graph around the base: a 3 x 3 grid of safe ground nodes.
TravGraph flatGraph() {
  TravGraph graph;
  for (int i = 0; i < 9; ++i) {
    TravNode n;
    n.position = Eigen::Vector3d(0.4 * (i % 3) - 0.4, 0.4 * (i / 3) - 0.4, 0.0);
    n.normal = Eigen::Vector3d::UnitZ();
    n.label = TravLabel::kGround;
    n.clearance = 5.0f;
    graph.nodes.push_back(n);
    if (i % 3 > 0) graph.edges.emplace_back(i - 1, i);
    if (i >= 3) graph.edges.emplace_back(i - 3, i);
  }
  graph.root = 4;
  return graph;
}

SceneGraph graphWith(uint32_t up_to, double y_offset) {
  SceneGraph graph;
  for (uint32_t id = 0; id <= up_to; ++id) {
    graph.keyframes[id].id = id;
    graph.keyframes[id].setPose(poseFromXyzRpy(0.5 * id, y_offset, 0, 0, 0, 0));
  }
  return graph;
}

TEST(RoomSegmentationSession, KeyframesWaitForTheBackendInIdOrder) {
  RoomSegmentationSession session{PipelineConfig(), RoomSegmentationOptions()};
  for (uint32_t id = 0; id < 3; ++id) {
    session.addGraph(id, 1.0 + id, poseFromXyzRpy(0.5 * id, 0, 0, 0, 0, 0), flatGraph());
  }
  session.processReady();
  EXPECT_EQ(session.keyframesSegmented(), 0u);
  EXPECT_EQ(session.pendingCount(), 3u);
  session.setSceneGraph(graphWith(1, 0.0));  // the backend holds keyframes 0 and 1
  session.processReady();
  EXPECT_EQ(session.keyframesSegmented(), 2u);
  EXPECT_EQ(session.pendingCount(), 1u);
  // A graph sent again for a segmented keyframe is ignored.
  session.addGraph(1, 2.0, Pose3::Identity(), flatGraph());
  EXPECT_EQ(session.pendingCount(), 1u);
}

TEST(RoomSegmentationSession, AKeyframeTheBackendNeverPlacesGoesInAfterTheWait) {
  RoomSegmentationOptions options;
  options.max_wait_keyframes = 2;
  RoomSegmentationSession session(PipelineConfig(), options);
  for (uint32_t id = 0; id < 5; ++id) {
    session.addGraph(id, 1.0 + id, poseFromXyzRpy(0.5 * id, 0, 0, 0, 0, 0), flatGraph());
    session.processReady();
  }
  // Keyframes 0..2 have 2 newer ones beyond the wait; 3 and 4 still wait.
  EXPECT_EQ(session.keyframesSegmented(), 2u);
  EXPECT_EQ(session.pendingCount(), 3u);
}

TEST(RoomSegmentationSession, MovedKeyframesReposeTheMapAndWallsMirrorTheBackend) {
  RoomSegmentationSession session{PipelineConfig(), RoomSegmentationOptions()};
  for (uint32_t id = 0; id < 2; ++id) {
    session.addGraph(id, 1.0 + id, poseFromXyzRpy(0.5 * id, 0, 0, 0, 0, 0), flatGraph());
  }
  SceneGraph graph = graphWith(1, 0.0);
  WallNode wall;
  wall.id = 6;
  wall.normal = Eigen::Vector3d(-1, 0, 0);
  wall.d = 3.0;
  wall.endpoints = {Eigen::Vector2d(3, -1), Eigen::Vector2d(3, 1)};
  graph.walls[6] = wall;
  session.setSceneGraph(graph);
  session.processReady();
  EXPECT_EQ(session.wallMap().landmarks().count(6), 1u);
  EXPECT_EQ(session.reposes(), 0u);
  session.setSceneGraph(graphWith(1, 0.01));  // below the re-posing threshold
  EXPECT_EQ(session.reposes(), 0u);
  session.setSceneGraph(graphWith(1, 0.3));
  EXPECT_EQ(session.reposes(), 1u);
  EXPECT_TRUE(session.wallMap().landmarks().empty());
}

}  // namespace
}  // namespace tacs
