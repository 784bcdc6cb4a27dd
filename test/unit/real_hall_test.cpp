// The real BALM hall (README "Test data"): 89 hand-held OS0-64-like scans at 1 Hz with turns of
// up to 90 deg between scans, and reference poses from a LiDAR-inertial odometry. Run with the
// hand-held preset (config/handheld.yaml), as a user would.
#include <gtest/gtest.h>
#include <pcl/io/pcd_io.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "common/real_data.h"
#include "common/test_paths.h"
#include "tacs_graphs/common/trajectory_io.h"
#include "tacs_graphs/eval/trajectory_metrics.h"
#include "tacs_graphs/pipeline/pipeline.h"
#include "tacs_graphs/walls/wall_segment.h"

namespace tacs {
namespace {

struct HallScan {
  double stamp = 0.0;
  PointCloud cloud;
};

// The scans listed in scans.txt ("index stamp file"), loaded in order.
std::vector<HallScan> loadHall(const std::string& dir) {
  std::ifstream list(dir + "scans.txt");
  std::vector<HallScan> scans;
  std::string line;
  while (std::getline(list, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream ss(line);
    std::string index, file;
    HallScan s;
    ss >> index >> s.stamp >> file;
    EXPECT_EQ(pcl::io::loadPCDFile(dir + file, s.cloud), 0) << file;
    scans.push_back(std::move(s));
  }
  return scans;
}

PipelineConfig handheldConfig() {
  return loadPipelineConfig(test::sourceDir() + "/config/handheld.yaml").config;
}

TEST(RealHall, OdometryFollowsTheHandHeldSensorThroughItsTurns) {
  TACS_DATA_SET_OR_SKIP(dir, "balm_indoor_hall");
  const std::vector<HallScan> scans = loadHall(dir);
  ASSERT_EQ(scans.size(), 89u);
  LidarOdometry odometry(handheldConfig().odometry);
  Trajectory estimate;
  for (const HallScan& s : scans) {
    const OdometryResult r = odometry.process(s.stamp, s.cloud);
    ASSERT_TRUE(r.ok) << "scan at " << s.stamp << ": " << r.error;
    estimate.push_back({s.stamp, r.T_odom_base});
  }
  const AteResult ate = computeAte(estimate, readTum(dir + "poses_tum.txt"), 0.05);
  EXPECT_EQ(ate.pairs, 89u);
  // 74 m walked; before the yaw-hypothesis recovery the track was lost at the first 50 deg turn
  // (ATE 14.9 m).
  EXPECT_LT(ate.rmse, 0.25) << "max " << ate.max;
}

// The hall as one room bounded by its walls, each of the five faces found and no wall elsewhere.
// `T_ref_map` takes the graph's map frame into the reference poses' frame, where the hall's faces
// are listed.
void expectTheHall(const SceneGraph& graph, const Pose3& T_ref_map, const Trajectory& reference) {
  ASSERT_EQ(graph.rooms.size(), 1u);
  // Every wall lies on a face of the hall (normal facing into the hall, n.p + d = 0): no beam,
  // ceiling step, column, shelf frame or bench.
  struct Face {
    const char* name;
    Eigen::Vector2d normal;
    double d;
  };
  const Face faces[] = {{"west", {1, 0}, 22.2},
                        {"north", {0, -1}, 18.4},
                        {"north-east step, x = 1.2", {-1, 0}, 1.2},
                        {"north-east step, y = 15.2", {0, -1}, 15.2},
                        {"east", {-1, 0}, 6.7}};
  const auto toRef = [&](const Eigen::Vector2d& q) -> Eigen::Vector2d {
    return (T_ref_map * Eigen::Vector3d(q.x(), q.y(), 0.0)).head<2>();
  };
  std::set<std::string> seen;
  for (const auto& [id, wall] : graph.walls) {
    if (!wall.is_wall) continue;
    Eigen::Vector3d n;
    double d = 0.0;
    transformPlane(T_ref_map, wall.normal, wall.d, &n, &d);
    const Face* face = nullptr;
    for (const Face& f : faces) {
      if (f.normal.dot(n.head<2>()) > std::cos(10 * M_PI / 180) && std::abs(d - f.d) < 0.3) {
        face = &f;
      }
    }
    ASSERT_NE(face, nullptr) << "wall " << id << " n " << n.transpose() << " d " << d << " from "
                             << toRef(wall.endpoints[0]).transpose() << " to "
                             << toRef(wall.endpoints[1]).transpose()
                             << " is on no face of the hall";
    seen.insert(face->name);
  }
  EXPECT_LE(graph.wallCount(), 10u);
  EXPECT_EQ(seen.size(), 5u) << "faces seen: " << seen.size();
  // Share of the walked path (the reference positions) on the room's free space.
  const RoomNode& room = graph.rooms.begin()->second;
  size_t covered = 0;
  for (const StampedPose& p : reference) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const Eigen::Vector2d& q : room.free_space) {
      nearest = std::min(nearest, (toRef(q) - p.pose.translation().head<2>()).norm());
    }
    covered += nearest < 0.5;
  }
  EXPECT_GE(static_cast<double>(covered) / reference.size(), 0.8);
}

TEST(RealHall, OnTheReferencePosesTheHallIsOneRoomBoundedByItsWalls) {
  TACS_DATA_SET_OR_SKIP(dir, "balm_indoor_hall");
  const Trajectory reference = readTum(dir + "poses_tum.txt", true);
  Pipeline pipeline(handheldConfig());
  pipeline.useGivenPoses(reference);
  for (const HallScan& s : loadHall(dir)) pipeline.processScan(s.stamp, s.cloud);
  pipeline.finish();
  expectTheHall(pipeline.sceneGraph(), Pose3::Identity(), reference);
}

TEST(RealHall, OnOurOwnOdometryTheSameHall) {
  TACS_DATA_SET_OR_SKIP(dir, "balm_indoor_hall");
  const Trajectory reference = readTum(dir + "poses_tum.txt", true);
  Pipeline pipeline(handheldConfig());
  for (const HallScan& s : loadHall(dir)) pipeline.processScan(s.stamp, s.cloud);
  pipeline.finish();
  const AteResult ate = computeAte(pipeline.keyframeTrajectory(), reference, 0.05);
  EXPECT_LT(ate.rmse, 0.25) << "keyframes, max " << ate.max;
  // The same hall as on the reference poses: one room, walls only on the hall's faces.
  expectTheHall(pipeline.sceneGraph(), ate.T_gt_estimate, reference);
}

}  // namespace
}  // namespace tacs
