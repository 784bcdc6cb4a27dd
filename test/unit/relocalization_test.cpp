// Relocalization in a prior map: the prior's files, placing a session by its room, refusing
// ambiguous and foreign places, pairing and merging rooms.
#include <gtest/gtest.h>
#include <pcl/common/common.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/box_room.h"
#include "tacs_graphs/backend/map_export.h"
#include "tacs_graphs/odometry/preprocess.h"
#include "tacs_graphs/relocalization/prior_session.h"
#include "tacs_graphs/sim/robot_path.h"

namespace tacs {
namespace {

namespace fs = std::filesystem;

constexpr double kPi = 3.14159265358979323846;

/// The room's cloud in the world frame, from a few sensor positions inside it.
PointCloud roomMap(const test::BoxRoom& scene, unsigned seed) {
  PointCloud all;
  const Eigen::Vector2d spots[] = {{2.5, 3.0}, {5.0, 3.5}, {7.5, 2.5}};
  for (const auto& s : spots) {
    const Pose3 T = poseFromXyzRpy(s.x(), s.y(), 1.0, 0.0, 0.0, 0.3 * seed);
    PointCloud scan = test::renderScan(scene, T, seed++, 16, 900, 0.01);
    for (auto& p : scan.points) p.getVector3fMap() = T.cast<float>() * p.getVector3fMap();
    all += scan;
  }
  return voxelDownsample(all, 0.05);
}

/// A graph with one room: free space on a 0.5 m grid inside the scene's room, in the frame
/// T_frame_world.
SceneGraph roomGraph(const test::BoxRoom& scene, const Pose3& T_frame_world) {
  SceneGraph g;
  RoomNode room;
  room.id = 3;
  for (double x = scene.room.lo.x() + 0.5; x < scene.room.hi.x() - 0.4; x += 0.5) {
    for (double y = scene.room.lo.y() + 0.5; y < scene.room.hi.y() - 0.4; y += 0.5) {
      room.free_space.push_back((T_frame_world * Eigen::Vector3d(x, y, 0.0)).head<2>());
    }
  }
  room.center = T_frame_world * (0.5 * (scene.room.lo + scene.room.hi));
  g.rooms[room.id] = room;
  KeyframeNode kf;
  kf.setPose(T_frame_world * poseFromXyzRpy(5.0, 3.5, 0.0, 0.0, 0.0, 0.0));
  g.keyframes[0] = kf;
  return g;
}

PointCloud moved(const PointCloud& cloud, const Pose3& T) {
  PointCloud out = cloud;
  for (auto& p : out.points) p.getVector3fMap() = T.cast<float>() * p.getVector3fMap();
  return out;
}

PriorMap priorOf(const test::BoxRoom& scene) {
  PriorMap prior;
  prior.dir = "memory";
  prior.graph = roomGraph(scene, Pose3::Identity());
  prior.points = roomMap(scene, 1);
  return prior;
}

TEST(RoomRelocalizer, PlacesASessionByItsRoom) {
  const test::BoxRoom scene;
  const PriorMap prior = priorOf(scene);
  const Pose3 T_world_session = poseFromXyzRpy(3.0, -2.0, 0.0, 0.0, 0.0, 2.2);
  const Pose3 T_session_world = T_world_session.inverse();
  const SceneGraph session = roomGraph(scene, T_session_world);
  RoomRelocalizer relocalizer(prior, RelocalizationConfig());
  const RelocalizationAttempt a =
      relocalizer.tryRoom(session, moved(roomMap(scene, 7), T_session_world), 3);
  ASSERT_TRUE(a.localized) << a.reason << " best " << a.best.score << " runner-up "
                           << a.runner_up_score;
  const Pose3 error = T_world_session.inverse() * a.best.T_prior_session;
  EXPECT_LT(error.translation().norm(), 0.03);
  EXPECT_LT(rotationAngleDeg(error), 0.3);
  EXPECT_GT(a.best.score, 0.9);
  EXPECT_EQ(a.rejected, a.hypotheses - 1);
}

TEST(RoomRelocalizer, PlacesASessionThatHasNoRoomByItsWalls) {
  const test::BoxRoom scene;
  const PriorMap prior = priorOf(scene);
  const Pose3 T_world_session = poseFromXyzRpy(-4.0, 6.0, 0.0, 0.0, 0.0, -0.9);
  RoomRelocalizer relocalizer(prior, RelocalizationConfig());
  const RelocalizationAttempt a = relocalizer.tryMap(
      moved(roomMap(scene, 11), T_world_session.inverse()), Eigen::Vector3d(1.0, 1.0, 0.0));
  ASSERT_TRUE(a.localized) << a.reason;
  EXPECT_FALSE(a.session_room.has_value());
  const Pose3 error = T_world_session.inverse() * a.best.T_prior_session;
  EXPECT_LT(error.translation().norm(), 0.03);
  EXPECT_LT(rotationAngleDeg(error), 0.3);
  EXPECT_EQ(a.best.prior_room, 3u);
}

TEST(RoomRelocalizer, ASymmetricRoomWaitsInsteadOfGuessing) {
  test::BoxRoom scene;
  scene.obstacles.clear();  // a bare 10 x 7 m box looks the same turned by 180 deg
  const PriorMap prior = priorOf(scene);
  const Pose3 T_session_world = poseFromXyzRpy(1.0, 1.0, 0.0, 0.0, 0.0, 0.4).inverse();
  RoomRelocalizer relocalizer(prior, RelocalizationConfig());
  const RelocalizationAttempt a = relocalizer.tryRoom(roomGraph(scene, T_session_world),
                                                      moved(roomMap(scene, 7), T_session_world), 3);
  EXPECT_FALSE(a.localized);
  EXPECT_EQ(a.reason, "two distinct places fit alike");
  EXPECT_GE(a.hypotheses, 2);
}

TEST(RoomRelocalizer, AnotherBuildingIsNotAPlace) {
  const test::BoxRoom scene;
  const PriorMap prior = priorOf(scene);
  RoomRelocalizer relocalizer(prior, RelocalizationConfig());
  // A room of the same size with its furniture elsewhere.
  test::BoxRoom other;
  other.obstacles = {{{1.0, 4.0, 0.0}, {2.5, 6.5, 2.0}}, {{8.0, 2.0, 0.0}, {8.6, 2.6, 2.8}}};
  const RelocalizationAttempt same_size =
      relocalizer.tryRoom(roomGraph(other, Pose3::Identity()), roomMap(other, 7), 3);
  EXPECT_FALSE(same_size.localized);
  // A room of another shape: no shape hypothesis, and no shift of its walls fits.
  test::BoxRoom corridor;
  corridor.room = {{0.0, 0.0, 0.0}, {20.0, 2.5, 2.8}};
  corridor.obstacles.clear();
  const RelocalizationAttempt narrow =
      relocalizer.tryRoom(roomGraph(corridor, Pose3::Identity()), roomMap(corridor, 7), 3);
  EXPECT_FALSE(narrow.localized);
  EXPECT_LT(narrow.best.score, RelocalizationConfig().min_score);
}

TEST(RoomRelocalizer, PairsRoomsByTheirFreeSpace) {
  const test::BoxRoom scene;
  const SceneGraph prior = roomGraph(scene, Pose3::Identity());
  const Pose3 T_world_session = poseFromXyzRpy(3.0, -2.0, 0.0, 0.0, 0.0, 2.2);
  SceneGraph session = roomGraph(scene, T_world_session.inverse());
  RoomNode elsewhere = session.rooms.at(3);  // a room 30 m away: no prior room there
  elsewhere.id = 8;
  for (auto& p : elsewhere.free_space) p.x() += 30.0;
  session.rooms[8] = elsewhere;
  const auto pairs = pairRooms(session, prior, T_world_session, 0.5);
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs.at(3), 3u);
}

TEST(SceneGraph, TransformedMovesPosesPlanesAndRooms) {
  SceneGraph g = roomGraph(test::BoxRoom(), Pose3::Identity());
  WallNode w;
  w.id = 1;
  w.normal = Eigen::Vector3d(1, 0, 0);
  w.d = -2.0;  // x = 2
  w.endpoints = {Eigen::Vector2d(2, 0), Eigen::Vector2d(2, 5)};
  w.z_range = {0.0, 2.8};
  g.walls[1] = w;
  const Pose3 T = poseFromXyzRpy(1.0, 2.0, 0.5, 0.0, 0.0, kPi / 2);
  const SceneGraph out = g.transformed(T);
  const WallNode& m = out.walls.at(1);
  const Eigen::Vector3d on_wall = T * Eigen::Vector3d(2.0, 1.0, 1.0);
  EXPECT_NEAR(m.normal.dot(on_wall) + m.d, 0.0, 1e-12);
  EXPECT_TRUE(m.endpoints[0].isApprox(Eigen::Vector2d(1.0, 4.0)));
  EXPECT_DOUBLE_EQ(m.z_range[1], 3.3);
  EXPECT_TRUE(out.keyframes.at(0).pose().isApprox(T * g.keyframes.at(0).pose()));
  EXPECT_TRUE(
      out.rooms.at(3).free_space[0].isApprox((T * Eigen::Vector3d(0.5, 0.5, 0.0)).head<2>()));
}

TEST(MergeSceneGraphs, ReobservedRoomsAndWallsKeepTheirPriorIds) {
  const test::BoxRoom scene;
  SceneGraph prior = roomGraph(scene, Pose3::Identity());
  WallNode w;
  w.id = 5;
  w.normal = Eigen::Vector3d(-1, 0, 0);
  w.d = 10.0;  // x = 10, facing the room
  w.endpoints = {Eigen::Vector2d(10, 0), Eigen::Vector2d(10, 7)};
  w.z_range = {0.0, 2.8};
  prior.walls[5] = w;
  prior.rooms[3].wall_ids = {5};
  const Pose3 T_prior_session = poseFromXyzRpy(3.0, -2.0, 0.0, 0.0, 0.0, 2.2);
  SceneGraph session = roomGraph(scene, T_prior_session.inverse());
  SceneGraph seen;  // the prior's wall as the session sees it
  seen.walls[0] = w;
  session.walls[0] = seen.transformed(T_prior_session.inverse()).walls.at(0);
  session.walls[0].id = 0;
  WallNode fresh = session.walls[0];  // a wall the prior never saw, 30 m away
  fresh.id = 1;
  fresh.d -= 30.0;
  session.walls[1] = fresh;
  session.rooms[3].wall_ids = {0, 1};
  RoomNode new_room = session.rooms[3];
  new_room.id = 4;
  new_room.wall_ids = {1};
  session.rooms[4] = new_room;
  const SceneGraph merged = mergeSceneGraphs(prior, session, T_prior_session, {{3, 3}});
  EXPECT_EQ(merged.walls.size(), 2u);  // wall 0 is the prior's wall 5; wall 1 is new
  EXPECT_EQ(merged.rooms.size(), 2u);  // room 3 is the prior's room 3; room 4 is new
  EXPECT_TRUE(merged.walls.count(5) && merged.walls.count(6));
  EXPECT_EQ(merged.rooms.at(4).wall_ids, std::vector<uint32_t>{6});
  EXPECT_EQ(merged.keyframes.size(), 2u);  // the prior's and the session's, under a new id
  EXPECT_EQ(merged.keyframes.at(1).room_id, -1);
}

TEST(OnOnePlane, NormalsOffsetsAndOverlapDecide) {
  WallNode a;
  a.normal = Eigen::Vector3d(1, 0, 0);
  a.d = -2.0;  // x = 2, from y = 0 to 5
  a.endpoints = {Eigen::Vector2d(2, 0), Eigen::Vector2d(2, 5)};
  WallNode b = a;
  b.d = -2.4;  // 0.4 m behind
  EXPECT_FALSE(onOnePlane(a, b, 10.0, 0.3));
  EXPECT_TRUE(onOnePlane(a, b, 10.0, 0.5));
  b = a;
  b.normal = Eigen::Vector3d(std::cos(0.25), std::sin(0.25), 0.0);  // 14 deg off
  EXPECT_FALSE(onOnePlane(a, b, 10.0, 0.3));
  EXPECT_TRUE(onOnePlane(a, b, 20.0, 0.3));
  b = a;
  b.endpoints = {Eigen::Vector2d(2, 6), Eigen::Vector2d(2, 9)};  // 1 m past a's end
  EXPECT_FALSE(onOnePlane(a, b, 20.0, 0.5));
  b.is_wall = !a.is_wall;
  b.endpoints = a.endpoints;
  EXPECT_FALSE(onOnePlane(a, b, 20.0, 0.5));  // a wall and a non-wall plane are never one
}

class PriorMapFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("tacs_prior_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    roomGraph(test::BoxRoom(), Pose3::Identity()).save((dir_ / "scene_graph.json").string());
    writePcdAtomically((dir_ / "map.pcd").string(), roomMap(test::BoxRoom(), 1));
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string loadError() {
    try {
      PriorMap::load(dir_.string());
    } catch (const PriorMapError& e) {
      return e.what();
    }
    return "";
  }
  static std::string read(const fs::path& file) {
    std::ostringstream s;
    s << std::ifstream(file).rdbuf();
    return s.str();
  }
  fs::path dir_;
};

TEST_F(PriorMapFiles, AGoodFolderLoads) {
  const PriorMap prior = PriorMap::load(dir_.string());
  EXPECT_EQ(prior.graph.rooms.size(), 1u);
  EXPECT_GT(prior.points.size(), 1000u);
}

TEST_F(PriorMapFiles, EachBadFileIsNamedAndLeftAsItWas) {
  const fs::path folder = dir_;
  dir_ /= "absent";
  EXPECT_NE(loadError().find("no such folder"), std::string::npos) << loadError();
  dir_ = folder;
  const std::string graph = (dir_ / "scene_graph.json").string();
  const std::string good = read(graph);

  std::ofstream(graph) << "{ \"format\": ";  // cut short
  EXPECT_NE(loadError().find(graph + ": not valid JSON"), std::string::npos) << loadError();
  EXPECT_EQ(read(graph), "{ \"format\": ");

  std::string other_version = good;
  other_version.replace(other_version.find("\"version\": "), 12, "\"version\": 9");
  std::ofstream(graph) << other_version;
  EXPECT_NE(loadError().find(graph + ": version"), std::string::npos) << loadError();

  std::ofstream(graph) << good;
  fs::remove(dir_ / "map.pcd");
  EXPECT_NE(loadError().find("map.pcd: missing"), std::string::npos) << loadError();
  std::ofstream(dir_ / "map.pcd") << "not a point cloud";
  EXPECT_NE(loadError().find("map.pcd: not a readable PCD"), std::string::npos) << loadError();
  writePcdAtomically((dir_ / "map.pcd").string(), roomMap(test::BoxRoom(), 1));
  fs::resize_file(dir_ / "map.pcd", fs::file_size(dir_ / "map.pcd") / 2);  // cut short
  EXPECT_NE(loadError().find("map.pcd: not a readable PCD point cloud (cut short)"),
            std::string::npos)
      << loadError();
  fs::remove(dir_ / "scene_graph.json");
  EXPECT_NE(loadError().find("scene_graph.json: missing"), std::string::npos) << loadError();
}

// The backend node's save beside its own folder: the session in the prior's frame, loadable as
// the next run's prior map; nothing before the session is placed.
TEST_F(PriorMapFiles, APlacedSessionIsSavedAsAPriorMapInThePriorsFrame) {
  const test::BoxRoom scene;
  const Pose3 T_world_session = poseFromXyzRpy(3.0, -2.0, 0.0, 0.0, 0.0, 2.2);
  const SceneGraph session = roomGraph(scene, T_world_session.inverse());
  const PointCloud session_map = moved(roomMap(scene, 7), T_world_session.inverse());
  KeyframeClouds clouds;
  clouds[0].reset(new PointCloud(moved(session_map, session.keyframes.at(0).pose().inverse())));
  const PriorMap loaded = PriorMap::load(dir_.string());
  const std::string prior_graph = read(dir_ / "scene_graph.json");
  for (PriorMode mode : {PriorMode::kMerge, PriorMode::kLocalizeOnly}) {
    SCOPED_TRACE(enumName(mode));
    const fs::path out = dir_ / ("in_prior_" + std::string(enumName(mode)));
    PriorSession prior(loaded, mode, RelocalizationConfig());
    EXPECT_FALSE(prior.writePriorFrameMap(out.string(), session, session_map, 0.05));
    EXPECT_FALSE(fs::exists(out));
    prior.update(session, clouds, 1.0, 5.0);
    ASSERT_TRUE(prior.localized());
    ASSERT_TRUE(prior.writePriorFrameMap(out.string(), session, session_map, 0.05));
    const PriorMap next = PriorMap::load(out.string());
    ASSERT_TRUE(next.graph.rooms.count(3));  // the re-observed room keeps its prior id
    EXPECT_EQ(read(out / "localization.json").find("\"status\": \"localized\""),
              read(out / "localization.json").find("\"status\""));
    // The session's points land on the prior's: the map's extent is the prior's.
    Eigen::Vector4f lo, hi, prior_lo, prior_hi;
    pcl::getMinMax3D(next.points, lo, hi);
    pcl::getMinMax3D(loaded.points, prior_lo, prior_hi);
    EXPECT_LT((lo - prior_lo).head<2>().norm(), 0.1);
    EXPECT_LT((hi - prior_hi).head<2>().norm(), 0.1);
    if (mode == PriorMode::kLocalizeOnly) {
      EXPECT_EQ(read(out / "scene_graph.json"), prior_graph);
      EXPECT_EQ(next.points.size(), loaded.points.size());
    } else {
      EXPECT_EQ(next.graph.keyframes.size(), 2u);  // the prior's and the session's
    }
  }
}

TEST(StartingAtWaypoint, ClosedPathsGoRoundOpenPathsGoBack) {
  sim::TrajectorySpec spec;
  spec.waypoints = {{0, 0, NAN}, {4, 0, NAN}, {4, 3, NAN}, {0, 3, NAN}, {0, 0, NAN}};
  const auto closed = sim::startingAtWaypoint(spec, 2, "w");
  ASSERT_EQ(closed.waypoints.size(), 5u);
  EXPECT_EQ(closed.waypoints.front().head<2>(), Eigen::Vector2d(4, 3));
  EXPECT_EQ(closed.waypoints[2].head<2>(), Eigen::Vector2d(0, 0));
  EXPECT_EQ(closed.waypoints.back().head<2>(), Eigen::Vector2d(4, 3));
  spec.waypoints.pop_back();  // open: 0 -> 1 -> 2 -> 3
  const auto open = sim::startingAtWaypoint(spec, 2, "w");
  ASSERT_EQ(open.waypoints.size(), 5u);  // 2 3 2 1 0
  EXPECT_EQ(open.waypoints[1].head<2>(), Eigen::Vector2d(0, 3));
  EXPECT_EQ(open.waypoints.back().head<2>(), Eigen::Vector2d(0, 0));
  EXPECT_THROW(sim::startingAtWaypoint(spec, 4, "w"), sim::WorldError);
}

}  // namespace
}  // namespace tacs
