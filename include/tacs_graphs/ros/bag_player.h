// A bag player paced by the suite: every message of a bag is published in order with /clock, and
// after each point cloud the player waits until the odometry says it handled that scan
// (/tacs/odometry/scan_done). The bag then plays as fast as the suite keeps up, and no scan is
// dropped from a full queue, as hdl_graph_slam's bag_player and glim_rosbag do. The bag's
// static transforms go out first, merged into one latched /tf_static.
#pragma once

#include <ros/ros.h>
#include <rosbag/bag.h>
#include <std_msgs/Header.h>

#include <map>
#include <string>

namespace tacs {

struct BagPlayerOptions {
  std::string bag;
  /// The PointCloud2 topic the suite registers; empty: the bag's only (or busiest) one.
  std::string cloud_topic;
  /// Header messages, one per scan the odometry handled (used or skipped).
  std::string ack_topic = "/tacs/odometry/scan_done";
  /// Scans published ahead of the last acknowledged one (1: strictly one at a time).
  int max_in_flight = 1;
  /// A scan not acknowledged within this time is counted and the bag goes on (s).
  double ack_timeout_s = 10.0;
  /// How long to wait for the suite to subscribe to the cloud topic before giving up (s).
  double wait_for_suite_s = 30.0;
  /// Upper bound on the speed, as a multiple of the bag's rate; 0: as fast as acknowledged.
  double max_rate = 0.0;
};

struct BagPlayerResult {
  size_t messages = 0;
  size_t clouds = 0;
  size_t acknowledged = 0;
  size_t timed_out = 0;
  double wall_s = 0.0;  // playing time
  double bag_s = 0.0;   // time span of the played messages
};

class BagPlayer {
 public:
  /// Opens the bag and selects the cloud topic; throws std::runtime_error with a message a user
  /// can act on (no file, not a bag, cut short, no PointCloud2 topic or an ambiguous one).
  BagPlayer(ros::NodeHandle& nh, const BagPlayerOptions& options);

  /// Plays the whole bag; false (with `error`) when the suite never subscribed or ROS stopped.
  bool play(BagPlayerResult* result, std::string* error);

  const std::string& cloudTopic() const { return options_.cloud_topic; }

 private:
  void onAck(const std_msgs::Header::ConstPtr&) { ++acks_; }
  bool waitForAcks(size_t wanted, double timeout_s);
  void publishStaticTransforms();

  ros::NodeHandle& nh_;
  BagPlayerOptions options_;
  rosbag::Bag bag_;
  std::map<std::string, ros::Publisher> publishers_;
  ros::Publisher clock_pub_;
  ros::Subscriber ack_sub_;
  size_t acks_ = 0;
};

}  // namespace tacs
