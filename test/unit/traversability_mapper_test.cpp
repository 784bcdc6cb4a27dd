// TraversabilityMapper on analytically ray-cast scans of a scene with a box, a wall with a 0.8 m
// and a 1.0 m doorway, a drop-off, a step and a half wall (paper Sec. III-A, III-B-2).
#include "tacs_graphs/traversability/traversability_mapper.h"

#include <gtest/gtest.h>
#include <pcl/kdtree/kdtree_flann.h>

#include <functional>
#include <random>

#include "common/traversability_scene.h"
#include "tacs_graphs/common/config.h"

namespace tacs {
namespace {

using test::runAt;
using test::ScanRun;
using test::Scene;
using test::testScene;

// Nodes reachable from the root over edges for which `keep` holds for both ends.
std::vector<char> component(const TravGraph& g, const std::function<bool(const TravNode&)>& keep) {
  std::vector<std::vector<uint32_t>> adj(g.nodes.size());
  for (const auto& e : g.edges) {
    adj[e.first].push_back(e.second);
    adj[e.second].push_back(e.first);
  }
  std::vector<char> in(g.nodes.size(), 0);
  if (g.root < 0 || !keep(g.nodes[g.root])) return in;
  std::vector<uint32_t> stack{static_cast<uint32_t>(g.root)};
  in[g.root] = 1;
  while (!stack.empty()) {
    const uint32_t s = stack.back();
    stack.pop_back();
    for (uint32_t t : adj[s]) {
      if (!in[t] && keep(g.nodes[t])) {
        in[t] = 1;
        stack.push_back(t);
      }
    }
  }
  return in;
}

// Counts traversable/safe-connected nodes whose world position lies in the box.
int countIn(const ScanRun& run, const std::vector<char>& in, double x0, double y0, double x1,
            double y1) {
  int n = 0;
  for (uint32_t i = 0; i < run.result.graph.nodes.size(); ++i) {
    const Eigen::Vector3d p = run.world(i);
    if (in[i] && p.x() > x0 && p.x() < x1 && p.y() > y0 && p.y() < y1) ++n;
  }
  return n;
}

struct Pose2 {
  double x, y, yaw;
};
// Several poses so the doorways fall at different offsets in the robot-centred grid.
const std::vector<Pose2> kPoses = [] {
  std::vector<Pose2> p = {{2.5, 1.5, 0.0}, {2.3, 1.7, 0.3}, {2.0, 2.0, -0.5}, {2.6, 1.2, 1.2}};
  if (const char* n = std::getenv("TRAV_SWEEP")) {
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0, 1);
    for (int i = 0; i < std::atoi(n); ++i)
      p.push_back({1.5 + 2 * u(rng), 1.0 + 1.5 * u(rng), 6.28 * u(rng)});
  }
  return p;
}();

TEST(TraversabilityMapper, GroundPrecisionAndRecall) {
  const Scene scene = testScene();
  for (const Pose2& pose : kPoses) {
    const ScanRun run = runAt(scene, pose.x, pose.y, pose.yaw);
    SCOPED_TRACE(run.result.warning);
    EXPECT_TRUE(run.result.warning.empty());
    std::vector<char> predicted(run.scan.cloud.size(), 0);
    for (const auto& p : run.result.ground->points) predicted[static_cast<size_t>(p.intensity)] = 1;
    double tp = 0, fp = 0, fn = 0;
    for (size_t i = 0; i < predicted.size(); ++i) {
      tp += predicted[i] && run.scan.is_ground[i];
      fp += predicted[i] && !run.scan.is_ground[i];
      fn += !predicted[i] && run.scan.is_ground[i];
    }
    const double precision = tp / (tp + fp), recall = tp / (tp + fn);
    std::printf("[ground] pose (%.1f, %.1f, %.1f): precision %.4f recall %.4f (%zu points)\n",
                pose.x, pose.y, pose.yaw, precision, recall, predicted.size());
    EXPECT_GE(precision, 0.95);
    EXPECT_GE(recall, 0.95);
    EXPECT_EQ(run.result.ground_points + run.result.nonground_points, run.scan.cloud.size());
  }
}

// A VLP-16 0.5 m above the floor of a 2 m wide corridor: the lowest scan line on each wall is
// level, 0.23 m up and alone in its nodes, yet no floor; the floor at the walls' feet shares
// nodes with the walls, yet is ground.
TEST(TraversabilityMapper, CorridorWallFeetAreNotGroundTheFloorBesideThemIs) {
  Scene scene;
  scene.floor(-12, -1.0, 12, 1.0, 0.0);
  scene.add(-12, -1.2, 0, 12, -1.0, 2.5, false);
  scene.add(-12, 1.0, 0, 12, 1.2, 2.5, false);
  for (double yaw : {0.0, 0.4}) {
    const Pose3 T_world_base = poseFromXyzRpy(0, 0, 0, 0, 0, yaw);
    const test::SyntheticScan scan =
        test::castScan(scene, test::LidarModel::vlp16(),
                       T_world_base * poseFromXyzRpy(0, 0, 0.5, 0, 0, 0), T_world_base);
    const TraversabilityResult result = TraversabilityMapper({}).process(scan.cloud);
    size_t on_wall = 0, found = 0, truth = 0;
    for (const auto& p : result.ground->points) {
      on_wall += p.z > 0.1f;  // the wall's foot, up to a few cm, is part of the floor
      found += scan.is_ground[static_cast<size_t>(p.intensity)];
    }
    for (uint8_t g : scan.is_ground) truth += g;
    SCOPED_TRACE("yaw " + std::to_string(yaw));
    EXPECT_EQ(on_wall, 0u);
    EXPECT_GE(static_cast<double>(found) / truth, 0.97);
  }
}

// The sensor's blind disc (no floor seen within 1.9 m of a VLP-16 0.5 m up) is filled, but not
// through a wall 1 m away: the room behind it stays unknown and out of the traversable graph.
TEST(TraversabilityMapper, BlindDiscStopsAtAWall) {
  Scene scene;
  scene.floor(-8, -8, 8, 8, 0.0);
  scene.add(-8, 1.0, 0, 8, 1.15, 2.5, false);
  const test::SyntheticScan scan = test::castScan(
      scene, test::LidarModel::vlp16(), poseFromXyzRpy(0, 0, 0.5, 0, 0, 0), Pose3::Identity());
  const TraversabilityResult result = TraversabilityMapper({}).process(scan.cloud);
  size_t blind = 0, beyond = 0;
  for (const TravNode& v : result.graph.nodes) {
    if (v.position.y() < 0.9 && v.position.head<2>().norm() < 1.5) blind += v.traversable;
    if (v.position.y() > 1.2) beyond += v.label == TravLabel::kGround || v.traversable;
  }
  EXPECT_GT(blind, 20u);  // the disc on the robot's side is filled
  EXPECT_EQ(beyond, 0u);
}

TEST(TraversabilityMapper, HazardsAreNotConnectedDoorwaysAre) {
  const Scene scene = testScene();
  for (const Pose2& pose : kPoses) {
    SCOPED_TRACE("pose " + std::to_string(pose.x) + " " + std::to_string(pose.y) + " " +
                 std::to_string(pose.yaw));
    const ScanRun run = runAt(scene, pose.x, pose.y, pose.yaw);
    const TravGraph& g = run.result.graph;
    ASSERT_GE(g.root, 0) << run.result.warning;
    const auto trav = component(g, [](const TravNode& v) { return v.traversable; });
    const auto safe = component(g, [](const TravNode& v) { return v.safe; });
    // The main room is reached, in both graphs.
    EXPECT_GT(countIn(run, trav, -2.5, -1.0, 5.5, 3.5), 200);
    EXPECT_GT(countIn(run, safe, -2.0, -1.0, 5.0, 3.0), 100);
    // Drop-off (lower level), step platform, floor beyond the half wall: never connected.
    EXPECT_EQ(countIn(run, trav, 6.2, -6, 10, 0.8), 0);
    EXPECT_EQ(countIn(run, trav, 6.2, 1.2, 10, 3.9), 0);
    EXPECT_EQ(countIn(run, trav, -6, -6, -3.3, 3.9), 0);
    // Both doorways stay connected in the traversable graph: room 2 right behind each.
    EXPECT_GT(countIn(run, trav, 0.6, 4.4, 1.4, 5.2), 0) << "0.8 m doorway";
    EXPECT_GT(countIn(run, trav, 3.6, 4.4, 4.6, 5.2), 0) << "1.0 m doorway";
    // ... while the safe graph splits at them: nothing beyond the wall.
    EXPECT_EQ(countIn(run, safe, -6, 4.2, 10, 8), 0);
    // Traversable centroids keep off obstacle points; a safe node has clearance >= lambda_o.
    PointCloud::Ptr flat(new PointCloud(*run.result.obstacles));
    for (auto& o : flat->points) o.z = 0.0f;
    pcl::KdTreeFLANN<pcl::PointXYZI> tree;
    tree.setInputCloud(flat);
    std::vector<int> idx(1);
    std::vector<float> d2(1);
    for (const TravNode& v : g.nodes) {
      EXPECT_EQ(v.safe, v.traversable && v.clearance >= 0.4f);
      if (!v.traversable) continue;
      pcl::PointXYZI q;
      q.x = static_cast<float>(v.position.x());
      q.y = static_cast<float>(v.position.y());
      q.z = 0.0f;
      ASSERT_EQ(tree.nearestKSearch(q, 1, idx, d2), 1);
      EXPECT_GT(std::sqrt(d2[0]), 0.05);
    }
    for (const auto& e : g.edges) {
      EXPECT_TRUE(g.nodes[e.first].traversable && g.nodes[e.second].traversable);
      EXPECT_LT(e.first, e.second);
    }
  }
}

TEST(TraversabilityMapper, WideOpeningKeepsTheSafeGraphConnected) {
  // Control for the doorway split: a 2.2 m opening leaves room for lambda_o on both sides.
  const Scene scene = testScene(2.2);
  const ScanRun run = runAt(scene, 3.0, 1.5, 0.2);
  const auto safe = component(run.result.graph, [](const TravNode& v) { return v.safe; });
  EXPECT_GT(countIn(run, safe, 3.6, 4.4, 5.8, 6.0), 3);
  // A larger lambda_o closes it again.
  TraversabilityConfig strict;
  strict.safe_clearance = 1.2;
  const ScanRun closed = runAt(scene, 3.0, 1.5, 0.2, 0.0, strict);
  const auto safe2 = component(closed.result.graph, [](const TravNode& v) { return v.safe; });
  EXPECT_EQ(countIn(closed, safe2, -6, 4.2, 10, 8), 0);
}

TEST(TraversabilityMapper, InferredNodesAreMarkedAndUncertain) {
  const ScanRun run = runAt(testScene(), 2.5, 1.5, 0.0);
  size_t inferred = 0, observed = 0;
  double var_inferred = 0, var_observed = 0;
  for (const TravNode& v : run.result.graph.nodes) {
    if (v.label != TravLabel::kGround) continue;
    if (v.inferred) {
      ++inferred;
      var_inferred += v.variance;
    } else {
      ++observed;
      var_observed += v.variance;
    }
  }
  ASSERT_GT(inferred, 0u);  // at least the blind disc under the robot and the box's shadow
  ASSERT_GT(observed, 0u);
  EXPECT_GT(var_inferred / inferred, var_observed / observed);
  // The node under the robot lies in the sensor's blind disc: inferred, at the floor height.
  const TravNode& root = run.result.graph.nodes[run.result.graph.root];
  EXPECT_NEAR(root.position.z(), 0.0, 0.05);
  EXPECT_LT(root.position.head<2>().norm(), 0.6);
}

TEST(TraversabilityConfig, ValidateNamesTheField) {
  TraversabilityConfig c;
  EXPECT_NO_THROW(c.validate());
  c.resolution = -1;
  try {
    c.validate();
    FAIL() << "no throw";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("traversability.resolution_m"), std::string::npos);
  }
  TraversabilityConfig d;
  d.robot_height = 0.05;
  EXPECT_THROW(TraversabilityMapper{d}, ConfigError);
}

}  // namespace
}  // namespace tacs
