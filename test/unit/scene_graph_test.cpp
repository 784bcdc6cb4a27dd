#include "tacs_graphs/scene_graph/scene_graph.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>

namespace tacs {
namespace {

SceneGraph makeGraph() {
  SceneGraph g;
  for (uint32_t i = 0; i < 3; ++i) {
    KeyframeNode kf;
    kf.id = i;
    kf.stamp = 1000.1 + 0.1 * i;
    kf.setPose(poseFromXyzRpy(0.1 * i, 1.0 / 3.0, 0.5, 0.01, -0.02, 0.7 * i));
    kf.room_id = i == 2 ? -1 : 4;
    g.keyframes[i] = kf;
  }
  WallNode w;
  w.id = 7;
  w.normal = Eigen::Vector3d(0.6, 0.8, 0.0);
  w.d = -2.0 / 7.0;
  w.endpoints = {Eigen::Vector2d(0, 1), Eigen::Vector2d(2.5, -1e-9)};
  w.z_range = {0.0, 2.8};
  g.walls[7] = w;
  w.id = 9;  // a cabinet front: a plane landmark, no wall
  w.d = 1.0;
  w.z_range = {0.0, 1.2};
  w.is_wall = false;
  g.walls[9] = w;
  RoomNode r;
  r.id = 4;
  r.kind = RoomKind::kCorridor;
  r.center = Eigen::Vector3d(1, 2, 0);
  r.wall_ids = {7};
  r.free_space = {Eigen::Vector2d(0.1, 0.2), Eigen::Vector2d(0.3, 0.4)};
  r.keyframe_ids = {0, 1};
  g.rooms[4] = r;
  LoopEdge l;
  l.from = 0;
  l.to = 2;
  l.position = Eigen::Vector3d(0.2, 0.1, 0.0);
  l.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitZ()));
  l.score = 0.0123;
  g.loops.push_back(l);
  return g;
}

TEST(SceneGraph, JsonRoundTripIsExact) {
  const SceneGraph g = makeGraph();
  const nlohmann::json j = g.toJson();
  EXPECT_EQ(j["format"], "tacs_graphs/scene_graph");
  const SceneGraph back = SceneGraph::fromJson(j);
  EXPECT_EQ(back.toJson(), j);
  EXPECT_EQ(back.keyframes.at(1).position, g.keyframes.at(1).position);
  EXPECT_EQ(back.walls.at(7).d, g.walls.at(7).d);
  EXPECT_TRUE(back.walls.at(7).is_wall);
  EXPECT_FALSE(back.walls.at(9).is_wall);
  EXPECT_EQ(back.wallCount(), 1u);
  // Graphs saved without the flag hold walls only; a flag of the wrong type names the field.
  nlohmann::json old = j;
  old["walls"][1].erase("is_wall");
  EXPECT_TRUE(SceneGraph::fromJson(old).walls.at(9).is_wall);
  old["walls"][1]["is_wall"] = "no";
  EXPECT_THROW(
      {
        try {
          SceneGraph::fromJson(old);
        } catch (const std::runtime_error& e) {
          EXPECT_NE(std::string(e.what()).find("walls[1].is_wall"), std::string::npos);
          throw;
        }
      },
      std::runtime_error);
  EXPECT_EQ(back.rooms.at(4).kind, RoomKind::kCorridor);
  EXPECT_EQ(back.loops[0].to, 2u);
}

TEST(SceneGraph, TheScanInputOfALiveGraphRoundTrips) {
  SceneGraph g = makeGraph();
  EXPECT_FALSE(g.toJson().contains("input"));  // offline graphs have none
  EXPECT_FALSE(SceneGraph::fromJson(g.toJson()).input);
  g.input = ScanInput{60, 54};
  const nlohmann::json j = g.toJson();
  EXPECT_NEAR(j["input"]["drop_ratio"].get<double>(), 54.0 / 114.0, 1e-12);
  const SceneGraph back = SceneGraph::fromJson(j);
  ASSERT_TRUE(back.input);
  EXPECT_EQ(back.input->scans_received, 60u);
  EXPECT_EQ(back.input->scans_missing, 54u);
  nlohmann::json bad = j;
  bad["input"]["scans_missing"] = -3;
  EXPECT_THROW(SceneGraph::fromJson(bad), std::runtime_error);
}

TEST(SceneGraph, SaveAndLoadRoundTripExactly) {
  const std::string path = ::testing::TempDir() + "/scene_graph_test.json";
  const SceneGraph g = makeGraph();
  g.save(path);
  const SceneGraph back = SceneGraph::load(path);
  EXPECT_EQ(back.toJson(), g.toJson());
  std::remove(path.c_str());
}

TEST(SceneGraph, PoseAccessorsAgree) {
  KeyframeNode kf;
  const Pose3 pose = poseFromXyzRpy(1, 2, 3, 0.1, 0.2, 0.3);
  kf.setPose(pose);
  EXPECT_TRUE(kf.pose().isApprox(pose, 1e-12));
}

std::string loadError(nlohmann::json j) {
  try {
    SceneGraph::fromJson(j);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(SceneGraph, ErrorsNameTheField) {
  auto j = makeGraph().toJson();
  j["rooms"][0]["kind"] = "hall";
  EXPECT_EQ(loadError(j), "rooms[0].kind: expected \"room\" or \"corridor\", got \"hall\"");
  j = makeGraph().toJson();
  j["walls"][0]["normal"] = {1, 0};
  EXPECT_EQ(loadError(j), "walls[0].normal: expected 3 numbers, got [1,0]");
  j = makeGraph().toJson();
  j.erase("loops");
  EXPECT_EQ(loadError(j), "loops: missing");
  j = makeGraph().toJson();
  j["format"] = "other";
  EXPECT_NE(loadError(j).find("format"), std::string::npos);
}

TEST(SceneGraph, LoadReportsBrokenJson) {
  const std::string path = ::testing::TempDir() + "/broken_scene_graph.json";
  std::ofstream(path) << "{\"format\": ";
  EXPECT_THROW(SceneGraph::load(path), std::runtime_error);
  std::remove(path.c_str());
}

}  // namespace
}  // namespace tacs
