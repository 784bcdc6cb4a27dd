#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "common/test_paths.h"
#include "tacs_graphs/common/trajectory_io.h"
#include "tacs_graphs/sim/ground_truth.h"
#include "tacs_graphs/sim/robot_path.h"
#include "tacs_graphs/sim/world.h"
#include "tacs_graphs/sim/world_drawing.h"

namespace tacs::sim {
namespace {

nlohmann::json minimalWorld() {
  return nlohmann::json::parse(R"({
    "name": "t",
    "walls": [{"from": [0, 0], "to": [4, 0]}, {"from": [4, 0], "to": [4, 3], "thickness": 0.2},
              {"from": [4, 3], "to": [0, 3]}, {"from": [0, 3], "to": [0, 0], "z_max": 1.0}],
    "boxes": [{"center": [1, 1, 0.4], "size": [0.5, 0.5, 0.8], "yaw_deg": 30}],
    "floors": [{"polygon": [[0, 0], [4, 0], [4, 3], [0, 3]], "z": 0.0}],
    "ceilings": [{"polygon": [[0, 0], [4, 0], [4, 3], [0, 3]], "z": 2.8}],
    "rooms": [{"id": "a", "kind": "room", "polygon": [[0, 0], [4, 0], [4, 3], [0, 3]]}],
    "trajectory": {"waypoints": [[1, 1.5], [3, 1.5, 0.0]], "speed_mps": 0.5, "laps": 2},
    "sensor": {"model": "os1_64", "rate_hz": 10, "mount_height_m": 0.6,
               "range_noise_std_m": 0.02, "seed": 7}
  })");
}

std::string errorOf(const nlohmann::json& j) {
  try {
    parseWorld(j, "w.json");
  } catch (const WorldError& e) {
    return e.what();
  }
  return "";
}

TEST(SimWorld, ParsesEveryField) {
  const World w = parseWorld(minimalWorld(), "w.json");
  EXPECT_EQ(w.name, "t");
  ASSERT_EQ(w.walls.size(), 4u);
  EXPECT_DOUBLE_EQ(w.walls[1].thickness, 0.2);
  EXPECT_DOUBLE_EQ(w.walls[3].z_max, 1.0);
  EXPECT_DOUBLE_EQ(w.walls[0].z_min, 0.0);
  ASSERT_EQ(w.boxes.size(), 1u);
  EXPECT_DOUBLE_EQ(w.boxes[0].yaw_deg, 30.0);
  EXPECT_DOUBLE_EQ(w.ceilings[0].z, 2.8);
  ASSERT_EQ(w.rooms.size(), 1u);
  EXPECT_EQ(w.rooms[0].id, "a");
  EXPECT_TRUE(std::isnan(w.trajectory.waypoints[0].z()));
  EXPECT_DOUBLE_EQ(w.trajectory.waypoints[1].z(), 0.0);
  EXPECT_EQ(w.trajectory.laps, 2);
  EXPECT_EQ(w.sensor.rings, 64);
  EXPECT_DOUBLE_EQ(w.sensor.vfov_deg, 45.0);
  EXPECT_DOUBLE_EQ(w.sensor.mount_height_m, 0.6);
  EXPECT_EQ(w.sensor.seed, 7u);
}

TEST(SimWorld, ErrorsNameTheJsonPath) {
  auto j = minimalWorld();
  j["walls"][3]["to"] = {1, 2, 3};
  EXPECT_EQ(errorOf(j), "w.json: walls[3].to: expected [x, y]");
  j = minimalWorld();
  j["walls"][1]["tickness"] = 0.1;
  EXPECT_EQ(errorOf(j), "w.json: walls[1].tickness: unknown key");
  j = minimalWorld();
  j["rooms"][0]["kind"] = "hall";
  EXPECT_EQ(errorOf(j), "w.json: rooms[0].kind: expected \"room\" or \"corridor\"");
  j = minimalWorld();
  j["trajectory"]["waypoints"][1] = "x";
  EXPECT_EQ(errorOf(j), "w.json: trajectory.waypoints[1]: expected [x, y] or [x, y, z]");
  j = minimalWorld();
  j["sensor"]["model"] = "hdl64";
  EXPECT_NE(errorOf(j).find("w.json: sensor.model: unknown model"), std::string::npos);
  j = minimalWorld();
  j["boxes"][0]["size"][2] = -1;
  EXPECT_EQ(errorOf(j), "w.json: boxes[0].size: every extent must be > 0");
  j = minimalWorld();
  j.erase("trajectory");
  EXPECT_EQ(errorOf(j), "w.json: trajectory: missing");
  j = minimalWorld();
  j["floors"][0]["polygon"][2] = {4};
  EXPECT_EQ(errorOf(j), "w.json: floors[0].polygon[2]: expected [x, y]");
  j = minimalWorld();
  j["walls"][0]["z_max"] = -1;
  EXPECT_EQ(errorOf(j), "w.json: walls[0].z_max: must be > z_min");
}

TEST(SimWorld, LoadWorldReportsFileProblems) {
  EXPECT_THROW(loadWorld("/nonexistent/w.json"), WorldError);
  const std::string path = ::testing::TempDir() + "/bad_world.json";
  std::ofstream(path) << "{ \"walls\": [ }";
  try {
    loadWorld(path);
    FAIL();
  } catch (const WorldError& e) {
    EXPECT_EQ(std::string(e.what()).rfind(path + ": invalid JSON", 0), 0u) << e.what();
  }
}

TEST(SimWorld, WaypointOverVoidIsRejected) {
  auto j = minimalWorld();
  j["trajectory"]["waypoints"][0] = {10, 10};
  const World w = parseWorld(j, "w.json");
  try {
    RobotPath path(w, 1, "w.json");
    FAIL();
  } catch (const WorldError& e) {
    EXPECT_STREQ(e.what(), "w.json: trajectory.waypoints[0]: not above any floor");
  }
}

TEST(SimWorld, ShippedWorldsLoadAndHaveConsistentRooms) {
  const auto dir = std::filesystem::path(test::sourceDir()) / "worlds";
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().string());
    const World w = loadWorld(entry.path().string());
    RobotPath path(w, 1, entry.path().string());
    EXPECT_GT(path.length(), 5.0);
    EXPECT_FALSE(w.rooms.empty());
    // Every room polygon lies on a floor.
    for (const auto& room : w.rooms) {
      Eigen::Vector2d c = Eigen::Vector2d::Zero();
      for (const auto& p : room.polygon) c += p;
      c /= room.polygon.size();
      bool on_floor = false;
      for (const auto& f : w.floors) on_floor |= pointInPolygon(f.polygon, c);
      EXPECT_TRUE(on_floor) << room.id;
    }
    // The robot (radius 0.25 m) never drives into a wall or an obstacle below its sensor.
    std::vector<Polygon2> blocking;
    for (const auto& wall : w.walls) {
      if (wall.z_min < 0.6 && wall.z_max > 0.05) blocking.push_back(wallFootprint(wall));
    }
    for (const auto& box : w.boxes) {
      if (box.center.z() - 0.5 * box.size.z() < 0.6) blocking.push_back(boxFootprint(box));
    }
    auto distanceToPolygon = [](const Polygon2& poly, const Eigen::Vector2d& p) {
      if (pointInPolygon(poly, p)) return 0.0;
      double d = 1e9;
      for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
        const Eigen::Vector2d ab = poly[i] - poly[j];
        const double t = std::clamp((p - poly[j]).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
        d = std::min(d, (p - poly[j] - t * ab).norm());
      }
      return d;
    };
    for (size_t i = 0; i < path.samples().size(); i += 5) {
      const Eigen::Vector2d p = path.samples()[i].head<2>();
      for (size_t k = 0; k < blocking.size(); ++k) {
        ASSERT_GT(distanceToPolygon(blocking[k], p), 0.25)
            << "path at (" << p.transpose() << ") hits obstacle " << k;
      }
    }
    // Room polygons stay out of the walls (a corner may touch a wall face).
    for (const auto& room : w.rooms) {
      for (const auto& v : room.polygon) {
        for (const auto& wall : w.walls) {
          Polygon2 core = wallFootprint(wall);
          Eigen::Vector2d c = 0.25 * (core[0] + core[1] + core[2] + core[3]);
          for (auto& q : core) q = c + 0.9 * (q - c);  // tolerance for faces touching
          EXPECT_FALSE(pointInPolygon(core, v)) << room.id << " vertex " << v.transpose();
        }
      }
    }
    ++count;
  }
  EXPECT_GE(count, 8);
}

TEST(SimGroundTruth, RoundTrip) {
  const World w = parseWorld(minimalWorld(), "w.json");
  const std::string path = ::testing::TempDir() + "/gt.json";
  writeGroundTruth(path, groundTruthOf(w));
  const GroundTruth gt = readGroundTruth(path);
  EXPECT_EQ(gt.world_name, "t");
  ASSERT_EQ(gt.rooms.size(), 1u);
  EXPECT_EQ(gt.rooms[0].polygon.size(), 4u);
  ASSERT_EQ(gt.walls.size(), 4u);
  EXPECT_DOUBLE_EQ(gt.walls[1].thickness, 0.2);
  EXPECT_TRUE(gt.walls[2].from.isApprox(Eigen::Vector2d(4, 3)));
  auto j = groundTruthToJson(groundTruthOf(w));
  j["rooms"][0].erase("polygon");
  EXPECT_THROW(groundTruthFromJson(j, "gt.json"), WorldError);
}

TEST(TrajectoryIo, TumRoundTripDuplicatesAndErrors) {
  Trajectory t(3);
  for (int i = 0; i < 3; ++i) {
    t[i].stamp = 1000.0 + 0.1 * i;
    t[i].pose = poseFromXyzRpy(i, -i, 0.5, 0.01 * i, 0.0, 0.3 * i);
  }
  const std::string path = ::testing::TempDir() + "/t.tum";
  writeTum(path, t);
  const Trajectory r = readTum(path);
  ASSERT_EQ(r.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(r[i].stamp, t[i].stamp, 1e-9);
    EXPECT_TRUE(r[i].pose.isApprox(t[i].pose, 1e-7));
  }
  std::ofstream(path) << "# c\n1 0 0 0 0 0 0 1\n\n1 5 0 0 0 0 0 1\n2 1 0 0 0 0 0 1\n";
  const Trajectory d = readTum(path);
  ASSERT_EQ(d.size(), 2u);
  EXPECT_DOUBLE_EQ(d[0].pose.translation().x(), 0.0);
  std::ofstream(path) << "1 0 0 0 0 0 0 1\n2 0 0 0 0 0 1\n";
  try {
    readTum(path);
    FAIL();
  } catch (const TrajectoryIoError& e) {
    EXPECT_EQ(std::string(e.what()).find(path + ": line 2:"), 0u) << e.what();
  }
}

TEST(TrajectoryIo, PosesToInterpolateInMustBeSorted) {
  // tacs_offline --poses reads its trajectory this way: an unsorted file names the line.
  const std::string path = ::testing::TempDir() + "/unsorted.tum";
  std::ofstream(path) << "1 0 0 0 0 0 0 1\n# c\n3 0 0 0 0 0 0 1\n2 0 0 0 0 0 0 1\n";
  EXPECT_EQ(readTum(path).size(), 3u);  // a plain read keeps the order it finds
  try {
    readTum(path, /*require_increasing=*/true);
    FAIL();
  } catch (const TrajectoryIoError& e) {
    EXPECT_EQ(std::string(e.what()).find(path + ": line 4: stamp 2.000000 is before"), 0u)
        << e.what();
  }
  EXPECT_THROW(readTum(::testing::TempDir() + "/missing.tum", true), TrajectoryIoError);
}

}  // namespace
}  // namespace tacs::sim
