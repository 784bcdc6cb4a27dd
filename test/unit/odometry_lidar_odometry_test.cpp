#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <functional>
#include <limits>
#include <vector>

#include "common/box_room.h"
#include "tacs_graphs/common/config.h"
#include "tacs_graphs/odometry/lidar_odometry.h"

namespace tacs {
namespace {

using test::rotationErrorDeg;
using test::translationError;

// Ground truth of a robot driving through the box room at 0.6 m/s while turning, at 10 Hz.
Pose3 truePose(double t) {
  const double yaw_rate = 0.25, speed = 0.6;
  const double yaw = yaw_rate * t;
  const double x = 2.5 + speed / yaw_rate * std::sin(yaw);
  const double y = 3.0 + speed / yaw_rate * (1.0 - std::cos(yaw));
  return poseFromXyzRpy(x, y, 0.5 + 0.01 * std::sin(t), 0.0, 0.0, yaw);
}

using Edit = std::function<void(int, PointCloud*, double* stamp)>;

// Runs `count` scans 0.1 s apart (plus `gap_s` of unseen driving before scan `gap_at`); `edit`
// may change a rendered scan or its stamp. Checks the pose of every accepted scan.
std::vector<OdometryResult> runSequence(int count, const Edit& edit = nullptr, int gap_at = -1,
                                        double gap_s = 0.0,
                                        const OdometryConfig& config = OdometryConfig()) {
  const test::BoxRoom room;
  LidarOdometry odometry{config};
  const Pose3 T_world_odom = truePose(0.0);
  std::vector<OdometryResult> results;
  for (int i = 0; i < count; ++i) {
    const double t = 0.1 * i + (gap_at >= 0 && i >= gap_at ? gap_s : 0.0);
    double stamp = 100.0 + t;
    PointCloud cloud = test::renderScan(room, truePose(t), 100 + i, 16, 600);
    if (edit) edit(i, &cloud, &stamp);
    results.push_back(odometry.process(stamp, cloud));
    const OdometryResult& r = results.back();
    if (!r.ok) continue;
    const Pose3 truth = T_world_odom.inverse() * truePose(t);
    EXPECT_LT(translationError(r.T_odom_base, truth), 0.05) << "scan " << i;
    EXPECT_LT(rotationErrorDeg(r.T_odom_base, truth), 1.0) << "scan " << i;
  }
  return results;
}

int countOk(const std::vector<OdometryResult>& results) {
  int ok = 0;
  for (const auto& r : results) ok += r.ok;
  return ok;
}

TEST(LidarOdometry, TracksASyntheticMovingSequence) {
  const auto results = runSequence(25);
  EXPECT_EQ(countOk(results), 25);
  ASSERT_TRUE(results.front().is_keyframe);
  EXPECT_EQ(results.front().keyframe_id, 0u);
  uint32_t keyframes = 0;
  for (const auto& r : results) {
    if (!r.is_keyframe) {
      EXPECT_FALSE(r.keyframe_cloud);
      continue;
    }
    EXPECT_EQ(r.keyframe_id, keyframes++);
    ASSERT_TRUE(r.keyframe_cloud);
    EXPECT_GT(r.keyframe_cloud->size(), 500u);
    if (r.keyframe_id > 0) {  // a relative-motion information that constrains all 6 axes
      using Solver = Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 6, 6>>;
      EXPECT_GT(Solver(r.information).eigenvalues().minCoeff(), 0.0);
      EXPECT_GT(r.registration.inlier_ratio, 0.5);
    }
  }
  // 1.5 m and 21 deg of motion with keyframes every 0.5 m or 15 deg.
  EXPECT_GE(keyframes, 3u);
  EXPECT_LE(keyframes, 8u);
}

TEST(LidarOdometry, AWideGateOnASubsetOfTheScanTracksAsTheWholeScanDoes) {
  OdometryConfig whole, subset;
  whole.wide_gate_max_points = 0;
  subset.wide_gate_max_points = 300;
  const auto all = runSequence(25, nullptr, -1, 0.0, whole);
  const auto part = runSequence(25, nullptr, -1, 0.0, subset);  // checks every pose as well
  ASSERT_EQ(countOk(part), 25);
  for (size_t i = 1; i < part.size(); ++i) {
    // The wide pass's scores count the subset's points; the narrow refinement used them all.
    EXPECT_LE(part[i].registration.inliers, 300u) << "scan " << i;
    EXPECT_GT(all[i].registration.inliers, 1000u) << "scan " << i;
    EXPECT_LT(translationError(part[i].T_odom_base, all[i].T_odom_base), 0.005) << "scan " << i;
  }
}

TEST(LidarOdometry, EmptyScanIsRejectedAndTrackingContinues) {
  const auto results = runSequence(15, [](int i, PointCloud* cloud, double*) {
    if (i == 6) cloud->clear();
  });
  EXPECT_FALSE(results[6].ok);
  EXPECT_NE(results[6].error.find("empty scan after preprocessing (0 points in"), std::string::npos)
      << results[6].error;
  EXPECT_EQ(countOk(results), 14);
  EXPECT_TRUE(results.back().ok);
}

TEST(LidarOdometry, AllNanScanIsRejectedWithItsCounts) {
  const auto results = runSequence(15, [](int i, PointCloud* cloud, double*) {
    if (i != 6) return;
    for (auto& p : cloud->points) p.x = p.y = p.z = std::numeric_limits<float>::quiet_NaN();
  });
  EXPECT_FALSE(results[6].ok);
  const std::string expected = "empty scan after preprocessing (" +
                               std::to_string(results[6].preprocess.input) + " points in, " +
                               std::to_string(results[6].preprocess.input) + " non-finite";
  EXPECT_GT(results[6].preprocess.input, 1000u);
  EXPECT_NE(results[6].error.find(expected), std::string::npos) << results[6].error;
  EXPECT_EQ(countOk(results), 14);
}

TEST(LidarOdometry, TwoSecondGapResetsTheMotionGuessAndTrackingContinues) {
  // The robot keeps driving through a 2 s gap in the data (1.2 m and 29 deg of unseen motion).
  const auto results = runSequence(15, nullptr, 8, 1.9);
  EXPECT_TRUE(results[8].ok) << results[8].error;
  EXPECT_TRUE(results[8].motion_prior_reset);
  EXPECT_FALSE(results[9].motion_prior_reset);
  EXPECT_EQ(countOk(results), 15);
}

TEST(LidarOdometry, ScanWithHalfItsPointsStillTracks) {
  const auto results = runSequence(15, [](int i, PointCloud* cloud, double*) {
    if (i != 7) return;
    PointCloud half;
    for (const auto& p : cloud->points) {
      if (p.y > 0.0f) half.push_back(p);  // the left half of the field of view
    }
    EXPECT_NEAR(half.size(), cloud->size() / 2.0, cloud->size() / 8.0);
    *cloud = half;
  });
  EXPECT_TRUE(results[7].ok) << results[7].error;
  EXPECT_EQ(countOk(results), 15);
}

TEST(LidarOdometry, NonIncreasingStampIsRejected) {
  const auto results = runSequence(12, [](int i, PointCloud*, double* stamp) {
    if (i == 5) *stamp -= 0.15;  // earlier than scan 4
  });
  EXPECT_FALSE(results[5].ok);
  EXPECT_NE(results[5].error.find("is not after the previous scan"), std::string::npos);
  EXPECT_EQ(countOk(results), 11);
}

TEST(LidarOdometry, TooFewPointsAreRejectedBeforeTheFirstKeyframe) {
  LidarOdometry odometry{OdometryConfig()};
  PointCloud few;
  for (int i = 0; i < 20; ++i) few.push_back(pcl::PointXYZI(0.0f));
  for (auto& p : few.points) p.x = 1.0f + 0.3f * (&p - &few.points[0]);
  const OdometryResult r = odometry.process(1.0, few);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("too few points after preprocessing"), std::string::npos) << r.error;
  EXPECT_EQ(odometry.numKeyframes(), 0u);
  EXPECT_FALSE(odometry.localMap());
}

// A standing robot in a 20 m corridor with pillars along its walls; from scan 3 on it sees a
// cabinet whose front stands `front_to_wall_m` in front of the far end wall, which the local map
// (scan 0) lacks, as a scan sees a cabinet through a doorway it has just passed. Returns the x
// error of the last scan [m]: within the gate the cabinet pairs with the end wall behind it and
// drags the scan along the corridor.
double xErrorWithUnmappedCabinet(const OdometryConfig& config, double front_to_wall_m = 0.7) {
  test::BoxRoom corridor;
  corridor.room = {{0.0, 0.0, 0.0}, {20.0, 2.2, 2.8}};
  corridor.obstacles = {{{4.0, 0.0, 0.0}, {4.4, 0.3, 2.8}},
                        {{8.0, 1.9, 0.0}, {8.4, 2.2, 2.8}},
                        {{15.0, 0.0, 0.0}, {15.4, 0.3, 2.8}}};
  test::BoxRoom with_cabinet = corridor;
  const double front = 20.0 - front_to_wall_m;
  with_cabinet.obstacles.push_back({{front, 0.0, 0.0}, {front + 0.3, 1.2, 2.0}});
  const Pose3 sensor = poseFromXyzRpy(12.0, 1.1, 0.5, 0.0, 0.0, 0.0);
  LidarOdometry odometry(config);
  OdometryResult r;
  for (int i = 0; i <= 5; ++i) {
    r = odometry.process(100.0 + 0.1 * i, test::renderScan(i < 3 ? corridor : with_cabinet, sensor,
                                                           200 + i, 16, 900));
    EXPECT_TRUE(r.ok) << "scan " << i << ": " << r.error;
  }
  EXPECT_EQ(odometry.numKeyframes(), 1u);  // the local map is scan 0 alone
  return std::abs(r.T_odom_base.translation().x());
}

TEST(LidarOdometry, NarrowRefinementIgnoresStructureTheLocalMapLacks) {
  OdometryConfig wide_only;
  wide_only.refine_correspondence_distance_m = 0.0;
  const double wide_error = xErrorWithUnmappedCabinet(wide_only);
  const double refined_error = xErrorWithUnmappedCabinet(OdometryConfig());
  EXPECT_GT(wide_error, 0.05);  // 78 mm when written
  EXPECT_LT(refined_error, 0.01);
}

TEST(LidarOdometry, RobustRefinementIgnoresStructureTheLocalMapLacksWithinItsGate) {
  // The cabinet's front 0.3 m before the end wall: within the narrow gate too.
  OdometryConfig least_squares;
  least_squares.refine_robust_plane_distance_m = 0.0;
  const double plain_error = xErrorWithUnmappedCabinet(least_squares, 0.3);
  const double robust_error = xErrorWithUnmappedCabinet(OdometryConfig(), 0.3);
  EXPECT_GT(plain_error, 0.015);  // 25 mm when written
  EXPECT_LT(robust_error, 0.005);
}

std::string validationError(const OdometryConfig& config) {
  try {
    config.validate();
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

// Drives along the middle of an empty box room, which looks the same turned by 180 deg, with a
// recovery tried on every scan; returns the largest yaw error over the scans.
double worstYawInASymmetricRoom(double min_gain, double max_angular_accel_dps2) {
  test::BoxRoom room;
  room.obstacles.clear();
  OdometryConfig config;
  config.recovery_relative_fit = 1.0;  // every scan fits below its predecessors' mean at times
  config.recovery_min_gain = min_gain;
  config.recovery_max_angular_accel_dps2 = max_angular_accel_dps2;
  LidarOdometry odometry{config};
  const auto pose = [](int i) { return poseFromXyzRpy(4.0 + 0.05 * i, 3.5, 0.5, 0.0, 0.0, 0.0); };
  double worst = 0.0;
  for (int i = 0; i < 40; ++i) {
    const OdometryResult r = odometry.process(100.0 + 0.1 * i, test::renderScan(room, pose(i), i));
    if (r.ok) worst = std::max(worst, rotationErrorDeg(r.T_odom_base, pose(0).inverse() * pose(i)));
  }
  return worst;
}

TEST(LidarOdometry, ATurnedViewThatFitsAsWellNeverFlipsThePose) {
  constexpr double kAnyTurn = 1e9;                           // deg/s^2: every hypothesis reachable
  EXPECT_GT(worstYawInASymmetricRoom(0.0, kAnyTurn), 90.0);  // the trap: any better fit flips
  EXPECT_LT(worstYawInASymmetricRoom(OdometryConfig().recovery_min_gain, kAnyTurn), 1.0);
}

TEST(LidarOdometry, AHypothesisTheRobotCannotReachNeverReplacesAPlausibleRegistration) {
  // The same trap, any better fit taken, but only turns of up to 18 deg in 0.1 s are reachable.
  EXPECT_LT(worstYawInASymmetricRoom(0.0, OdometryConfig().recovery_max_angular_accel_dps2), 1.0);
}

TEST(OdometryConfig, ValidateNamesTheBadField) {
  EXPECT_EQ(validationError(OdometryConfig()), "");
  OdometryConfig config;
  config.gicp.k_neighbors = 2;
  EXPECT_NE(validationError(config).find("odometry.gicp.k_neighbors"), std::string::npos);
  config = OdometryConfig();
  config.preprocess.max_range_m = 0.1;
  EXPECT_NE(validationError(config).find("odometry.preprocess.max_range_m"), std::string::npos);
  config = OdometryConfig();
  config.min_inlier_ratio = 1.5;
  EXPECT_NE(validationError(config).find("odometry.min_inlier_ratio"), std::string::npos);
  config = OdometryConfig();
  config.refine_correspondence_distance_m = -0.1;
  EXPECT_NE(validationError(config).find("odometry.refine_correspondence_distance_m"),
            std::string::npos);
  config = OdometryConfig();
  config.refine_robust_plane_distance_m = -0.05;
  EXPECT_NE(validationError(config).find("odometry.refine_robust_plane_distance_m"),
            std::string::npos);
  config = OdometryConfig();
  config.gicp.robust_plane_distance_m = -0.05;
  EXPECT_NE(validationError(config).find("odometry.gicp.robust_plane_distance_m"),
            std::string::npos);
  config = OdometryConfig();
  config.recovery_min_gain = -0.1;
  EXPECT_NE(validationError(config).find("odometry.recovery_min_gain"), std::string::npos);
  config = OdometryConfig();
  config.recovery_max_angular_accel_dps2 = 0.0;
  EXPECT_NE(validationError(config).find("odometry.recovery_max_angular_accel_dps2"),
            std::string::npos);
  config = OdometryConfig();
  config.wide_gate_max_points = -1;
  EXPECT_NE(validationError(config).find("odometry.wide_gate_max_points"), std::string::npos);
}

}  // namespace
}  // namespace tacs
