// Test node of bad_messages.test: feeds gicp_odometry good and bad clouds in turn, in a sensor
// frame whose extrinsic comes from TF.
#include <geometry_msgs/TransformStamped.h>
#include <gtest/gtest.h>
#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <tacs_graphs/Keyframe.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include <chrono>
#include <functional>
#include <limits>
#include <thread>

#include "common/box_room.h"
#include "tacs_graphs/ros/cloud_conversion.h"

namespace tacs {
namespace {

constexpr const char* kSensorFrame = "velodyne";
const Eigen::Vector3d kSensorInBase(0.1, 0.0, 0.6);

class BadMessagesTest : public ::testing::Test {
 protected:
  void SetUp() override {
    pub_ = nh_.advertise<sensor_msgs::PointCloud2>("/bad_messages/points", 10);
    odom_sub_ =
        nh_.subscribe<nav_msgs::Odometry>("/tacs/odom", 100, [this](const auto&) { ++odometry_; });
    keyframe_sub_ = nh_.subscribe<tacs_graphs::Keyframe>(
        "/tacs/keyframe", 100, [this](const tacs_graphs::Keyframe::ConstPtr& kf) {
          ++keyframes_;
          sensor_origin_ = {kf->sensor_origin.x, kf->sensor_origin.y, kf->sensor_origin.z};
        });
    geometry_msgs::TransformStamped extrinsic;
    extrinsic.header.stamp = ros::Time::now();
    extrinsic.header.frame_id = "base_link";
    extrinsic.child_frame_id = kSensorFrame;
    extrinsic.transform.translation.x = kSensorInBase.x();
    extrinsic.transform.translation.y = kSensorInBase.y();
    extrinsic.transform.translation.z = kSensorInBase.z();
    extrinsic.transform.rotation.w = 1.0;
    tf_.sendTransform(extrinsic);
    ASSERT_TRUE(waitFor([this] {
      return pub_.getNumSubscribers() > 0 && odom_sub_.getNumPublishers() > 0 &&
             keyframe_sub_.getNumPublishers() > 0;
    })) << "gicp_odometry did not connect";
  }

  // Spins until `done` or 30 s of wall time (the node's first scans can be slow on a busy CI).
  bool waitFor(const std::function<bool()>& done) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(30);
    while (!done()) {
      if (std::chrono::steady_clock::now() > deadline || !ros::ok()) return false;
      ros::spinOnce();
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    return true;
  }

  sensor_msgs::PointCloud2 goodScan(int i, double stamp) {
    const Pose3 T = poseFromXyzRpy(3.0 + 0.05 * i, 3.0, 0.5, 0.0, 0.0, 0.0);
    return toRosCloud(test::renderScan(room_, T, 7 + i), kSensorFrame, stamp);
  }

  // Publishes a good scan and waits for its odometry.
  void publishGood(int i, double stamp) {
    const int before = odometry_;
    pub_.publish(goodScan(i, stamp));
    ASSERT_TRUE(waitFor([&] { return odometry_ > before; })) << "no odometry for scan " << i;
  }

  ros::NodeHandle nh_;
  ros::Publisher pub_;
  ros::Subscriber odom_sub_, keyframe_sub_;
  tf2_ros::StaticTransformBroadcaster tf_;
  test::BoxRoom room_;
  int odometry_ = 0;
  int keyframes_ = 0;
  Eigen::Vector3d sensor_origin_ = Eigen::Vector3d::Constant(-1.0);
};

TEST_F(BadMessagesTest, BadCloudsAreSkippedAndOdometryGoesOn) {
  double t = 100.0;
  for (int i = 0; i < 3; ++i, t += 0.1) publishGood(i, t);

  pub_.publish(toRosCloud(PointCloud(), kSensorFrame, t));  // empty
  t += 0.1;
  publishGood(3, t);
  t += 0.1;

  PointCloud nans;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  for (int k = 0; k < 500; ++k) nans.push_back(pcl::PointXYZI(nan, nan, nan, 0.0f));
  pub_.publish(toRosCloud(nans, kSensorFrame, t));
  t += 0.1;
  publishGood(4, t);
  t += 0.1;

  sensor_msgs::PointCloud2 no_z = goodScan(5, t);
  no_z.fields.erase(no_z.fields.begin() + 2);  // x y [z] intensity
  pub_.publish(no_z);
  t += 0.1;
  publishGood(5, t);

  pub_.publish(goodScan(6, t - 1.0));  // a stamp one second in the past
  t += 0.1;
  publishGood(6, t);
  t += 0.1;
  publishGood(7, t);

  // Every good scan and nothing else produced odometry, and the first scan was a keyframe; a
  // keyframe carries the sensor origin the odometry took from TF.
  EXPECT_EQ(odometry_, 8);
  EXPECT_TRUE(waitFor([this] { return keyframes_ >= 1; }));
  EXPECT_TRUE(sensor_origin_.isApprox(kSensorInBase, 1e-6)) << sensor_origin_.transpose();
}

}  // namespace
}  // namespace tacs

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "bad_messages_test");
  return RUN_ALL_TESTS();
}
