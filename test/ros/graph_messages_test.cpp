#include "tacs_graphs/ros/graph_messages.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "tacs_graphs/ros/keyframe_input.h"
#include "tacs_graphs/ros/message_conversion.h"
#include "tacs_graphs/ros/scene_graph_markers.h"

namespace tacs {
namespace {

WallSegment makeWall() {
  WallSegment w;
  w.normal = Eigen::Vector3d(0.0, -1.0, 0.0);
  w.d = 2.5;
  w.inliers = 321;
  w.endpoints[0] = {-1.0, 2.5};
  w.endpoints[1] = {3.0, 2.5};
  w.z_min = -0.4;
  w.z_max = 2.2;
  return w;
}

SceneGraph makeGraph() {
  SceneGraph g;
  for (uint32_t id = 0; id < 3; ++id) {
    KeyframeNode kf;
    kf.id = id;
    kf.stamp = 10.0 + id;
    kf.setPose(poseFromXyzRpy(id, 0.5 * id, 0.0, 0.0, 0.0, 0.1 * id));
    kf.room_id = id == 2 ? 7 : -1;
    g.keyframes[id] = kf;
  }
  WallNode w;
  w.id = 4;
  w.normal = Eigen::Vector3d::UnitX();
  w.d = -1.5;
  w.endpoints = {Eigen::Vector2d(1.5, 0.0), Eigen::Vector2d(1.5, 3.0)};
  w.z_range = {0.0, 2.8};
  g.walls[4] = w;
  RoomNode r;
  r.id = 7;
  r.kind = RoomKind::kCorridor;
  r.center = Eigen::Vector3d(3.0, 1.0, 0.0);
  r.wall_ids = {4};
  r.free_space = {Eigen::Vector2d(2.0, 1.0), Eigen::Vector2d(2.5, 1.0)};
  r.keyframe_ids = {2};
  g.rooms[7] = r;
  LoopEdge loop;
  loop.from = 0;
  loop.to = 2;
  loop.position = Eigen::Vector3d(2.0, 1.0, 0.0);
  loop.score = 0.02;
  g.loops.push_back(loop);
  return g;
}

TEST(GraphMessages, WallObservationRoundTrip) {
  const WallSegment w = makeWall();
  const WallSegment back = fromWallObservationMsg(toWallObservationMsg(w));
  EXPECT_TRUE(back.normal.isApprox(w.normal));
  EXPECT_DOUBLE_EQ(back.d, w.d);
  EXPECT_EQ(back.inliers, w.inliers);
  EXPECT_TRUE(back.endpoints[1].isApprox(w.endpoints[1]));
  EXPECT_DOUBLE_EQ(back.z_min, w.z_min);
  EXPECT_DOUBLE_EQ(back.z_max, w.z_max);
}

TEST(GraphMessages, KeyframeRoundTripKeepsPoseInformationAndCloud) {
  PointCloud cloud;
  for (int i = 0; i < 5; ++i) cloud.push_back(pcl::PointXYZI(1.0f * i, 2.0f, 0.5f, 3.0f));
  Eigen::Matrix<double, 6, 6> info = Eigen::Matrix<double, 6, 6>::Identity() * 100.0;
  info(0, 5) = 7.0;
  const Pose3 pose = poseFromXyzRpy(1, 2, 0.1, 0.0, 0.02, 1.2);
  const auto msg =
      toKeyframeMsg(12, 42.5, pose, info, cloud, Eigen::Vector3d(0.1, 0, 0.6), "odom", "base_link");
  EXPECT_EQ(msg.header.frame_id, "odom");
  EXPECT_EQ(msg.cloud.header.frame_id, "base_link");
  const KeyframeInput in = fromKeyframeMsg(msg);
  ASSERT_TRUE(in.ok) << in.error;
  EXPECT_EQ(in.id, 12u);
  EXPECT_DOUBLE_EQ(in.stamp, 42.5);
  EXPECT_TRUE(in.T_odom_base.isApprox(pose, 1e-9));
  EXPECT_TRUE(in.information.isApprox(info));
  ASSERT_EQ(in.cloud->size(), 5u);
  EXPECT_FLOAT_EQ(in.cloud->points[4].x, 4.0f);
  EXPECT_TRUE(in.sensor_in_base.isApprox(Eigen::Vector3d(0.1, 0, 0.6)));
}

TEST(GraphMessages, MalformedKeyframeIsRejectedWithReason) {
  auto msg = toKeyframeMsg(1, 1.0, Pose3::Identity(), Eigen::Matrix<double, 6, 6>::Zero(),
                           PointCloud(), Eigen::Vector3d::Zero(), "odom", "base_link");
  msg.cloud.fields.clear();
  KeyframeInput in = fromKeyframeMsg(msg);
  EXPECT_FALSE(in.ok);
  EXPECT_NE(in.error.find("x/y/z"), std::string::npos) << in.error;
  msg = toKeyframeMsg(1, 1.0, Pose3::Identity(), Eigen::Matrix<double, 6, 6>::Zero(), PointCloud(),
                      Eigen::Vector3d::Zero(), "odom", "base_link");
  msg.odom_pose.position.x = std::nan("");
  in = fromKeyframeMsg(msg);
  EXPECT_FALSE(in.ok);
  EXPECT_NE(in.error.find("pose"), std::string::npos) << in.error;
  msg.odom_pose.position.x = 0.0;
  msg.sensor_origin.z = std::numeric_limits<double>::infinity();
  in = fromKeyframeMsg(msg);
  EXPECT_FALSE(in.ok);
  EXPECT_NE(in.error.find("sensor origin"), std::string::npos) << in.error;
}

TEST(GraphMessages, TraversableGraphRoundTrip) {
  TravGraph g;
  for (int i = 0; i < 3; ++i) {
    TravNode n;
    n.position = Eigen::Vector3d(0.1 * i, 0.2, -0.5);
    n.label = i == 2 ? TravLabel::kNonGround : TravLabel::kGround;
    n.inferred = i == 1;
    n.clearance = 0.25f * i;
    n.traversable = i < 2;  // the edge's ends
    n.safe = i == 1;
    g.nodes.push_back(n);
  }
  g.edges = {{0, 1}};
  g.root = 0;
  const Pose3 pose = poseFromXyzRpy(3, 4, 0, 0, 0, 0.3);
  const auto msg = toTraversableGraphMsg(g, 9, pose, "base_link", 5.0);
  EXPECT_EQ(msg.keyframe_id, 9u);
  EXPECT_DOUBLE_EQ(msg.odom_pose.position.y, 4.0);
  const TravGraph back = fromTraversableGraphMsg(msg);
  ASSERT_EQ(back.nodes.size(), 3u);
  EXPECT_EQ(back.root, 0);
  EXPECT_EQ(back.nodes[2].label, TravLabel::kNonGround);
  EXPECT_TRUE(back.nodes[1].inferred);
  EXPECT_FLOAT_EQ(back.nodes[2].clearance, 0.5f);
  // The flags the traversable map builds free space from.
  EXPECT_TRUE(back.nodes[0].traversable);
  EXPECT_FALSE(back.nodes[0].safe);
  EXPECT_TRUE(back.nodes[1].safe);
  EXPECT_FALSE(back.nodes[2].traversable);
  ASSERT_EQ(back.edges.size(), 1u);
  EXPECT_EQ(back.edges[0].second, 1u);
}

TEST(GraphMessages, TraversableGraphWithoutRootPointsPastTheNodes) {
  TravGraph g;
  g.nodes.resize(2);
  const auto msg = toTraversableGraphMsg(g, 0, Pose3::Identity(), "base_link", 0.0);
  EXPECT_EQ(msg.root_index, 2u);
  EXPECT_EQ(fromTraversableGraphMsg(msg).root, -1);
}

TEST(GraphMessages, SceneGraphRoundTrip) {
  const SceneGraph g = makeGraph();
  const auto msg = toSceneGraphMsg(g, {{4, 11}}, "map", 12.0);
  ASSERT_EQ(msg.walls.size(), 1u);
  EXPECT_EQ(msg.walls[0].observation_count, 11u);
  ASSERT_EQ(msg.rooms.size(), 1u);
  EXPECT_EQ(msg.rooms[0].kind, tacs_graphs::Room::CORRIDOR);
  EXPECT_EQ(msg.rooms[0].wall_ids[0], 4);
  EXPECT_EQ(msg.rooms[0].wall_ids[1], -1);
  const SceneGraph back = fromSceneGraphMsg(msg);
  ASSERT_EQ(back.keyframes.size(), 3u);
  EXPECT_TRUE(back.keyframes.at(2).pose().isApprox(g.keyframes.at(2).pose(), 1e-9));
  EXPECT_EQ(back.keyframes.at(2).room_id, 7);
  EXPECT_DOUBLE_EQ(back.keyframes.at(1).stamp, 11.0);
  ASSERT_EQ(back.walls.count(4), 1u);
  EXPECT_DOUBLE_EQ(back.walls.at(4).d, -1.5);
  EXPECT_TRUE(back.walls.at(4).endpoints[1].isApprox(Eigen::Vector2d(1.5, 3.0)));
  EXPECT_DOUBLE_EQ(back.walls.at(4).z_range[1], 2.8);
  EXPECT_TRUE(msg.walls[0].is_wall);
  EXPECT_TRUE(back.walls.at(4).is_wall);
  SceneGraph other = g;
  other.walls.at(4).is_wall = false;
  EXPECT_FALSE(fromSceneGraphMsg(toSceneGraphMsg(other, {}, "map", 12.0)).walls.at(4).is_wall);
  ASSERT_EQ(back.rooms.count(7), 1u);
  EXPECT_EQ(back.rooms.at(7).kind, RoomKind::kCorridor);
  EXPECT_EQ(back.rooms.at(7).wall_ids, (std::vector<uint32_t>{4}));
  EXPECT_EQ(back.rooms.at(7).free_space.size(), 2u);
  ASSERT_EQ(back.loops.size(), 1u);
  EXPECT_EQ(back.loops[0].to, 2u);
  EXPECT_TRUE(back.loops[0].position.isApprox(Eigen::Vector3d(2.0, 1.0, 0.0)));
}

TEST(GraphMessages, RoomObservationCarriesTheMappedRoomAndItsMerging) {
  MappedRoom room;
  room.id = 4;
  room.room.kind = RoomKind::kCorridor;
  room.room.walls = {3, 7, -1, -1};
  room.room.center = Eigen::Vector3d(1.0, 2.0, 0.1);
  room.room.axes_yaw = 0.2;
  room.room.free_space = {{0.5, 2.0, 0.0}, {1.5, 2.0, 0.2}};
  room.room.keyframe_ids = {1, 2};
  RoomAssociation association;
  association.room_id = 4;
  association.created = false;
  association.wall_to_wall = {{3, 9}};
  const tacs_graphs::RoomObservation msg = toRoomObservationMsg(room, association);
  EXPECT_TRUE(msg.redetected);
  EXPECT_EQ(msg.wall_ids[2], -1);
  const MappedRoom back = fromRoomObservationMsg(msg);
  EXPECT_EQ(back.id, 4u);
  EXPECT_EQ(back.room.kind, RoomKind::kCorridor);
  EXPECT_EQ(back.room.walls, room.room.walls);
  EXPECT_EQ(back.room.wallPairs().size(), 1u);
  EXPECT_TRUE(back.room.center.isApprox(room.room.center));
  EXPECT_DOUBLE_EQ(back.room.axes_yaw, 0.2);
  ASSERT_EQ(back.room.free_space.size(), 2u);
  EXPECT_DOUBLE_EQ(back.room.free_space[1].z(), 0.2);
  EXPECT_EQ(back.room.keyframe_ids, room.room.keyframe_ids);
  EXPECT_EQ(wallToWallPairs(msg), association.wall_to_wall);
}

TEST(GraphMessages, LoopClosureRoundTripsThroughTheBackendEdge) {
  LoopClosure loop;
  loop.from = 2;
  loop.to = 9;
  loop.T_from_to = poseFromXyzRpy(1.0, -0.5, 0.0, 0.0, 0.0, 0.3);
  loop.information = Matrix6d::Identity() * 50.0;
  loop.score = 0.8;
  loop.fitness = 0.01;
  const tacs_graphs::LoopClosure msg = toLoopClosureMsg(loop, 3, "map", 5.0);
  EXPECT_EQ(msg.room_id, 3);
  EXPECT_DOUBLE_EQ(msg.fitness, 0.01);
  EXPECT_TRUE(fromMatrixArray(msg.information).isApprox(loop.information));
  const LoopEdge edge = fromLoopClosureMsg(msg);
  EXPECT_EQ(edge.from, 2u);
  EXPECT_EQ(edge.to, 9u);
  EXPECT_TRUE(edge.relativePose().isApprox(loop.T_from_to, 1e-9));
  EXPECT_DOUBLE_EQ(edge.score, 0.8);
}

TEST(SceneGraphMarkers, DrawsEveryLayer) {
  const auto markers = sceneGraphMarkers(makeGraph(), "map", 1.0);
  ASSERT_FALSE(markers.markers.empty());
  EXPECT_EQ(markers.markers[0].action, visualization_msgs::Marker::DELETEALL);
  std::map<std::string, int> per_ns;
  for (const auto& m : markers.markers) ++per_ns[m.ns];
  EXPECT_EQ(per_ns["keyframes"], 1);
  EXPECT_EQ(per_ns["trajectory"], 1);
  EXPECT_EQ(per_ns["walls"], 1);
  EXPECT_EQ(per_ns["rooms"], 1);
  EXPECT_EQ(per_ns["room_walls"], 1);
  EXPECT_EQ(per_ns["loops"], 1);
  EXPECT_EQ(per_ns["room_floors"], 1);
  for (const auto& m : markers.markers) {
    if (m.ns == "room_floors") {
      // The floor grows from the free space at x = 2-2.5 m up to the wall at x = 1.5, not past.
      ASSERT_FALSE(m.points.empty());
      double min_x = 1e9;
      for (const auto& p : m.points) min_x = std::min(min_x, p.x);
      EXPECT_GE(min_x, 1.4);
      EXPECT_LT(min_x, 1.8);
    }
    if (m.ns == "walls") {
      // The wall runs along y over 3 m at x = 1.5.
      EXPECT_NEAR(m.scale.x, 3.0, 1e-9);
      EXPECT_NEAR(m.pose.position.x, 1.5, 1e-9);
      EXPECT_NEAR(m.pose.position.z, 1.4, 1e-9);
    }
  }
}

TEST(SceneGraphMarkers, APriorMapShowsItsReobservedRoomsInItsFrame) {
  const SceneGraph prior = makeGraph();
  const uint32_t prior_room = prior.rooms.begin()->first;
  const auto markers = priorMapMarkers(prior, {{42, prior_room}, {43, 999}}, "prior_map", 1.0);
  int pillars = 0;
  std::string label;
  for (const auto& m : markers.markers) {
    EXPECT_EQ(m.header.frame_id, "prior_map");
    if (m.ns != "matched_rooms") continue;
    if (m.type == visualization_msgs::Marker::CYLINDER) ++pillars;
    if (m.type == visualization_msgs::Marker::TEXT_VIEW_FACING) label = m.text;
  }
  EXPECT_EQ(pillars, 1);  // room 999 is no prior room: nothing drawn for it
  EXPECT_EQ(label, "prior " + std::to_string(prior_room) + " = room 42");
}

}  // namespace
}  // namespace tacs
