// Association of wall observations to map landmarks, extent growth and duplicate merging.
#include <gtest/gtest.h>
#include <pcl/common/transforms.h>

#include <cmath>
#include <random>

#include "common/synthetic_walls.h"
#include "tacs_graphs/common/config.h"
#include "tacs_graphs/walls/dominant_axes.h"
#include "tacs_graphs/walls/wall_extractor.h"
#include "tacs_graphs/walls/wall_map.h"

namespace tacs {
namespace {

constexpr double kDeg = M_PI / 180.0;

// The rules below other than the observation count, tested on landmarks seen once.
WallAssociationConfig oneView() {
  WallAssociationConfig config;
  config.min_wall_observations = 1;
  return config;
}

// A vertical wall observation on the line through a and b, normal facing the origin.
WallSegment observation(const Eigen::Vector2d& a, const Eigen::Vector2d& b, uint32_t inliers) {
  WallSegment w;
  const Eigen::Vector2d dir = (b - a).normalized();
  w.normal = Eigen::Vector3d(-dir.y(), dir.x(), 0.0);
  w.d = -w.normal.head<2>().dot(a);
  if (w.d < 0.0) {
    w.normal = -w.normal;
    w.d = -w.d;
  }
  w.endpoints[0] = a;
  w.endpoints[1] = b;
  w.z_min = 0.0;
  w.z_max = 2.5;
  w.inliers = inliers;
  return w;
}

TEST(WallMap, FromSceneGraphKeepsTheBackendsIdsAndPlanes) {
  SceneGraph graph;
  WallNode wall;
  wall.id = 3;
  wall.normal = Eigen::Vector3d(0.0, -1.0, 0.0);
  wall.d = 7.0;  // the plane y = 7, seen from below
  wall.endpoints = {Eigen::Vector2d(9.0, 7.0), Eigen::Vector2d(11.0, 7.0)};
  wall.z_range = {0.0, 2.5};
  graph.walls[3] = wall;
  wall.id = 8;
  wall.d = 9.0;
  graph.walls[8] = wall;
  const WallMap map = wallMapFromSceneGraph(graph, {{3, 4}});
  ASSERT_EQ(map.landmarks().size(), 2u);
  const WallLandmark& lm = map.landmarks().at(3);
  EXPECT_EQ(lm.id, 3u);
  EXPECT_NEAR(lm.d, 7.0, 1e-12);
  EXPECT_NEAR(lm.length(), 2.0, 1e-12);
  EXPECT_DOUBLE_EQ(lm.z_max, 2.5);
  EXPECT_EQ(lm.observations, 4u);
  EXPECT_EQ(map.landmarks().at(8).observations, 1u);  // count unknown
  // The mirrored map still associates: the same wall seen again is landmark 3, a new one gets
  // an id after the backend's.
  WallMap copy = map;
  const Pose3 T = poseFromXyzRpy(10, 5, 0, 0, 0, 90 * kDeg);
  const auto seen = copy.associate({observation({2, -1}, {2, 1}, 300)}, T);
  EXPECT_EQ(seen[0].landmark_id, 3u);
  const auto other = copy.associate({observation({2, -1}, {2, 1}, 300)},
                                    poseFromXyzRpy(10, -5, 0, 0, 0, -90 * kDeg));
  EXPECT_TRUE(other[0].created);
  EXPECT_EQ(other[0].landmark_id, 9u);
}

TEST(WallMap, ObservationsMoveToTheMapFrameAndGrowOneLandmark) {
  WallMap map;
  // Robot at (10, 5) turned by 90 deg sees a wall 2 m ahead (base x = 2) from y -1..1.
  const Pose3 T = poseFromXyzRpy(10, 5, 0, 0, 0, 90 * kDeg);
  const auto first = map.associate({observation({2, -1}, {2, 1}, 300)}, T);
  ASSERT_EQ(first.size(), 1u);
  EXPECT_TRUE(first[0].created);
  const WallLandmark& lm = map.landmarks().at(first[0].landmark_id);
  EXPECT_NEAR(lm.normal.y(), -1.0, 1e-9);  // faces back towards the robot
  EXPECT_NEAR(lm.d, 7.0, 1e-9);            // the map plane y = 7
  EXPECT_NEAR(lm.length(), 2.0, 1e-9);
  // Moved 1.5 m along the wall, the robot sees an overlapping piece: same landmark, longer.
  const Pose3 T2 = poseFromXyzRpy(11.5, 5, 0, 0, 0, 90 * kDeg);
  const auto second = map.associate({observation({2, -1}, {2, 1}, 300)}, T2);
  EXPECT_FALSE(second[0].created);
  EXPECT_EQ(second[0].landmark_id, first[0].landmark_id);
  ASSERT_EQ(map.landmarks().size(), 1u);
  EXPECT_NEAR(map.landmarks().begin()->second.length(), 3.5, 1e-6);
  EXPECT_EQ(map.landmarks().begin()->second.observations, 2u);
  // The opposite face (normal +y) and a parallel wall 1 m behind are other landmarks.
  const auto third = map.associate({observation({-2, -1}, {-2, 1}, 300)},
                                   poseFromXyzRpy(10, 9, 0, 0, 0, 90 * kDeg));
  EXPECT_TRUE(third[0].created);
  const auto fourth = map.associate({observation({3, -1}, {3, 1}, 300)}, T);
  EXPECT_TRUE(fourth[0].created);
  EXPECT_EQ(map.landmarks().size(), 3u);
}

TEST(WallMap, CollinearWallsBeyondTheGapStayApartAndBridgedPiecesMerge) {
  WallMap map;
  const Pose3 I = Pose3::Identity();
  const auto a = map.associate({observation({-6, 3}, {-2, 3}, 200)}, I);
  const auto b = map.associate({observation({2, 3}, {6, 3}, 200)}, I);
  EXPECT_TRUE(b[0].created);
  EXPECT_EQ(map.landmarks().size(), 2u);
  EXPECT_TRUE(map.mergeDuplicates().empty());  // 4 m apart: two walls
  // A later view covers the gap: it joins one of them, whose extent now touches the other.
  map.associate({observation({-2.2, 3}, {2.2, 3}, 200)}, I);
  ASSERT_EQ(map.landmarks().size(), 2u);
  const auto merges = map.mergeDuplicates();
  ASSERT_EQ(merges.size(), 1u);
  ASSERT_EQ(map.landmarks().size(), 1u);
  const WallLandmark& kept = map.landmarks().begin()->second;
  EXPECT_EQ(merges[0].second, kept.id);
  EXPECT_EQ(merges[0].first, kept.id == a[0].landmark_id ? b[0].landmark_id : a[0].landmark_id);
  EXPECT_NEAR(kept.length(), 12.0, 1e-6);
  EXPECT_EQ(kept.observations, 3u);
}

// The wall y = 3 seen in two pieces 0.3 m apart (within max_gap), after `first` was mapped.
size_t landmarksAfterTwoPieces(const std::vector<WallSegment>& first) {
  WallMap map;
  const Pose3 I = Pose3::Identity();
  map.associate(first, I);
  map.associate({observation({-3, 3}, {-0.15, 3}, 200)}, I);
  map.associate({observation({0.15, 3}, {3, 3}, 200)}, I);
  map.mergeDuplicates();
  return map.landmarks().size();
}

TEST(WallMap, APartitionMeetingAWallKeepsItsTwoSidesApart) {
  // Alone, the pieces are one wall.
  EXPECT_EQ(landmarksAfterTwoPieces({}), 1u);
  // A partition (x = -0.08, 2.5 m long) meets the wall in the gap: the pieces are the walls of
  // two rooms, also for mergeDuplicates().
  EXPECT_EQ(landmarksAfterTwoPieces({observation({-0.08, 2.95}, {-0.08, 0.45}, 200)}), 3u);
  // A box side (0.5 m) against the wall is no partition, nor is a wall behind the line.
  EXPECT_EQ(landmarksAfterTwoPieces({observation({-0.08, 2.95}, {-0.08, 2.45}, 60)}), 2u);
  EXPECT_EQ(landmarksAfterTwoPieces({observation({-0.08, 3.3}, {-0.08, 6}, 200)}), 2u);
}

TEST(WallMap, MergeChainsReportSurvivingIds) {
  WallAssociationConfig cfg;
  cfg.max_gap = 0.5;
  WallMap map(cfg);
  const Pose3 I = Pose3::Identity();
  map.associate({observation({0, 2}, {2, 2}, 100)}, I);  // id 0
  map.associate({observation({3, 2}, {5, 2}, 100)}, I);  // id 1
  map.associate({observation({6, 2}, {8, 2}, 100)}, I);  // id 2
  ASSERT_EQ(map.landmarks().size(), 3u);
  // Optimisation moves the planes slightly; the extents are then widened by one observation each.
  map.associate({observation({1.5, 2}, {3.2, 2}, 100)}, I);
  map.associate({observation({4.8, 2}, {6.2, 2}, 100)}, I);
  const auto merges = map.mergeDuplicates();
  ASSERT_EQ(map.landmarks().size(), 1u);
  const uint32_t kept = map.landmarks().begin()->first;
  EXPECT_EQ(merges.size(), 2u);
  for (const auto& m : merges) {
    EXPECT_EQ(m.second, kept);
    EXPECT_NE(m.first, kept);
  }
}

TEST(WallMap, ALandmarkOnASurfaceSeenOverIsNoWall) {
  WallMap map(oneView());
  const Pose3 T_map_base = Pose3::Identity();
  // A cabinet row at x = 4 (y 0..3) seen over from afar, later seen from too close to see over
  // it: the close observation makes a landmark, which lies on the surface seen over.
  map.addSeenOver({observation({4, 0}, {4, 3}, 100)}, T_map_base);
  ASSERT_EQ(map.seenOverSurfaces().size(), 1u);
  // The wall x = 4.5 behind it (y -2..5) and the cabinet seen close up.
  const auto a = map.associate(
      {observation({4.5, -2}, {4.5, 5}, 300), observation({4.02, 0.2}, {4.02, 2.9}, 80)},
      T_map_base);
  ASSERT_EQ(a.size(), 2u);
  ASSERT_NE(a[0].landmark_id, a[1].landmark_id);
  EXPECT_FALSE(map.isSeenOver(a[0].landmark_id));  // 0.5 m behind the surface: a wall
  EXPECT_TRUE(map.isSeenOver(a[1].landmark_id));
  EXPECT_FALSE(map.isSeenOver(999));
  EXPECT_TRUE(map.isWall(a[0].landmark_id));
  EXPECT_FALSE(map.isWall(a[1].landmark_id));
  const auto walls = map.walls();
  ASSERT_EQ(walls.size(), 1u);
  EXPECT_EQ(walls.begin()->first, a[0].landmark_id);
  // A wall that only overlaps a short surface seen over on its plane (a low cabinet pushed
  // against it, 0.1 m deep) stays a wall: less than half its length is covered.
  map.addSeenOver({observation({4.4, 0}, {4.4, 2}, 50)}, T_map_base);
  EXPECT_FALSE(map.isSeenOver(a[0].landmark_id));
  // Seen over along most of its length, it is not a wall.
  map.addSeenOver({observation({4.45, 2}, {4.45, 4.5}, 50)}, T_map_base);
  EXPECT_TRUE(map.isSeenOver(a[0].landmark_id));
  EXPECT_TRUE(map.walls().empty());
}

TEST(WallMap, AWallSeenReachingHighIsNoBenchInFrontOfIt) {
  // A hall's wall x = 4.5 seen 6 m high, with a bench 0.1 m in front of it along its length that
  // the sensor sees over (its top 0.5 m up): the bench is not the wall's face seen over.
  const Pose3 I = Pose3::Identity();
  WallSegment wall = observation({4.5, -2}, {4.5, 5}, 300);
  wall.z_max = 6.0;
  WallSegment bench = observation({4.4, -2}, {4.4, 5}, 100);
  bench.z_max = 0.5;
  WallMap map(oneView());
  map.addSeenOver({bench}, I);
  const uint32_t id = map.associate({wall}, I)[0].landmark_id;
  EXPECT_FALSE(map.isSeenOver(id));
  EXPECT_TRUE(map.isWall(id));
  // One observation that took in the wall behind a cabinet (its top at the wall's) among nine
  // of the cabinet itself: the mean top stays near the cabinet's, so it stays seen over.
  WallSegment cabinet = observation({4.4, -2}, {4.4, 5}, 100);
  cabinet.z_max = 1.9;
  WallSegment through = cabinet;
  through.z_max = 6.0;
  WallMap cabinets;
  cabinets.addSeenOver({cabinet}, I);
  std::vector<WallSegment> seen(10, cabinet);
  seen[0] = through;
  const uint32_t c = cabinets.associate(seen, I)[0].landmark_id;
  EXPECT_NEAR(cabinets.landmarks().at(c).mean_top, 2.31, 1e-9);
  EXPECT_DOUBLE_EQ(cabinets.landmarks().at(c).z_max, 6.0);
  EXPECT_TRUE(cabinets.isSeenOver(c));
}

TEST(WallMap, AMachineInFrontOfATallerWallIsNoWall) {
  // A hall's wall x = 6.7 seen 6 m high and, 0.7 m or 1.05 m in front of it (the real hall's
  // machine as two odometries place it), the 2.8 m long face of a machine 2 m high: the wall was
  // seen above the machine, which bounds no room.
  const Pose3 I = Pose3::Identity();
  WallSegment wall = observation({6.7, -25}, {6.7, 15}, 900);
  wall.z_max = 6.0;
  for (const double front : {6.0, 5.65}) {
    WallSegment machine = observation({front, -20.7}, {front, -17.9}, 120);
    machine.z_max = 2.0;
    WallMap map(oneView());
    const auto ids = map.associate({wall, machine}, I);
    ASSERT_NE(ids[0].landmark_id, ids[1].landmark_id);
    EXPECT_TRUE(map.standsBeforeATallerWall(ids[1].landmark_id)) << front;
    EXPECT_FALSE(map.isWall(ids[1].landmark_id)) << front;
    EXPECT_TRUE(map.isWall(ids[0].landmark_id)) << front;
  }
  // As high as the wall behind it (a wall of a room's alcove), or further than 1.25 m in front
  // (the next wall of a stepped hall), or beside the wall's end: a wall.
  for (const auto& [front, top] : {std::pair<double, double>{6.0, 5.8}, {5.3, 2.0}}) {
    WallSegment near = observation({front, -20.7}, {front, -17.9}, 120);
    near.z_max = top;
    WallMap m(oneView());
    EXPECT_TRUE(m.isWall(m.associate({wall, near}, I)[1].landmark_id)) << front << " " << top;
  }
  WallSegment beside = observation({6.0, 15.5}, {6.0, 18.5}, 120);
  beside.z_max = 2.0;
  WallMap m(oneView());
  EXPECT_TRUE(m.isWall(m.associate({wall, beside}, I)[1].landmark_id));
}

TEST(WallSegment, ATiltedRoundTripKeepsTheHeightRange) {
  // Into a frame tilted 25 deg (a hand-held sensor) and back: the height range is the wall's,
  // not a box grown by the tilt.
  const WallSegment wall = observation({4, -5}, {4, 5}, 100);
  Pose3 T = Pose3::Identity();
  T.linear() = Eigen::AngleAxisd(25 * kDeg, Eigen::Vector3d::UnitY()).toRotationMatrix() *
               Eigen::AngleAxisd(-10 * kDeg, Eigen::Vector3d::UnitX()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(0.3, -0.2, 1.8);
  const WallSegment back = transformWall(transformWall(wall, T.inverse()), T);
  EXPECT_NEAR(back.z_min, wall.z_min, 1e-9);
  EXPECT_NEAR(back.z_max, wall.z_max, 1e-9);
  EXPECT_NEAR(back.d, wall.d, 1e-9);
  // A level transform moves the range by its height.
  const WallSegment raised = transformWall(wall, Pose3(Eigen::Translation3d(1, 2, 0.5)));
  EXPECT_NEAR(raised.z_min, 0.5, 1e-9);
  EXPECT_NEAR(raised.z_max, 3.0, 1e-9);
}

// A segment on x = `x` (y 0..2.5) facing +x, away from the origin.
WallSegment facingAway(double x) {
  WallSegment w = observation({x, 0}, {x, 2.5}, 100);
  w.normal = Eigen::Vector3d(1, 0, 0);
  w.d = -x;
  return w;
}

TEST(WallMap, TheFrontOfACabinetSeenOverFromBehindIsNoWall) {
  const Pose3 I = Pose3::Identity();
  const WallSegment front = observation({4, 0}, {4, 2.5}, 100);  // x = 4, facing the origin
  // A free-standing cabinet 0.6 m deep whose back (x = 4.6) was seen over from the far side.
  WallMap slab;
  slab.addSeenOver({facingAway(4.6)}, I);
  EXPECT_TRUE(slab.isSeenOver(slab.associate({front}, I)[0].landmark_id));
  // A wall 0.15 m thick with a low cabinet in the next room: that room's face of the wall stands
  // between, so the cabinet front is not the back of this wall.
  WallMap wall;
  wall.associate({facingAway(4.15)}, I);
  wall.addSeenOver({facingAway(4.6)}, I);
  EXPECT_FALSE(wall.isSeenOver(wall.associate({front}, I)[0].landmark_id));
  // Too far behind to be one object.
  WallMap apart;
  apart.addSeenOver({facingAway(5.5)}, I);
  EXPECT_FALSE(apart.isSeenOver(apart.associate({front}, I)[0].landmark_id));
}

TEST(WallMap, LandmarksShorterThanAWallAreNoWallsUntilTheyGrow) {
  WallAssociationConfig config = oneView();
  config.min_wall_length = 1.0;
  WallMap map(config);
  // A pillar face 0.6 m wide, and a wall first seen as a 0.7 m piece.
  const auto a =
      map.associate({observation({3, -0.3}, {3, 0.3}, 60), observation({-2, 1}, {-2, 1.7}, 70)},
                    Pose3::Identity());
  EXPECT_FALSE(map.isWall(a[0].landmark_id));
  EXPECT_FALSE(map.isWall(a[1].landmark_id));
  EXPECT_TRUE(map.walls().empty());
  EXPECT_EQ(map.landmarks().size(), 2u);  // still landmarks
  map.associate({observation({-2, 1.5}, {-2, 3}, 90)}, Pose3::Identity());
  EXPECT_TRUE(map.isWall(a[1].landmark_id));
  ASSERT_EQ(map.walls().size(), 1u);
  config.min_wall_length = -1.0;
  EXPECT_THROW(WallMap{config}, ConfigError);
}

TEST(WallMap, APlaneSeenFromFewerKeyframesThanTheMinimumIsNoWallYet) {
  // A 3.4 m face seen from one keyframe of the real hall (a machine in its corner) came and went
  // between runs; the hall's walls were seen from 26 keyframes or more.
  WallAssociationConfig config;
  config.min_wall_observations = 3;
  WallMap map(config);
  const Pose3 I = Pose3::Identity();
  const uint32_t id = map.associate({observation({5, 13.3}, {5, 16.8}, 90)}, I)[0].landmark_id;
  EXPECT_FALSE(map.isWall(id));
  map.associate({observation({5, 13.5}, {5, 16.5}, 90)}, I);
  EXPECT_FALSE(map.isWall(id));
  EXPECT_TRUE(map.walls().empty());
  map.associate({observation({5, 13.4}, {5, 16.7}, 90)}, I);
  EXPECT_EQ(map.landmarks().at(id).observations, 3u);
  EXPECT_TRUE(map.isWall(id));
  config.min_wall_observations = 0;
  EXPECT_THROW(WallMap{config}, ConfigError);
}

TEST(WallMap, UpdateLandmarkPlaneMovesTheExtentAndKeepsTheFacing) {
  WallMap map;
  const auto a = map.associate({observation({-2, 3}, {2, 3}, 100)}, Pose3::Identity());
  const uint32_t id = a[0].landmark_id;
  // Given with the opposite sign: plane y = 3.2 as (0, 1, 0), d = -3.2.
  map.updateLandmarkPlane(id, {0, 1, 0}, -3.2);
  const WallLandmark& lm = map.landmarks().at(id);
  EXPECT_NEAR(lm.normal.y(), -1.0, 1e-12);
  EXPECT_NEAR(lm.d, 3.2, 1e-12);
  EXPECT_NEAR(lm.endpoints[0].y(), 3.2, 1e-12);
  EXPECT_NEAR(lm.endpoints[1].y(), 3.2, 1e-12);
  EXPECT_NEAR(lm.length(), 4.0, 1e-12);
  map.updateLandmarkPlane(999, {1, 0, 0}, 0.0);  // unknown id: ignored
  EXPECT_EQ(map.landmarks().size(), 1u);
  WallAssociationConfig bad;
  bad.max_plane_distance = 0.0;
  EXPECT_THROW(WallMap{bad}, ConfigError);
}

TEST(WallMap, KeyframesWithNoisyPosesGiveOneLandmarkPerWallFace) {
  test::SyntheticScene scene;
  scene.spacing = 0.07;
  scene.twoRoomsWithDoor();
  WallExtractionConfig ecfg;
  ecfg.max_range = 5.0;  // each keyframe sees only part of the walls
  const WallExtractor extractor(ecfg);
  WallMap map;
  std::mt19937 rng(3);
  std::normal_distribution<double> pos_noise(0.0, 0.03), yaw_noise(0.0, 0.5 * kDeg);
  const double path[][3] = {{1, 1, 0.3},   {2.5, 2, 0.6}, {4, 3, 0.0},  {4.5, 1.5, 0.0},
                            {5.5, 1.5, 0}, {7, 2, 0.4},   {9, 3, 1.2},  {8, 1, -2.0},
                            {6, 2.5, 3.0}, {3, 2.5, 3.1}, {1.5, 3, 2.0}};
  for (const auto& kf : path) {
    const Pose3 T_true = poseFromXyzRpy(kf[0], kf[1], 0.5, 0, 0, kf[2]);
    PointCloud cloud;
    pcl::transformPointCloud(scene.cloud, cloud, T_true.inverse().matrix().cast<float>());
    const auto walls = extractor.extract(cloud).walls;
    const Pose3 T_noisy = poseFromXyzRpy(kf[0] + pos_noise(rng), kf[1] + pos_noise(rng), 0.5, 0, 0,
                                         kf[2] + yaw_noise(rng));
    map.associate(walls, T_noisy);
    map.mergeDuplicates();
  }
  // Faces: x=0 (+x), x=10 (-x), y=0 (+y), y=4 (-y), partition seen from the left (-x) and from
  // the right (+x), each in two pieces split by the door.
  struct Face {
    Eigen::Vector2d n;
    double offset;  // n.p + offset = 0
    int pieces;
  };
  const Face faces[] = {{{1, 0}, 0, 1},  {{-1, 0}, 10, 1}, {{0, 1}, 0, 1},
                        {{0, -1}, 4, 1}, {{-1, 0}, 5, 2},  {{1, 0}, -5, 2}};
  size_t expected = 0;
  for (const auto& f : faces) {
    SCOPED_TRACE(f.n.transpose());
    int found = 0;
    for (const auto& [id, lm] : map.landmarks()) {
      if (lm.normal.head<2>().dot(f.n) > 0.99 && std::abs(lm.d - f.offset) < 0.15) ++found;
    }
    EXPECT_EQ(found, f.pieces);
    expected += f.pieces;
  }
  EXPECT_EQ(map.landmarks().size(), expected);
  // No wall held twice: no two landmarks pass the association gates together.
  EXPECT_TRUE(map.mergeDuplicates().empty());
  // Every landmark was seen from several keyframes.
  for (const auto& [id, lm] : map.landmarks()) EXPECT_GE(lm.observations, 2u) << id;
  // The building axes of the map are the map axes here.
  const DominantAxes axes = estimateDominantAxes(map);
  EXPECT_TRUE(axes.valid);
  EXPECT_NEAR(axes.yaw, 0.0, 1.5 * kDeg);
}

}  // namespace
}  // namespace tacs
