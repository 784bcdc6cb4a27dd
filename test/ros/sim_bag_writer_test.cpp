#include "tacs_graphs/ros/sim_bag_writer.h"

#include <gtest/gtest.h>
#include <nav_msgs/Odometry.h>
#include <rosbag/view.h>
#include <sensor_msgs/point_cloud2_iterator.h>
#include <tf2_msgs/TFMessage.h>

#include <fstream>
#include <iterator>
#include <string>

#include "tacs_graphs/ros/bag_scan_source.h"

namespace tacs {
namespace {

TEST(SimBagWriter, WritesCloudTfAndGroundTruth) {
  sim::SimScan a, b;
  a.stamp = 1000.0;
  a.points = {{1.f, 2.f, 3.f, 40.f, 5, 0.01f}, {-1.f, 0.5f, 0.f, 7.f, 15, 0.09f}};
  b = a;
  b.stamp = 1000.1;
  b.T_world_base.translation() = Eigen::Vector3d(0.08, 0, 0);
  const std::string path = ::testing::TempDir() + "/sim_test.bag";
  {
    SimBagWriter writer(path, poseFromXyzRpy(0, 0, 0.5, 0, 0, 0), SimBagWriter::Options{});
    writer.write(a);
    writer.write(b);
  }
  rosbag::Bag bag(path, rosbag::bagmode::Read);
  int clouds = 0, odoms = 0, tfs = 0;
  for (const auto& m : rosbag::View(bag)) {
    if (auto c = m.instantiate<sensor_msgs::PointCloud2>()) {
      EXPECT_EQ(m.getTopic(), "/velodyne_points");
      EXPECT_EQ(c->header.frame_id, "velodyne");
      ASSERT_EQ(c->fields.size(), 6u);
      EXPECT_EQ(c->fields[4].name, "ring");
      EXPECT_EQ(c->fields[4].datatype, sensor_msgs::PointField::UINT16);
      EXPECT_EQ(c->fields[5].name, "time");
      sensor_msgs::PointCloud2ConstIterator<float> x(*c, "x"), t(*c, "time");
      sensor_msgs::PointCloud2ConstIterator<uint16_t> ring(*c, "ring");
      EXPECT_FLOAT_EQ(x[0], 1.f);
      ++x, ++t, ++ring;
      EXPECT_FLOAT_EQ(x[0], -1.f);
      EXPECT_FLOAT_EQ(t[0], 0.09f);
      EXPECT_EQ(ring[0], 15);
      ++clouds;
    } else if (auto o = m.instantiate<nav_msgs::Odometry>()) {
      EXPECT_EQ(m.getTopic(), "/ground_truth/odom");
      EXPECT_EQ(o->header.frame_id, "world");
      EXPECT_EQ(o->child_frame_id, "base_link");
      if (odoms == 1) {
        EXPECT_NEAR(o->twist.twist.linear.x, 0.8, 1e-6);
      }
      ++odoms;
    } else if (auto tf = m.instantiate<tf2_msgs::TFMessage>()) {
      EXPECT_EQ(m.getTopic(), "/tf_static");
      ASSERT_EQ(tf->transforms.size(), 1u);
      EXPECT_EQ(tf->transforms[0].child_frame_id, "velodyne");
      EXPECT_DOUBLE_EQ(tf->transforms[0].transform.translation.z, 0.5);
      ++tfs;
    }
  }
  EXPECT_EQ(clouds, 2);
  EXPECT_EQ(odoms, 2);
  EXPECT_EQ(tfs, 1);
}

TEST(SimBagWriter, BagScanSourceReadsEveryScanBack) {
  const std::string path = ::testing::TempDir() + "/sim_read_test.bag";
  {
    SimBagWriter writer(path, poseFromXyzRpy(0, 0, 0.5, 0, 0, 0), SimBagWriter::Options{});
    sim::SimScan scan;
    scan.points = {{1.f, 2.f, 3.f, 40.f, 5, 0.01f}, {-1.f, 0.5f, 0.f, 7.f, 15, 0.09f}};
    for (int i = 0; i < 5; ++i) {
      scan.stamp = 1000.0 + 0.1 * i;
      writer.write(scan);
    }
  }
  BagScanSource source(path, "/velodyne_points");
  EXPECT_EQ(source.messageCount(), 5u);
  BagScanSource::Scan scan;
  int read = 0;
  while (source.next(&scan)) {
    ASSERT_TRUE(scan.conversion.ok) << scan.conversion.error;
    EXPECT_EQ(scan.frame_id, "velodyne");
    EXPECT_EQ(scan.cloud.size(), 2u);
    EXPECT_NEAR(scan.stamp, 1000.0 + 0.1 * read, 1e-6);
    ++read;
  }
  EXPECT_EQ(read, 5);
  EXPECT_TRUE(source.lookupTransform("base_link", "velodyne").has_value());
}

// The message of a BagScanSource that cannot open `path`.
std::string openError(const std::string& path) {
  try {
    BagScanSource source(path, "/velodyne_points");
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(SimBagWriter, BagScanSourceNamesADirectoryAndACutShortBag) {
  EXPECT_NE(openError(::testing::TempDir()).find("is a directory"), std::string::npos);
  const std::string path = ::testing::TempDir() + "/sim_cut_test.bag";
  {
    SimBagWriter writer(path, Pose3::Identity(), SimBagWriter::Options{});
    sim::SimScan scan;
    scan.points.assign(2000, {1.f, 2.f, 3.f, 40.f, 5, 0.01f});
    for (int i = 0; i < 5; ++i) {
      scan.stamp = 1000.0 + 0.1 * i;
      writer.write(scan);
    }
  }
  // The first half of the file: what a recording killed mid-way leaves.
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string cut = ::testing::TempDir() + "/sim_cut_test_half.bag";
  std::ofstream(cut, std::ios::binary) << bytes.substr(0, bytes.size() / 2);
  const std::string error = openError(cut);
  EXPECT_NE(error.find("rosbag reindex " + cut), std::string::npos) << error;
}

}  // namespace
}  // namespace tacs
