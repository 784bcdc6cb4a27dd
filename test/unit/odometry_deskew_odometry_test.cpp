// The odometry on distorted sweeps: a simulated sensor swept while the robot drives at 1.5 m/s
// and turns at up to 90 deg/s, each firing from the pose at its time (issue "real sensors").
#include <gtest/gtest.h>
#include <pcl/common/transforms.h>

#include <algorithm>
#include <cmath>
#include <future>
#include <memory>
#include <vector>

#include "tacs_graphs/odometry/lidar_odometry.h"
#include "tacs_graphs/sim/scan_stream.h"

namespace tacs {
namespace {

sim::World fastTurnsWorld() {
  const auto j = nlohmann::json::parse(R"({
    "walls": [{"from": [-0.1, 0], "to": [12.1, 0]}, {"from": [12, 0], "to": [12, 9]},
              {"from": [12.1, 9], "to": [-0.1, 9]}, {"from": [0, 9], "to": [0, 0]},
              {"from": [5, 3], "to": [5, 6]}],
    "boxes": [{"center": [8, 5, 0.6], "size": [1.2, 1, 1.2], "yaw_deg": 20},
              {"center": [3, 7, 0.5], "size": [0.8, 0.8, 1.0], "yaw_deg": 0}],
    "floors": [{"polygon": [[0, 0], [12, 0], [12, 9], [0, 9]], "z": 0.0}],
    "ceilings": [{"polygon": [[0, 0], [12, 0], [12, 9], [0, 9]], "z": 3.0}],
    "trajectory": {"waypoints": [[2, 1.5], [10, 1.5], [10, 7.5], [2, 7.5], [2, 2.5]],
                   "speed_mps": 1.5, "max_yaw_rate_dps": 90, "max_accel_mps2": 1.5,
                   "corner_radius_m": 0.4},
    "sensor": {"model": "custom", "rings": 16, "vfov_deg": 30, "hres_deg": 0.4, "seed": 5,
               "motion_distortion": true}
  })");
  return sim::parseWorld(j, "fast_turns.json");
}

struct Errors {
  double rms_m = 0.0;     // of the poses at the stamps
  double max_deg = 0.0;   // of the poses at the stamps
  double step_m = 0.0;    // mean error of the motion between consecutive scans
  double step_deg = 0.0;  // ... its rotation
  int failed = 0;
  // RMS distance to the nearest wall of the keyframe clouds' wall points, each cloud placed at
  // its scan's true pose: how well the cloud handed to walls and maps is deskewed to the stamp.
  double keyframe_wall_rms_m = 0.0;
};

// Distance of a world point to the nearest wall face of fastTurnsWorld() (walls 0.15 m thick
// about their centre lines).
double distanceToWall(const Eigen::Vector3f& p) {
  double d =
      std::min({std::abs(p.x()), std::abs(p.x() - 12.0f), std::abs(p.y()), std::abs(p.y() - 9.0f)});
  if (p.y() > 3.0f && p.y() < 6.0f) d = std::min<double>(d, std::abs(p.x() - 5.0f));
  return std::abs(d - 0.075);
}

// Runs the odometry over the whole sweep sequence with the simulator's point times and returns
// its pose errors at the scan stamps (odom frame = the first scan's true pose).
Errors runOdometry(const OdometryConfig& config) {
  const sim::World world = fastTurnsWorld();
  sim::ScanStream stream(world, sim::SimOptions{});
  LidarOdometry odometry(config);
  const Pose3 T_base_sensor = stream.baseToSensor();
  Errors e;
  int n = 0;
  Pose3 T_world_odom = Pose3::Identity();
  Pose3 last_estimate, last_truth;
  double wall_sq = 0.0;
  size_t wall_points = 0;
  sim::SimScan scan;
  while (stream.next(&scan)) {
    PointCloud cloud;
    pcl::transformPointCloud(sim::toPointCloud(scan), cloud, T_base_sensor.cast<float>());
    std::vector<float> times;
    for (const auto& p : scan.points) times.push_back(p.time);
    const OdometryResult r = odometry.process(scan.stamp, cloud, &times);
    if (n == 0) T_world_odom = scan.T_world_base;
    ++n;
    if (!r.ok) {
      ++e.failed;
      continue;
    }
    // Wall points only: above the boxes and below the ceiling, and near a wall (boxes and a
    // badly deskewed return farther than 0.5 m are left out alike, so the raw cloud's figure
    // is a lower bound).
    if (r.keyframe_cloud && n > 1) {  // the first scan has no motion to deskew with
      const Eigen::Affine3f T = scan.T_world_base.cast<float>();
      for (const auto& q : r.keyframe_cloud->points) {
        const Eigen::Vector3f p = T * q.getVector3fMap();
        const double d = distanceToWall(p);
        if (p.z() < 1.4f || p.z() > 2.7f || d > 0.5) continue;
        wall_sq += d * d;
        ++wall_points;
      }
    }
    const Pose3 error = (T_world_odom * r.T_odom_base).inverse() * scan.T_world_base;
    e.rms_m += error.translation().squaredNorm();
    e.max_deg = std::max(e.max_deg, rotationAngleDeg(error));
    if (n > 1) {
      const Pose3 step_error = (last_estimate.inverse() * r.T_odom_base).inverse() *
                               (last_truth.inverse() * scan.T_world_base);
      e.step_m += step_error.translation().norm();
      e.step_deg += rotationAngleDeg(step_error);
    }
    last_estimate = r.T_odom_base;
    last_truth = scan.T_world_base;
  }
  e.rms_m = std::sqrt(e.rms_m / std::max(1, n - e.failed));
  e.step_m /= std::max(1, n - e.failed - 1);
  e.step_deg /= std::max(1, n - e.failed - 1);
  e.keyframe_wall_rms_m = std::sqrt(wall_sq / std::max<size_t>(1, wall_points));
  return e;
}

// The default configuration's run, shared by the tests below.
const Errors& defaultRun() {
  static const Errors errors = runOdometry(OdometryConfig());
  return errors;
}

TEST(DeskewedOdometry, FollowsFastTurnsFromThePointTimes) {
  const Errors& deskewed = defaultRun();
  OdometryConfig raw_config;
  raw_config.deskew = false;
  const Errors raw = runOdometry(raw_config);
  EXPECT_EQ(deskewed.failed, 0);
  EXPECT_LT(deskewed.rms_m, 0.05);
  EXPECT_LT(deskewed.max_deg, 1.0);
  // Without deskew the same sweeps are registered as if taken from one pose.
  EXPECT_LT(deskewed.rms_m, 0.5 * raw.rms_m);
  // The keyframe clouds handed on are deskewed to the stamp as well.
  EXPECT_LT(deskewed.keyframe_wall_rms_m, 0.5 * raw.keyframe_wall_rms_m);
  // ... with the step's velocity: 15.5 mm (11.9 with the velocity the registered cloud was
  // deskewed with, which put the worlds' stamp poses farther off; an undistorted sweep 7.0 mm).
  EXPECT_LT(deskewed.keyframe_wall_rms_m, 0.018);
  std::printf(
      "[          ] deskewed: rms %.4f m, max %.2f deg, keyframe walls %.4f m; raw: rms %.4f m, "
      "max %.2f deg, keyframe walls %.4f m\n",
      deskewed.rms_m, deskewed.max_deg, deskewed.keyframe_wall_rms_m, raw.rms_m, raw.max_deg,
      raw.keyframe_wall_rms_m);
}

TEST(DeskewedOdometry, RegisteringAtTheSweepsMiddleBeatsRegisteringAtItsStamp) {
  // A wrong deskew velocity shifts a stamp-referenced cloud as a whole, and the next velocity
  // (two poses apart) carries that shift on; referenced to the middle it only bends the cloud.
  const Errors& middle = defaultRun();
  OdometryConfig stamp_config;
  stamp_config.deskew_to_mid_sweep = false;
  const Errors stamp = runOdometry(stamp_config);
  // The steps show it; the drift's maximum is about the same once both clouds are deskewed from
  // their voxel centroids (0.6 deg middle, 0.9 stamp; 1.5 when the stamp mode deskewed raw
  // returns).
  EXPECT_LT(middle.step_m, 0.8 * stamp.step_m);
  EXPECT_LT(middle.max_deg, 1.0);
  std::printf(
      "[          ] middle: rms %.4f m, max %.2f deg, step %.4f m %.3f deg; stamp: rms %.4f m, max "
      "%.2f deg, step %.4f m %.3f deg\n",
      middle.rms_m, middle.max_deg, middle.step_m, middle.step_deg, stamp.rms_m, stamp.max_deg,
      stamp.step_m, stamp.step_deg);
}

TEST(DeskewedOdometry, ScansPreparedAheadOnAnotherThreadGiveTheSameResults) {
  // prepare() reads only the configuration: every scan prepared at once on another thread before
  // the first is registered gives what process() gives scan by scan.
  const sim::World world = fastTurnsWorld();
  sim::ScanStream stream(world, sim::SimOptions{});
  const Eigen::Affine3f T_base_sensor = stream.baseToSensor().cast<float>();
  std::vector<double> stamps;
  std::vector<std::shared_ptr<const PointCloud>> clouds;
  std::vector<std::shared_ptr<const std::vector<float>>> times;
  sim::SimScan scan;
  for (int i = 0; i < 40 && stream.next(&scan); ++i) {
    auto cloud = std::make_shared<PointCloud>();
    pcl::transformPointCloud(sim::toPointCloud(scan), *cloud, T_base_sensor);
    auto t = std::make_shared<std::vector<float>>();
    for (const auto& p : scan.points) t->push_back(p.time);
    stamps.push_back(scan.stamp);
    clouds.push_back(cloud);
    times.push_back(t);
  }
  ASSERT_EQ(stamps.size(), 40u);
  LidarOdometry one_by_one(OdometryConfig{}), ahead(OdometryConfig{});
  std::vector<PreparedScan> prepared =
      std::async(std::launch::async, [&] {
        std::vector<PreparedScan> out;
        for (size_t i = 0; i < stamps.size(); ++i)
          out.push_back(ahead.prepare(stamps[i], clouds[i], times[i]));
        return out;
      }).get();
  int keyframes = 0;
  for (size_t i = 0; i < stamps.size(); ++i) {
    const OdometryResult a = one_by_one.process(stamps[i], *clouds[i], times[i].get());
    const OdometryResult b = ahead.process(prepared[i]);
    ASSERT_EQ(a.ok, b.ok) << "scan " << i;
    EXPECT_TRUE(a.deskewed);
    EXPECT_TRUE(a.T_odom_base.isApprox(b.T_odom_base, 0.0)) << "scan " << i;
    ASSERT_EQ(a.is_keyframe, b.is_keyframe) << "scan " << i;
    if (a.is_keyframe) {
      ++keyframes;
      ASSERT_EQ(a.keyframe_cloud->size(), b.keyframe_cloud->size());
    }
  }
  EXPECT_GT(keyframes, 3);
}

}  // namespace
}  // namespace tacs
