#include <gtest/gtest.h>

#include <sensor_msgs/point_cloud2_iterator.h>

#include <limits>

#include "tacs_graphs/ros/cloud_conversion.h"

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

}  // namespace
}  // namespace tacs
