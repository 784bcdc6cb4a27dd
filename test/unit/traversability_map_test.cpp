// TraversableMap: accumulation of keyframe graphs in the map frame and its queries.
#include <gtest/gtest.h>

#include <set>

#include "common/traversability_scene.h"
#include "tacs_graphs/traversability/traversable_map.h"

namespace tacs {
namespace {

using test::runAt;
using test::ScanRun;
using test::testScene;

size_t countInBox(const TravGraph& g, const std::vector<uint32_t>& ids, double x0, double y0,
                  double x1, double y1) {
  size_t n = 0;
  for (uint32_t i : ids) {
    const Eigen::Vector3d& p = g.nodes[i].position;
    n += (p.x() > x0 && p.x() < x1 && p.y() > y0 && p.y() < y1) ? 1 : 0;
  }
  return n;
}

class TraversableMapTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const test::Scene scene = testScene();
    runs_ = new std::vector<ScanRun>{runAt(scene, 2.5, 1.5, 0.0), runAt(scene, 1.0, 0.5, 0.7),
                                     runAt(scene, 2.0, 6.0, -1.0)};  // the last in room 2
  }
  static void TearDownTestSuite() { delete runs_; }
  static std::vector<ScanRun>* runs_;
};
std::vector<ScanRun>* TraversableMapTest::runs_ = nullptr;

TEST_F(TraversableMapTest, MergesOverlappingKeyframes) {
  TraversableMap map{TraversabilityConfig{}};
  size_t inserted = 0, inserted_edges = 0;
  for (uint32_t k = 0; k < 2; ++k) {
    map.insert((*runs_)[k].result.graph, (*runs_)[k].T_world_base, k);
    inserted += (*runs_)[k].result.graph.nodes.size();
    inserted_edges += (*runs_)[k].result.graph.edges.size();
  }
  const TravGraph& g = map.graph();
  EXPECT_EQ(map.keyframeCount(), 2u);
  EXPECT_LT(g.nodes.size(), inserted);  // the two views overlap
  EXPECT_GT(g.nodes.size(), (*runs_)[0].result.graph.nodes.size() / 2);
  EXPECT_LE(g.edges.size(), inserted_edges);
  // No duplicate edges; edges join traversable nodes.
  std::set<std::pair<uint32_t, uint32_t>> unique(g.edges.begin(), g.edges.end());
  EXPECT_EQ(unique.size(), g.edges.size());
  size_t merged = 0;
  for (uint32_t i = 0; i < g.nodes.size(); ++i) {
    merged += map.observations(i) > 1 ? 1 : 0;
    EXPECT_EQ(g.nodes[i].safe, g.nodes[i].traversable && g.nodes[i].clearance >= 0.4f);
  }
  EXPECT_GT(merged, 100u);
  for (const auto& e : g.edges) {
    EXPECT_TRUE(g.nodes[e.first].traversable && g.nodes[e.second].traversable);
  }
  // Merged nodes lie on the floor of the world (ground-truth poses).
  for (uint32_t i : map.componentAt({2.5, 1.5, 0.0}, false)) {
    EXPECT_NEAR(g.nodes[i].position.z(), 0.0, 0.06)
        << g.nodes[i].position.transpose() << " inferred " << g.nodes[i].inferred << " var "
        << g.nodes[i].variance;
  }
}

TEST_F(TraversableMapTest, ClearanceIsTheMinimumOverObservations) {
  TraversableMap one{TraversabilityConfig{}}, both{TraversabilityConfig{}};
  one.insert((*runs_)[0].result.graph, (*runs_)[0].T_world_base, 0);
  both.insert((*runs_)[0].result.graph, (*runs_)[0].T_world_base, 0);
  both.insert((*runs_)[1].result.graph, (*runs_)[1].T_world_base, 1);
  // Same keyframe first: node i of `one` is node i of `both`.
  for (uint32_t i = 0; i < one.graph().nodes.size(); ++i) {
    EXPECT_LE(both.graph().nodes[i].clearance, one.graph().nodes[i].clearance);
    EXPECT_GE(both.graph().nodes[i].traversable, one.graph().nodes[i].traversable);
  }
}

TEST_F(TraversableMapTest, SafeComponentsSplitAtDoorwaysTraversableDoesNot) {
  TraversableMap map{TraversabilityConfig{}};
  for (uint32_t k = 0; k < runs_->size(); ++k) {
    map.insert((*runs_)[k].result.graph, (*runs_)[k].T_world_base, k);
  }
  const TravGraph& g = map.graph();
  const auto room1 = map.componentAt({2.5, 1.5, 0.0});
  const auto room2 = map.componentAt({2.0, 6.0, 0.0});
  ASSERT_GT(room1.size(), 100u);
  ASSERT_GT(room2.size(), 100u);
  EXPECT_EQ(countInBox(g, room1, -6, 4.2, 10, 8), 0u);   // room 1 stays in room 1
  EXPECT_EQ(countInBox(g, room2, -6, -6, 10, 3.9), 0u);  // room 2 stays in room 2
  // The traversable graph joins them through the doorways.
  const auto all = map.componentAt({2.5, 1.5, 0.0}, false);
  EXPECT_GT(countInBox(g, all, -6, 4.2, 10, 8), 50u);
  const std::set<uint32_t> all_set(all.begin(), all.end());
  EXPECT_TRUE(all_set.count(room2.front()));
  // safeComponents() lists both rooms, largest first, disjoint.
  const auto comps = map.safeComponents();
  ASSERT_GE(comps.size(), 2u);
  for (size_t k = 1; k < comps.size(); ++k) EXPECT_GE(comps[k - 1].size(), comps[k].size());
  std::set<uint32_t> seen;
  for (const auto& c : comps) {
    for (uint32_t i : c) EXPECT_TRUE(seen.insert(i).second);
  }
  // Far from any node: nothing.
  EXPECT_TRUE(map.componentAt({50.0, 50.0, 0.0}).empty());
}

TEST_F(TraversableMapTest, NodesWithinMatchesBruteForce) {
  TraversableMap map{TraversabilityConfig{}};
  map.insert((*runs_)[0].result.graph, (*runs_)[0].T_world_base, 0);
  const Eigen::Vector3d c(1.7, 0.3, 5.0);
  const auto got = map.nodesWithin(c, 1.3);
  std::vector<uint32_t> want;
  for (uint32_t i = 0; i < map.graph().nodes.size(); ++i) {
    if ((map.graph().nodes[i].position - c).head<2>().norm() <= 1.3) want.push_back(i);
  }
  EXPECT_EQ(got, want);
  EXPECT_FALSE(got.empty());
}

TEST_F(TraversableMapTest, UpdatePosesAndReinsertRebuild) {
  TraversableMap map{TraversabilityConfig{}};
  const ScanRun& run = (*runs_)[0];
  map.insert(run.result.graph, run.T_world_base, 7);
  const TravGraph before = map.graph();
  auto total_observations = [&map] {
    uint32_t n = 0;
    for (uint32_t i = 0; i < map.graph().nodes.size(); ++i) n += map.observations(i);
    return n;
  };
  const uint32_t observations_before = total_observations();
  Pose3 moved = run.T_world_base;
  moved.translation() += Eigen::Vector3d(1.0, -0.5, 0.0);
  map.updatePoses({{7, moved}, {99, Pose3::Identity()}});  // unknown ids are ignored
  ASSERT_EQ(map.keyframeCount(), 1u);
  // Same as inserting at the new pose from scratch.
  TraversableMap fresh{TraversabilityConfig{}};
  fresh.insert(run.result.graph, moved, 7);
  ASSERT_EQ(map.graph().nodes.size(), fresh.graph().nodes.size());
  ASSERT_EQ(map.graph().edges, fresh.graph().edges);
  for (uint32_t i = 0; i < fresh.graph().nodes.size(); ++i) {
    EXPECT_TRUE(map.graph().nodes[i].position.isApprox(fresh.graph().nodes[i].position));
  }
  EXPECT_FALSE(map.graph().nodes[0].position.isApprox(before.nodes[0].position));
  // Inserting the same id again replaces the keyframe instead of double counting it.
  map.insert(run.result.graph, run.T_world_base, 7);
  EXPECT_EQ(map.keyframeCount(), 1u);
  EXPECT_EQ(total_observations(), observations_before);
  ASSERT_EQ(map.graph().nodes.size(), before.nodes.size());
  for (uint32_t i = 0; i < map.graph().nodes.size(); ++i) {
    EXPECT_TRUE(map.graph().nodes[i].position.isApprox(before.nodes[i].position));
  }
  map.clear();
  EXPECT_TRUE(map.graph().nodes.empty());
}

// A robot parked at one place for many keyframes: the map keeps the local graphs of
// max_keyframes_per_place old keyframes plus the young ones, and the merged graph is the same.
TEST_F(TraversableMapTest, RevisitsOfAPlaceKeepABoundedNumberOfLocalGraphs) {
  TraversabilityConfig config;
  config.map_retention.max_keyframes_per_place = 3;
  config.map_retention.min_age_keyframes = 5;
  TraversableMap map{config};
  const ScanRun& run = (*runs_)[0];
  std::map<uint32_t, Pose3> poses;
  for (uint32_t id = 0; id < 30; ++id) {
    map.insert(run.result.graph, run.T_world_base, id);
    poses[id] = run.T_world_base;
  }
  EXPECT_EQ(map.keyframeCount(), 3u + 5u);
  map.updatePoses(poses);  // rebuilds from the kept local graphs only
  TraversableMap single{config};
  single.insert(run.result.graph, run.T_world_base, 0);
  ASSERT_EQ(map.graph().nodes.size(), single.graph().nodes.size());
  EXPECT_EQ(map.graph().edges, single.graph().edges);
  EXPECT_EQ(map.observations(0), 8u * single.observations(0));  // 8 local graphs merged
}

}  // namespace
}  // namespace tacs
