#include "tacs_graphs/ros/cloud_conversion.h"

#include <gtest/gtest.h>
#include <sensor_msgs/point_cloud2_iterator.h>

#include <limits>
#include <string>
#include <vector>

namespace tacs {
namespace {

PointCloud makeCloud(size_t n) {
  PointCloud c;
  for (size_t i = 0; i < n; ++i) {
    pcl::PointXYZI p;
    p.x = static_cast<float>(i);
    p.y = 2.0f * i;
    p.z = -1.0f;
    p.intensity = 7.0f;
    c.push_back(p);
  }
  return c;
}

TEST(CloudConversion, RoundTripsXyzi) {
  const auto msg = toRosCloud(makeCloud(5), "velodyne", 12.5);
  EXPECT_EQ(msg.header.frame_id, "velodyne");
  EXPECT_DOUBLE_EQ(msg.header.stamp.toSec(), 12.5);
  PointCloud out;
  const auto r = fromRosCloud(msg, &out);
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(out.size(), 5u);
  EXPECT_FLOAT_EQ(out[3].y, 6.0f);
  EXPECT_FLOAT_EQ(out[3].intensity, 7.0f);
}

TEST(CloudConversion, DropsAndCountsNonFinitePoints) {
  auto cloud = makeCloud(4);
  cloud[1].x = std::numeric_limits<float>::quiet_NaN();
  cloud[2].z = std::numeric_limits<float>::infinity();
  PointCloud out;
  const auto r = fromRosCloud(toRosCloud(cloud, "s", 0.0), &out);
  ASSERT_TRUE(r.ok);
  EXPECT_EQ(r.points_in, 4u);
  EXPECT_EQ(r.non_finite, 2u);
  EXPECT_EQ(out.size(), 2u);
}

TEST(CloudConversion, RejectsCloudWithoutZ) {
  auto msg = toRosCloud(makeCloud(3), "s", 0.0);
  msg.fields.erase(msg.fields.begin() + 2);  // drop "z"
  PointCloud out;
  const auto r = fromRosCloud(msg, &out);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("missing x/y/z"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("intensity"), std::string::npos) << r.error;
}

TEST(CloudConversion, RejectsTruncatedData) {
  auto msg = toRosCloud(makeCloud(3), "s", 0.0);
  msg.data.resize(msg.data.size() - 1);
  PointCloud out;
  const auto r = fromRosCloud(msg, &out);
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("bytes"), std::string::npos) << r.error;
}

TEST(CloudConversion, EmptyCloudIsValidAndEmpty) {
  PointCloud out;
  const auto r = fromRosCloud(toRosCloud(PointCloud(), "s", 0.0), &out);
  EXPECT_TRUE(r.ok);
  EXPECT_TRUE(out.empty());
}

TEST(CloudConversion, ReadsFloat64CoordinatesAndMissingIntensity) {
  sensor_msgs::PointCloud2 msg;
  sensor_msgs::PointCloud2Modifier modifier(msg);
  modifier.setPointCloud2Fields(3, "x", 1, sensor_msgs::PointField::FLOAT64, "y", 1,
                                sensor_msgs::PointField::FLOAT64, "z", 1,
                                sensor_msgs::PointField::FLOAT64);
  modifier.resize(2);
  sensor_msgs::PointCloud2Iterator<double> x(msg, "x"), y(msg, "y"), z(msg, "z");
  for (int i = 0; i < 2; ++i, ++x, ++y, ++z) {
    *x = 1.5 * i;
    *y = 0.25;
    *z = 3.0;
  }
  PointCloud out;
  const auto r = fromRosCloud(msg, &out);
  ASSERT_TRUE(r.ok) << r.error;
  ASSERT_EQ(out.size(), 2u);
  EXPECT_FLOAT_EQ(out[1].x, 1.5f);
  EXPECT_FLOAT_EQ(out[1].intensity, 0.0f);
}

// A cloud with x y z and one time field of the given type, name and values (a NaN point at 3).
template <class T>
sensor_msgs::PointCloud2 timedCloud(const std::string& name, uint8_t type,
                                    const std::vector<T>& times) {
  sensor_msgs::PointCloud2 msg;
  msg.header.stamp.fromSec(1000.0);
  sensor_msgs::PointCloud2Modifier modifier(msg);
  modifier.setPointCloud2Fields(4, "x", 1, sensor_msgs::PointField::FLOAT32, "y", 1,
                                sensor_msgs::PointField::FLOAT32, "z", 1,
                                sensor_msgs::PointField::FLOAT32, name.c_str(), 1, type);
  modifier.resize(times.size());
  sensor_msgs::PointCloud2Iterator<float> x(msg, "x"), y(msg, "y"), z(msg, "z");
  sensor_msgs::PointCloud2Iterator<T> t(msg, name);
  for (size_t i = 0; i < times.size(); ++i, ++x, ++y, ++z, ++t) {
    *x = i == 3 ? std::numeric_limits<float>::quiet_NaN() : 1.0f + i;
    *y = 0.0f;
    *z = 0.0f;
    *t = times[i];
  }
  return msg;
}

TEST(CloudConversion, ReadsVelodyneTimeAlignedWithTheKeptPoints) {
  std::vector<float> times;
  for (int i = 0; i < 100; ++i) times.push_back(0.001f * i);
  const TimedScan scan = fromRosCloudWithTimes(
      timedCloud("time", sensor_msgs::PointField::FLOAT32, times), 1000.0, PointTimeConfig());
  ASSERT_TRUE(scan.conversion.ok) << scan.conversion.error;
  EXPECT_EQ(scan.conversion.time_field, "time");
  ASSERT_TRUE(scan.times.ok) << scan.times.message;
  ASSERT_EQ(scan.times.offset_s.size(), scan.cloud.size());  // the NaN point dropped from both
  EXPECT_EQ(scan.cloud.size(), 99u);
  EXPECT_NEAR(scan.times.offset_s[3], 0.004, 1e-6);  // point 4 follows point 2
}

TEST(CloudConversion, ReadsOusterNanoseconds) {
  std::vector<uint32_t> times;
  for (uint32_t i = 0; i < 100; ++i) times.push_back(i * 1000000u);
  const TimedScan scan = fromRosCloudWithTimes(
      timedCloud("t", sensor_msgs::PointField::UINT32, times), 1000.0, PointTimeConfig());
  ASSERT_TRUE(scan.times.ok) << scan.times.message;
  EXPECT_EQ(scan.times.unit, "ns");
  EXPECT_NEAR(scan.times.offset_s.back(), 0.099, 1e-6);
}

TEST(CloudConversion, ReadsHesaiAbsoluteSeconds) {
  std::vector<double> times;
  for (int i = 0; i < 100; ++i) times.push_back(1000.0 + 0.001 * i);
  const TimedScan scan = fromRosCloudWithTimes(
      timedCloud("timestamp", sensor_msgs::PointField::FLOAT64, times), 1000.0, PointTimeConfig());
  ASSERT_TRUE(scan.times.ok) << scan.times.message;
  EXPECT_TRUE(scan.times.absolute);
  EXPECT_NEAR(scan.times.offset_s.back(), 0.099, 1e-6);
}

TEST(CloudConversion, NoTimeFieldOrDisabledGivesAReasonAndKeepsTheScan) {
  const TimedScan plain =
      fromRosCloudWithTimes(toRosCloud(makeCloud(5), "s", 1.0), 1.0, PointTimeConfig());
  EXPECT_TRUE(plain.conversion.ok);
  EXPECT_EQ(plain.cloud.size(), 5u);
  EXPECT_FALSE(plain.times.ok);
  EXPECT_EQ(plain.times.reason, "no_field");
  PointTimeConfig none;
  none.time_field = "none";
  std::vector<float> times(10, 0.0f);
  const TimedScan disabled = fromRosCloudWithTimes(
      timedCloud("time", sensor_msgs::PointField::FLOAT32, times), 1000.0, none);
  EXPECT_EQ(disabled.times.reason, "disabled");
  const TimedScan constant = fromRosCloudWithTimes(
      timedCloud("time", sensor_msgs::PointField::FLOAT32, times), 1000.0, PointTimeConfig());
  EXPECT_EQ(constant.times.reason, "constant");
  EXPECT_EQ(constant.cloud.size(), 9u);
}

}  // namespace
}  // namespace tacs
