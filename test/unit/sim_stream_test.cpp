#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

#include "common/test_paths.h"
#include "tacs_graphs/sim/robot_path.h"
#include "tacs_graphs/sim/scan_stream.h"

namespace tacs::sim {
namespace {

World lRoom() {
  const auto j = nlohmann::json::parse(R"({
    "walls": [{"from": [-0.1, 0], "to": [8.1, 0]}, {"from": [8, 0], "to": [8, 6]},
              {"from": [8.1, 6], "to": [-0.1, 6]}, {"from": [0, 6], "to": [0, 0]}],
    "boxes": [{"center": [4, 3, 0.5], "size": [1, 1, 1], "yaw_deg": 20}],
    "floors": [{"polygon": [[0, 0], [8, 0], [8, 6], [0, 6]], "z": 0.0}],
    "ceilings": [{"polygon": [[0, 0], [8, 0], [8, 6], [0, 6]], "z": 2.8}],
    "trajectory": {"waypoints": [[1, 1], [6, 1], [6, 5]], "speed_mps": 2.0},
    "sensor": {"model": "custom", "rings": 8, "vfov_deg": 30, "hres_deg": 1.0, "seed": 3}
  })");
  return parseWorld(j, "l.json");
}

std::vector<SimScan> renderAll(const World& w, const SimOptions& opt) {
  ScanStream s(w, opt);
  std::vector<SimScan> out;
  SimScan scan;
  while (s.next(&scan)) out.push_back(scan);
  return out;
}

bool sameBytes(const std::vector<SimScan>& a, const std::vector<SimScan>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].stamp != b[i].stamp || a[i].points.size() != b[i].points.size()) return false;
    if (std::memcmp(a[i].points.data(), b[i].points.data(),
                    a[i].points.size() * sizeof(SimPoint)) != 0) {
      return false;
    }
  }
  return true;
}

TEST(SimStream, DeterministicPerSeed) {
  const World w = lRoom();
  const auto a = renderAll(w, SimOptions{});
  const auto b = renderAll(w, SimOptions{});
  EXPECT_TRUE(sameBytes(a, b));
  SimOptions other;
  other.seed = 4;
  EXPECT_FALSE(sameBytes(a, renderAll(w, other)));
  SimOptions same;
  same.seed = 3;  // the world's own seed
  EXPECT_TRUE(sameBytes(a, renderAll(w, same)));
  // Random access renders the same sweep as the sequential stream.
  ScanStream s(w, SimOptions{});
  SimScan scan;
  s.render(5, &scan);
  EXPECT_TRUE(sameBytes({scan}, {a[5]}));
}

TEST(SimStream, SweepsAreTheSameForAnyThreadCount) {
  // The firings are cast in blocks side by side (ScanStream::render).
  World w = lRoom();
  w.sensor.motion_distortion = true;
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const auto one = renderAll(w, SimOptions{});
  omp_set_num_threads(3);
  const auto three = renderAll(w, SimOptions{});
  omp_set_num_threads(threads);
  ASSERT_FALSE(one.empty());
  EXPECT_GT(one[3].points.size(), 1000u);
  EXPECT_TRUE(sameBytes(one, three));
}

TEST(SimStream, GroundTruthFollowsWaypoints) {
  const World w = lRoom();
  ScanStream s(w, SimOptions{});
  const Trajectory gt = s.groundTruth();
  // 9 m of polyline; corner rounding shortens it a little.
  EXPECT_NEAR(s.path().length(), 9.0, 0.3);
  EXPECT_GT(s.path().duration(), 9.0 / 2.0);
  ASSERT_EQ(gt.size(), s.scanCount());
  EXPECT_EQ(gt.size(), static_cast<size_t>(s.path().duration() * 10));
  EXPECT_DOUBLE_EQ(gt[0].stamp, 1000.0);
  EXPECT_NEAR(gt[1].stamp - gt[0].stamp, 0.1, 1e-12);
  EXPECT_TRUE(gt[0].pose.translation().head<2>().isApprox(Eigen::Vector2d(1, 1), 1e-6));
  EXPECT_LT((gt.back().pose.translation().head<2>() - Eigen::Vector2d(6, 5)).norm(), 0.25);
  for (const auto& p : gt) {
    const Eigen::Vector3d t = p.pose.translation();
    // Within the corner rounding of the polyline (1,1)-(6,1)-(6,5).
    const double d = std::min(std::abs(t.y() - 1.0) + std::max(0.0, t.x() - 6.0),
                              std::abs(t.x() - 6.0) + std::max(0.0, 1.0 - t.y()));
    EXPECT_LT(d, 0.2);
    EXPECT_NEAR(t.z(), 0.0, 0.02);  // floor + vibration
    // Heading along the path: +x first, +y after the corner; never backwards.
    const Eigen::Vector3d fwd = p.pose.linear().col(0);
    EXPECT_GT(fwd.x() + fwd.y(), 0.6);
    EXPECT_LT(std::abs(fwd.z()), 0.02);  // vibration stays small
  }
  // Consecutive headings change smoothly (no jumps at the corner).
  for (size_t i = 1; i < gt.size(); ++i) {
    const Eigen::Matrix3d dR = gt[i - 1].pose.linear().transpose() * gt[i].pose.linear();
    EXPECT_LT(Eigen::AngleAxisd(dR).angle(), 0.1) << i;  // 45 deg/s yaw-rate limit + vibration
    const double v = (gt[i].pose.translation() - gt[i - 1].pose.translation()).norm() / 0.1;
    EXPECT_LT(v, 2.0 + 0.05);
  }
  // Starts at rest, reaches the cruise speed on the first straight.
  EXPECT_LT((gt[1].pose.translation() - gt[0].pose.translation()).norm(), 0.01);
  double vmax = 0.0;
  for (size_t i = 1; i < gt.size(); ++i) {
    vmax = std::max(vmax, (gt[i].pose.translation() - gt[i - 1].pose.translation()).norm() / 0.1);
  }
  EXPECT_GT(vmax, 1.5);
  SimOptions opt;
  opt.duration_s = 1.0;
  EXPECT_EQ(ScanStream(w, opt).scanCount(), 10u);
}

// Largest change of the yaw rate along the path [deg/s^2], as a sweep sees it: the rate over
// 0.05 s windows, compared 0.1 s apart; and the largest such rate [deg/s].
std::pair<double, double> yawAccelAndRate(const RobotPath& path) {
  auto yaw = [&](double t) {
    const Eigen::Vector3d x = path.poseAt(t).linear().col(0);
    return std::atan2(x.y(), x.x()) * 180.0 / M_PI;
  };
  auto rate = [&](double t) { return std::remainder(yaw(t) - yaw(t - 0.05), 360.0) / 0.05; };
  double max_accel = 0.0, max_rate = 0.0;
  for (double t = 0.05; t + 0.1 < path.duration(); t += 0.01) {
    max_accel = std::max(max_accel, std::abs(rate(t + 0.1) - rate(t)) / 0.1);
    max_rate = std::max(max_rate, std::abs(rate(t)));
  }
  return {max_accel, max_rate};
}

TEST(SimStream, AYawAccelerationLimitRampsTheTurns) {
  // The legged office at 90 deg/s: its U-turns step the yaw rate from 0 to the limit.
  World w = loadWorld(test::sourceDir() + "/worlds/legged_office.json");
  w.trajectory.max_yaw_rate_dps = 90.0;
  const RobotPath stepped(w, 1, "legged_office");
  const auto [step_accel, step_rate] = yawAccelAndRate(stepped);
  EXPECT_GT(step_accel, 800.0);
  EXPECT_NEAR(step_rate, 90.0, 1.0);

  w.trajectory.max_yaw_accel_dps2 = 180.0;
  const RobotPath ramped(w, 1, "legged_office");
  const auto [accel, rate] = yawAccelAndRate(ramped);
  EXPECT_LT(accel, 1.1 * 180.0);
  EXPECT_NEAR(rate, 90.0, 1.0);  // long turns still reach the rate limit
  // Ramping takes time; the path is the same.
  EXPECT_GT(ramped.duration(), stepped.duration() + 10.0);
  EXPECT_NEAR(ramped.length(), stepped.length(), 1e-6);
  const Eigen::Vector3d end_ramped = ramped.poseAt(ramped.duration()).translation();
  const Eigen::Vector3d end_stepped = stepped.poseAt(stepped.duration()).translation();
  EXPECT_LT((end_ramped - end_stepped).head<2>().norm(), 1e-6);
}

TEST(SimStream, MotionDistortionMovesLateFirings) {
  World w = lRoom();
  w.sensor.range_noise_std_m = 0.0;
  w.sensor.dropout_prob = 0.0;
  SimOptions on;
  on.motion_distortion = true;
  const auto still = renderAll(w, SimOptions{});
  const auto moving = renderAll(w, on);
  ASSERT_EQ(still.size(), moving.size());
  // A sweep in the middle of the first straight (full speed): late firings are displaced by
  // about the distance driven since the sweep start, the first firing not at all.
  const size_t k = 20;
  const auto& a = still[k].points;
  const auto& b = moving[k].points;
  ASSERT_EQ(a.size(), b.size());
  EXPECT_NEAR(a.front().x, b.front().x, 1e-4);
  const double driven =
      (still[k + 1].T_world_base.translation() - still[k].T_world_base.translation()).norm();
  EXPECT_GT(driven, 0.1);
  std::vector<double> late;
  for (size_t i = 0; i < a.size(); ++i) {
    if (a[i].time > 0.09f) late.push_back(std::hypot(a[i].x - b[i].x, a[i].y - b[i].y));
  }
  ASSERT_FALSE(late.empty());
  std::nth_element(late.begin(), late.begin() + late.size() / 2, late.end());
  EXPECT_NEAR(late[late.size() / 2], 0.95 * driven, 0.3 * driven);
  const PointCloud cloud = toPointCloud(still[0]);
  EXPECT_EQ(cloud.size(), still[0].points.size());
  EXPECT_EQ(cloud.header.frame_id, "velodyne");
  EXPECT_FLOAT_EQ(cloud.points[7].intensity, still[0].points[7].intensity);
}

}  // namespace
}  // namespace tacs::sim
