// The voxel free-space baseline (S-Graphs+ style): occupancy slice from keyframe clouds, the
// 0.8 m doorway clearance cut, clusters; and the segmenter running it end to end.
#include <gtest/gtest.h>

#include "common/room_layout.h"
#include "common/synthetic_walls.h"
#include "tacs_graphs/common/config.h"
#include "tacs_graphs/pipeline/pipeline_config.h"
#include "tacs_graphs/rooms/room_segmenter.h"
#include "tacs_graphs/rooms/voxel_free_space.h"

namespace tacs {
namespace {

const Eigen::Vector3d kSensor(0, 0, 0.5);

// Rooms [0,5]x[0,4] and [5,10]x[0,4]; the partition x = 5 has a 1 m door at y 1..2.
PointCloud sceneFrom(const Pose3& T_map_base) {
  test::SyntheticScene scene;
  scene.spacing = 0.08;
  scene.twoRoomsWithDoor();
  scene.transform(T_map_base.inverse());
  return scene.cloud;
}

test::FloorPlan twoRoomsPlan() {
  test::FloorPlan p;
  p.wall({0, 0}, {10, 0}, 1);
  p.wall({10, 0}, {10, 4}, 1);
  p.wall({10, 4}, {0, 4}, 1);
  p.wall({0, 4}, {0, 0}, 1);
  p.wall({5, 0}, {5, 1});
  p.wall({5, 2}, {5, 4});
  return p;
}

TEST(RoomsVoxel, DoorwayClearanceSplitsTwoRooms) {
  VoxelFreeSpace voxels{VoxelFreeSpaceConfig{}};
  const Pose3 a = poseFromXyzRpy(2.5, 2.5, 0, 0, 0, 0), b = poseFromXyzRpy(7.5, 2.5, 0, 0, 0, 0);
  voxels.integrate(0, sceneFrom(a), a, kSensor);
  voxels.integrate(1, sceneFrom(b), b, kSensor);
  const auto clusters = voxels.clusters();
  ASSERT_EQ(clusters.size(), 2u);
  for (const auto& c : clusters) {
    ASSERT_EQ(c.keyframe_ids.size(), 1u);
    const bool left = c.keyframe_ids[0] == 0;
    for (const auto& p : c.points) {
      EXPECT_TRUE(left ? p.x() < 5.1 : p.x() > 4.9) << p.transpose();
      EXPECT_GT(p.y(), -0.1);
      EXPECT_LT(p.y(), 4.1);
    }
    // Most of the room's 20 m^2 is free space.
    EXPECT_GT(c.points.size() * 0.01, 14.0);
  }
}

TEST(RoomsVoxel, WiderClearanceNeverCutsALargerDoor) {
  VoxelFreeSpaceConfig config;
  config.doorway_clearance = 0.3;  // the 1 m door keeps a 0.4 m wide core: one cluster
  VoxelFreeSpace voxels{config};
  const Pose3 a = poseFromXyzRpy(2.5, 2.5, 0, 0, 0, 0), b = poseFromXyzRpy(7.5, 2.5, 0, 0, 0, 0);
  voxels.integrate(0, sceneFrom(a), a, kSensor);
  voxels.integrate(1, sceneFrom(b), b, kSensor);
  EXPECT_EQ(voxels.clusters().size(), 1u);
}

TEST(RoomsVoxel, SegmenterFindsBothRooms) {
  RoomsConfig config;
  config.method = RoomMethod::kVoxel;
  config.voxel.update_every_keyframes = 2;
  RoomSegmenter seg(config, DominantAxesConfig{}, poseFromXyzRpy(0, 0, kSensor.z(), 0, 0, 0));
  const test::FloorPlan plan = twoRoomsPlan();
  const WallMap walls = plan.wallMap();
  const TraversableMap unused{TraversabilityConfig{}};
  const Pose3 a = poseFromXyzRpy(2.5, 2.5, 0, 0, 0, 0), b = poseFromXyzRpy(7.5, 2.5, 0, 0, 0, 0);
  const PointCloud ca = sceneFrom(a), cb = sceneFrom(b);
  EXPECT_TRUE(seg.processKeyframe(0, a, unused, walls, &ca).observations.empty());
  const auto r = seg.processKeyframe(1, b, unused, walls, &cb);
  EXPECT_EQ(r.observations.size(), 2u);
  ASSERT_EQ(seg.rooms().size(), 2u);
  for (const auto& [id, room] : seg.rooms()) {
    EXPECT_EQ(room.room.kind, RoomKind::kRoom);
    EXPECT_NEAR(room.room.center.y(), 2.0, 1e-6);
    const double x = room.room.center.x();
    EXPECT_TRUE(std::abs(x - 2.5) < 1e-6 || std::abs(x - 7.5) < 1e-6) << x;
  }
  // A second clustering of the same map associates both clusters to the mapped rooms.
  const auto again = seg.finish(unused, walls);
  ASSERT_EQ(again.associations.size(), 2u);
  for (const auto& as : again.associations) EXPECT_FALSE(as.created);
  EXPECT_EQ(seg.rooms().size(), 2u);
}

TEST(RoomsVoxel, VoxelMethodWithoutCloudReportsIt) {
  RoomsConfig config;
  config.method = RoomMethod::kVoxel;
  RoomSegmenter seg(config);
  const TraversableMap unused{TraversabilityConfig{}};
  const auto r = seg.processKeyframe(0, Pose3::Identity(), unused, WallMap{});
  ASSERT_EQ(r.rejected.size(), 1u);
  EXPECT_TRUE(seg.rooms().empty());
}

TEST(RoomsVoxel, ConfigNamesTheBadField) {
  PipelineConfig pipeline;
  std::vector<std::string> unknown;
  try {
    configFromJson(nlohmann::json{{"rooms", {{"method", "octree"}}}}, "t.yaml", &pipeline,
                   &unknown);
    FAIL() << "accepted an unknown method";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("t.yaml: rooms.method: must be tacs, voxel or none"),
              std::string::npos)
        << e.what();
  }
  RoomsConfig config;
  config.method = RoomMethod::kVoxel;
  config.voxel.band_max = 0.1;
  EXPECT_THROW(config.validate(), ConfigError);
}

}  // namespace
}  // namespace tacs
