#include <gtest/gtest.h>

#include "tacs_graphs/odometry/external_odometry.h"

namespace tacs {
namespace {

PointCloud scan() {
  PointCloud cloud;
  for (int i = 0; i < 400; ++i) {
    const double a = i * 2.0 * M_PI / 400.0;
    cloud.push_back(pcl::PointXYZI(5.0 * std::cos(a), 5.0 * std::sin(a), 0.3f * (i % 5), 1.0f));
  }
  return cloud;
}

TEST(ExternalOdometry, InterpolatesPosesBetweenMessages) {
  ExternalOdometry odom(OdometryConfig(), 0.05, 1.0);
  odom.addPose(1.0, poseFromXyzRpy(0, 0, 0, 0, 0, 0));
  odom.addPose(1.2, poseFromXyzRpy(1.0, 0, 0, 0, 0, 0.2));
  const auto mid = odom.poseAt(1.1);
  ASSERT_TRUE(mid.has_value());
  EXPECT_NEAR(mid->translation().x(), 0.5, 1e-9);
  EXPECT_NEAR(Eigen::AngleAxisd(mid->rotation()).angle(), 0.1, 1e-9);
  EXPECT_FALSE(odom.poseAt(0.9).has_value());
  EXPECT_FALSE(odom.poseAt(1.3).has_value());
}

TEST(ExternalOdometry, KeyframesByDistanceWithInformation) {
  OdometryConfig config;
  config.keyframe_distance_m = 0.5;
  config.preprocess.voxel_size_m = 0.0;
  ExternalOdometry odom(config, 0.1, 1.0);
  for (int i = 0; i <= 10; ++i) odom.addPose(i * 0.1, poseFromXyzRpy(0.1 * i, 0, 0, 0, 0, 0));
  int keyframes = 0;
  for (int i = 0; i <= 10; ++i) {
    const OdometryResult r = odom.process(i * 0.1, scan());
    ASSERT_TRUE(r.ok) << r.error;
    if (!r.is_keyframe) continue;
    EXPECT_EQ(r.keyframe_id, static_cast<uint32_t>(keyframes));
    EXPECT_DOUBLE_EQ(r.information(0, 0), keyframes == 0 ? 0.0 : 100.0);
    ++keyframes;
  }
  EXPECT_EQ(keyframes, 3);  // at 0, 0.5 and 1.0 m
}

TEST(ExternalOdometry, RejectsScansWithoutPoseOrOutOfOrder) {
  ExternalOdometry odom(OdometryConfig(), 0.05, 1.0);
  OdometryResult r = odom.process(1.0, scan());
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("no external odometry"), std::string::npos);
  odom.addPose(1.0, Pose3::Identity());
  odom.addPose(1.4, Pose3::Identity());
  odom.addPose(2.4, Pose3::Identity());
  EXPECT_TRUE(odom.process(1.2, scan()).ok);
  EXPECT_FALSE(odom.process(1.1, scan()).ok);
  EXPECT_TRUE(odom.process(1.3, PointCloud()).error.find("too few") != std::string::npos);
  // Poses further apart than max_time_gap_s are not interpolated.
  r = odom.process(1.9, scan());
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("no external odometry"), std::string::npos);
}

}  // namespace
}  // namespace tacs
