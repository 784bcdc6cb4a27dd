#include "tacs_graphs/ros/bag_scan_source.h"

#include <nav_msgs/Odometry.h>
#include <sensor_msgs/PointCloud2.h>
#include <tf2/buffer_core.h>
#include <tf2_eigen/tf2_eigen.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <filesystem>
#include <stdexcept>

namespace tacs {
namespace {
constexpr const char* kCloudType = "sensor_msgs/PointCloud2";
}

void openBag(const std::string& path, rosbag::Bag* bag) {
  if (!std::filesystem::exists(path)) throw std::runtime_error(path + ": no such file");
  if (std::filesystem::is_directory(path)) {
    throw std::runtime_error(path + ": is a directory, not a bag file (give the .bag inside it)");
  }
  try {
    bag->open(path, rosbag::bagmode::Read);
  } catch (const rosbag::BagException& e) {
    // A recording cut short (a crash, a full disk) lacks the index at its end.
    const std::string why = e.what();
    const bool truncated = why.find("wanted") != std::string::npos;
    throw std::runtime_error(
        path + ": not a readable rosbag (" + why + ")" +
        (truncated ? "; it looks cut short: 'rosbag reindex " + path + "' rebuilds its index"
                   : std::string()));
  }
}

std::vector<std::string> pointCloudTopics(const rosbag::Bag& bag) {
  std::vector<std::string> topics;
  for (const auto* c : rosbag::View(bag).getConnections()) {
    if (c->datatype == kCloudType &&
        std::find(topics.begin(), topics.end(), c->topic) == topics.end()) {
      topics.push_back(c->topic);
    }
  }
  return topics;
}

BagScanSource::BagScanSource(const std::string& path, const std::string& topic,
                             const PointTimeConfig& point_times)
    : point_times_(point_times) {
  openBag(path, &bag_);
  std::string found_type;
  for (const auto* c : rosbag::View(bag_).getConnections()) {
    if (c->topic == topic) found_type = c->datatype;
  }
  if (found_type.empty() || found_type != kCloudType) {
    std::string topics;
    for (const auto& t : pointCloudTopics()) topics += "\n  " + t;
    const std::string what = found_type.empty()
                                 ? "has no topic " + topic
                                 : "topic " + topic + " is " + found_type + ", not " + kCloudType;
    throw std::runtime_error(path + ": " + what + "; PointCloud2 topics in the bag:" +
                             (topics.empty() ? std::string(" none") : topics));
  }
  view_ = std::make_unique<rosbag::View>(bag_, rosbag::TopicQuery(topic));
  message_count_ = view_->size();
  it_ = view_->begin();
}

bool BagScanSource::next(Scan* scan) {
  if (it_ == view_->end()) return false;
  // The iterator owns the instance it dereferences to and replaces it when it advances: copy it.
  const rosbag::MessageInstance m = *it_;
  ++it_;
  scan->cloud.clear();
  const auto msg = m.instantiate<sensor_msgs::PointCloud2>();
  scan->stamp = m.getTime().toSec();
  if (!msg) {
    scan->conversion = CloudConversionResult();
    scan->conversion.error = "message could not be deserialised as PointCloud2";
    return true;
  }
  // The header stamp is the scan time; the bag's receive time only stands in when it is unset.
  if (!msg->header.stamp.isZero()) scan->stamp = msg->header.stamp.toSec();
  scan->frame_id = msg->header.frame_id;
  TimedScan timed = fromRosCloudWithTimes(*msg, scan->stamp, point_times_);
  scan->cloud = std::move(timed.cloud);
  scan->conversion = std::move(timed.conversion);
  scan->times = std::move(timed.times);
  return true;
}

std::optional<Pose3> BagScanSource::lookupTransform(const std::string& target,
                                                    const std::string& source) const {
  if (target == source) return Pose3::Identity();
  tf2::BufferCore buffer(ros::Duration(1e6));
  rosbag::View tf_view(bag_, rosbag::TopicQuery(std::vector<std::string>{"/tf_static", "/tf"}));
  for (const auto& m : tf_view) {
    const auto msg = m.instantiate<tf2_msgs::TFMessage>();
    if (!msg) continue;
    for (const auto& t : msg->transforms) {
      // Treat every edge as static: only the rigid sensor mount is looked up here.
      buffer.setTransform(t, "bag", /*is_static=*/true);
    }
  }
  try {
    return tf2::transformToEigen(buffer.lookupTransform(target, source, ros::Time(0)));
  } catch (const tf2::TransformException&) {
    return std::nullopt;
  }
}

Trajectory BagScanSource::readOdometryTopic(const std::string& topic) const {
  Trajectory out;
  rosbag::View view(bag_, rosbag::TopicQuery(topic));
  for (const auto& m : view) {
    const auto msg = m.instantiate<nav_msgs::Odometry>();
    if (!msg) continue;
    Eigen::Isometry3d pose;
    tf2::fromMsg(msg->pose.pose, pose);
    out.push_back({msg->header.stamp.toSec(), pose});
  }
  return out;
}

std::vector<std::string> BagScanSource::pointCloudTopics() const {
  return tacs::pointCloudTopics(bag_);
}

}  // namespace tacs
