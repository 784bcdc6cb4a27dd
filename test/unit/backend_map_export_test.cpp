#include <gtest/gtest.h>
#include <octomap/octomap.h>
#include <pcl/io/pcd_io.h>

#include <cstdio>

#include "tacs_graphs/backend/backend.h"
#include "tacs_graphs/backend/map_export.h"
#include "tacs_graphs/odometry/preprocess.h"

namespace tacs {
namespace {

PointCloud::Ptr wallPatch() {
  // A 2 x 2 m patch of the plane x = 3 in the keyframe frame, 5 cm spacing.
  auto cloud = std::make_shared<PointCloud>();
  for (double y = -1; y <= 1; y += 0.05) {
    for (double z = 0; z <= 2; z += 0.05) {
      pcl::PointXYZI p;
      p.x = 3.0f;
      p.y = static_cast<float>(y);
      p.z = static_cast<float>(z);
      cloud->push_back(p);
    }
  }
  return cloud;
}

SceneGraph twoKeyframes() {
  SceneGraph g;
  g.keyframes[0].id = 0;
  g.keyframes[1].id = 1;
  g.keyframes[1].setPose(poseFromXyzRpy(0, 0, 0, 0, 0, M_PI));  // looking the other way
  return g;
}

TEST(MapExport, VoxelDownsampleKeepsOnePointPerVoxel) {
  const PointCloud down = voxelDownsample(*wallPatch(), 0.2);
  // 41 x 41 points on a 2 x 2 m patch -> about 11 x 11 voxels of 0.2 m.
  EXPECT_GE(down.size(), 100u);
  EXPECT_LE(down.size(), 144u);
}

TEST(MapExport, MapCloudMovesEachKeyframeByItsPose) {
  KeyframeClouds clouds = {{0, wallPatch()}, {1, wallPatch()}, {7, wallPatch()}};  // 7: no pose
  const PointCloud map = buildMapCloud(twoKeyframes(), clouds, 0.1);
  int at_plus3 = 0, at_minus3 = 0;
  for (const auto& p : map) {
    if (std::abs(p.x - 3.0f) < 0.06f) ++at_plus3;
    if (std::abs(p.x + 3.0f) < 0.06f) ++at_minus3;
  }
  EXPECT_GT(at_plus3, 100);
  EXPECT_GT(at_minus3, 100);
  EXPECT_EQ(at_plus3 + at_minus3, static_cast<int>(map.size()));
}

TEST(MapExport, OctomapMarksTheWallOccupiedAndTheWayFree) {
  const std::string path = ::testing::TempDir() + "/map_export_test.bt";
  MapExportConfig config;
  writeOctomap(path, twoKeyframes(), {{0, wallPatch()}}, config);
  octomap::OcTree tree(path);
  const auto* wall = tree.search(3.0, 0.0, 1.0);
  ASSERT_NE(wall, nullptr);
  EXPECT_TRUE(tree.isNodeOccupied(wall));
  const auto* between = tree.search(1.5, 0.0, 0.5);
  ASSERT_NE(between, nullptr);
  EXPECT_FALSE(tree.isNodeOccupied(between));
  std::remove(path.c_str());
}

// Three keyframes seeing a room's corner from places 0.7 m apart, one wall 20 m away: the leaves
// accumulated apart and set once must give OctoMap's insertPointCloud, leaf for leaf.
void expectOctomapsOwnInsertion(double max_range_m) {
  SceneGraph graph;
  KeyframeClouds clouds;
  auto room = std::make_shared<PointCloud>(*wallPatch());
  for (double x = -2; x <= 3; x += 0.07) {
    pcl::PointXYZI p;
    p.x = static_cast<float>(x), p.y = 1.5f, p.z = 0.5f;
    room->push_back(p);
    p.y = 20.0f;  // beyond a 15 m range: free space only, up to the range
    room->push_back(p);
  }
  for (uint32_t id = 0; id < 3; ++id) {
    graph.keyframes[id].id = id;
    graph.keyframes[id].setPose(poseFromXyzRpy(-0.7 * id, 0.2 * id, 0.1, 0, 0, 0.3 * id));
    clouds[id] = room;
  }
  MapExportConfig config;
  config.octomap_ray_voxel_m = 0.0;
  config.octomap_max_range_m = max_range_m;
  const std::string path = ::testing::TempDir() + "/map_export_equal.bt";
  writeOctomap(path, graph, clouds, config);
  const octomap::OcTree ours(path);
  octomap::OcTree expected(config.octomap_resolution_m);
  for (uint32_t id = 0; id < 3; ++id) {
    const Pose3 pose = graph.keyframes.at(id).pose();
    octomap::Pointcloud scan;
    for (const auto& p : *room) {
      const Eigen::Vector3d q = pose * Eigen::Vector3d(p.x, p.y, p.z);
      scan.push_back(static_cast<float>(q.x()), static_cast<float>(q.y()),
                     static_cast<float>(q.z()));
    }
    const Eigen::Vector3d o = pose.translation();
    expected.insertPointCloud(scan, octomap::point3d(o.x(), o.y(), o.z()),
                              config.octomap_max_range_m, false, /*discretize=*/true);
  }
  size_t leaves = 0, occupied = 0;
  for (auto it = expected.begin_leafs(); it != expected.end_leafs(); ++it) {
    const octomap::OcTreeNode* node = ours.search(it.getKey());
    ASSERT_NE(node, nullptr) << it.getCoordinate();
    // map.bt keeps free or occupied per leaf (OctoMap's binary format).
    EXPECT_EQ(ours.isNodeOccupied(node), expected.isNodeOccupied(*it)) << it.getCoordinate();
    ++leaves;
    occupied += expected.isNodeOccupied(*it);
  }
  EXPECT_GT(leaves, 1000u);
  EXPECT_GT(occupied, 100u);
  expected.toMaxLikelihood();
  expected.prune();
  EXPECT_EQ(ours.size(), expected.size());
  std::remove(path.c_str());
}

TEST(MapExport, OctomapMatchesOctomapsOwnInsertionWithARayToEveryPoint) {
  expectOctomapsOwnInsertion(15.0);
}

TEST(MapExport, OctomapMatchesOctomapsOwnInsertionWithRaysTooLongForTheKeyframeCube) {
  // 60 m rays of 0.1 m leaves: the cube of leaves a keyframe can reach would take 120 MB of bits,
  // so the leaves are marked in the map-wide directory instead.
  expectOctomapsOwnInsertion(60.0);
}

// The share of the floor's leaves (z = 0, 1-4 m around the robot) that map.bt holds occupied when
// the rays start at `sensor_in_base`: one keyframe sees the floor, three more at the same place
// (the robot standing) see the foot of a wall ring 6 m away.
double occupiedFloorShare(const Eigen::Vector3d& sensor_in_base) {
  auto floor = std::make_shared<PointCloud>(), ring = std::make_shared<PointCloud>();
  pcl::PointXYZI p;
  p.z = 0.02f;
  for (double x = -4; x <= 4; x += 0.05) {
    for (double y = -4; y <= 4; y += 0.05) {
      const double r = std::hypot(x, y);
      if (r < 1.0 || r > 4.0) continue;
      p.x = static_cast<float>(x), p.y = static_cast<float>(y);
      floor->push_back(p);
    }
  }
  for (double a = 0; a < 2 * M_PI; a += 0.002) {
    p.x = static_cast<float>(6.0 * std::cos(a)), p.y = static_cast<float>(6.0 * std::sin(a));
    ring->push_back(p);
  }
  SceneGraph graph;
  KeyframeClouds clouds;
  for (uint32_t id = 0; id < 4; ++id) {
    graph.keyframes[id].id = id;
    clouds[id] = id == 0 ? floor : ring;
  }
  const std::string path = ::testing::TempDir() + "/map_export_floor.bt";
  writeOctomap(path, graph, clouds, MapExportConfig(), sensor_in_base);
  const octomap::OcTree tree(path);
  std::remove(path.c_str());
  int occupied = 0;
  for (const auto& q : *floor) {
    const octomap::OcTreeNode* node = tree.search(q.x, q.y, q.z);
    occupied += node && tree.isNodeOccupied(node);
  }
  return static_cast<double>(occupied) / static_cast<double>(floor->size());
}

TEST(MapExport, OctomapRaysStartAtTheSensorNotTheBase) {
  // A base on the floor and its LiDAR 0.5 m above: rays from the base would run along the floor's
  // leaves to the wall's foot and clear them.
  EXPECT_GT(occupiedFloorShare(Eigen::Vector3d(0, 0, 0.5)), 0.99);
  EXPECT_LT(occupiedFloorShare(Eigen::Vector3d::Zero()), 0.2);
}

TEST(MapExport, PcdRoundTripAndEmptyMap) {
  const std::string path = ::testing::TempDir() + "/map_export_test.pcd";
  writePcdAtomically(path, *wallPatch());
  PointCloud back;
  ASSERT_EQ(pcl::io::loadPCDFile(path, back), 0);
  EXPECT_EQ(back.size(), wallPatch()->size());
  writePcdAtomically(path, PointCloud());
  ASSERT_EQ(pcl::io::loadPCDFile(path, back), 0);
  EXPECT_TRUE(back.empty());
  std::remove(path.c_str());
}

// Out along x and back over the same line, a keyframe every 0.5 m: with one cloud per place the
// way back keeps only the clouds of its youngest keyframes; keyframes without clouds are fine.
TEST(MapClouds, KeepsTheCloudsOfTheFirstPassOnAReturn) {
  Backend backend{BackendConfig(), WallAssociationConfig()};
  KeyframeRetentionConfig retention;
  retention.place_radius_m = 0.3;
  retention.max_keyframes_per_place = 1;
  retention.min_age_keyframes = 3;
  MapClouds clouds(retention);
  for (uint32_t id = 0; id < 40; ++id) {
    const double x = id < 20 ? 0.5 * id : 0.5 * (39 - id);
    backend.addKeyframe(id, 0.1 * id, poseFromXyzRpy(x, 0, 0, 0, 0, 0),
                        Backend::Matrix6d::Identity());
    clouds.add(id, id == 5 ? nullptr : wallPatch(), backend);
  }
  // 19 of the first pass (id 5 had none) and the 3 youngest of the way back.
  EXPECT_EQ(clouds.clouds().size(), 19u + 3u);
  for (uint32_t id = 0; id < 20; ++id) EXPECT_EQ(clouds.clouds().count(id), id == 5 ? 0u : 1u);
}

}  // namespace
}  // namespace tacs
