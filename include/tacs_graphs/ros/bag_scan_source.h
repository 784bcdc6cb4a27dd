// Reads LiDAR scans from a rosbag file with the rosbag C++ API (no ROS master needed).
#pragma once

#include <rosbag/bag.h>
#include <rosbag/view.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "tacs_graphs/common/types.h"
#include "tacs_graphs/ros/cloud_conversion.h"

namespace tacs {

/// Opens a bag for reading; throws std::runtime_error with a message a user can act on: no such
/// file, a directory, not a bag, or a recording cut short ('rosbag reindex').
void openBag(const std::string& path, rosbag::Bag* bag);

/// The PointCloud2 topics of a bag, in the order of their connections.
std::vector<std::string> pointCloudTopics(const rosbag::Bag& bag);

class BagScanSource {
 public:
  struct Scan {
    double stamp = 0.0;
    std::string frame_id;
    PointCloud cloud;                  // sensor frame
    CloudConversionResult conversion;  // conversion.ok == false: the message was unusable
    PointTimes times;                  // per-point times relative to `stamp`, when usable
  };

  /// Opens `path` and selects the PointCloud2 `topic`. Throws std::runtime_error with a message a
  /// user can act on: the file is missing or not a bag, the topic is absent (the message lists the
  /// PointCloud2 topics present) or has another type.
  /// `point_times` says where each scan's per-point time is read from.
  BagScanSource(const std::string& path, const std::string& topic,
                const PointTimeConfig& point_times = PointTimeConfig());

  /// Next scan in bag order; false at the end of the bag.
  bool next(Scan* scan);

  size_t messageCount() const { return message_count_; }

  /// T_target_source from the bag's /tf_static and /tf (first value of each edge, chains
  /// followed), or nullopt when the frames are not connected.
  std::optional<Pose3> lookupTransform(const std::string& target, const std::string& source) const;

  /// Poses from a nav_msgs/Odometry topic (the simulator's /ground_truth/odom); empty if absent.
  Trajectory readOdometryTopic(const std::string& topic) const;

  /// The PointCloud2 topics of the bag.
  std::vector<std::string> pointCloudTopics() const;

 private:
  rosbag::Bag bag_;
  std::unique_ptr<rosbag::View> view_;
  rosbag::View::iterator it_;
  size_t message_count_ = 0;
  PointTimeConfig point_times_;
};

}  // namespace tacs
