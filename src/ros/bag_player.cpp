#include "tacs_graphs/ros/bag_player.h"

#include <ros/callback_queue.h>
#include <rosbag/view.h>
#include <rosgraph_msgs/Clock.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <stdexcept>

#include "tacs_graphs/ros/bag_scan_source.h"

namespace tacs {
namespace {

constexpr const char* kTfStatic = "/tf_static";

// The busiest PointCloud2 topic: the LiDAR's, when a bag also holds a map or a filtered cloud.
std::string busiestCloudTopic(const rosbag::Bag& bag) {
  std::string best;
  size_t best_count = 0;
  for (const std::string& topic : pointCloudTopics(bag)) {
    const size_t count = rosbag::View(bag, rosbag::TopicQuery(topic)).size();
    if (count > best_count) {
      best = topic;
      best_count = count;
    }
  }
  return best;
}

}  // namespace

BagPlayer::BagPlayer(ros::NodeHandle& nh, const BagPlayerOptions& options)
    : nh_(nh), options_(options) {
  openBag(options_.bag, &bag_);
  const std::vector<std::string> clouds = pointCloudTopics(bag_);
  if (options_.cloud_topic.empty()) {
    options_.cloud_topic = busiestCloudTopic(bag_);
    if (options_.cloud_topic.empty()) {
      throw std::runtime_error(options_.bag + ": no PointCloud2 topic to pace the bag by");
    }
  } else if (std::find(clouds.begin(), clouds.end(), options_.cloud_topic) == clouds.end()) {
    std::string list;
    for (const auto& t : clouds) list += " " + t;
    throw std::runtime_error(options_.bag + ": no PointCloud2 topic " + options_.cloud_topic +
                             "; PointCloud2 topics in the bag:" + (list.empty() ? " none" : list));
  }
  clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 1);
  ack_sub_ = nh_.subscribe(options_.ack_topic, 100, &BagPlayer::onAck, this,
                           ros::TransportHints().tcpNoDelay());
}

void BagPlayer::publishStaticTransforms() {
  // All of the bag's static transforms in one latched message, before the first cloud: a cloud
  // recorded before them would meet no extrinsic, and a latched topic keeps only its last message.
  std::map<std::string, geometry_msgs::TransformStamped> by_child;
  for (const rosbag::MessageInstance& m : rosbag::View(bag_, rosbag::TopicQuery(kTfStatic))) {
    if (const auto tf = m.instantiate<tf2_msgs::TFMessage>()) {
      for (const auto& t : tf->transforms) by_child[t.child_frame_id] = t;
    }
  }
  if (by_child.empty()) return;
  tf2_msgs::TFMessage all;
  for (const auto& [child, t] : by_child) all.transforms.push_back(t);
  publishers_.at(kTfStatic).publish(all);
}

bool BagPlayer::waitForAcks(size_t wanted, double timeout_s) {
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout_s);
  while (acks_ < wanted) {
    if (!ros::ok() || ros::WallTime::now() > deadline) return false;
    ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.002));
  }
  return true;
}

bool BagPlayer::play(BagPlayerResult* result, std::string* error) {
  *result = BagPlayerResult();
  rosbag::View view(bag_);
  // Advertised up front, so the suite's subscriptions are in place before the first message.
  for (const auto* c : view.getConnections()) {
    if (publishers_.count(c->topic) > 0) continue;
    ros::AdvertiseOptions opts(c->topic, 1000, c->md5sum, c->datatype, c->msg_def);
    opts.latch = c->topic == kTfStatic;
    publishers_[c->topic] = nh_.advertise(opts);
  }
  ros::Publisher& cloud_pub = publishers_.at(options_.cloud_topic);
  const ros::WallTime wait_end =
      ros::WallTime::now() + ros::WallDuration(options_.wait_for_suite_s);
  while (cloud_pub.getNumSubscribers() == 0 || ack_sub_.getNumPublishers() == 0) {
    if (!ros::ok() || ros::WallTime::now() > wait_end) {
      *error = "after " + std::to_string(static_cast<int>(options_.wait_for_suite_s)) +
               " s nobody subscribes to " + options_.cloud_topic + " or publishes " +
               options_.ack_topic + ": is the suite running (roslaunch tacs_graphs ...), with " +
               "points_topic set to " + options_.cloud_topic + "?";
      return false;
    }
    ros::WallDuration(0.05).sleep();
  }
  publishStaticTransforms();
  ros::WallDuration(0.2).sleep();  // the connections' headers settle before the first message
  const ros::WallTime start = ros::WallTime::now();
  ros::Time first, last;
  for (const rosbag::MessageInstance& m : view) {
    if (!ros::ok()) {
      *error = "stopped";
      return false;
    }
    const ros::Time t = m.getTime();
    if (result->messages == 0) first = t;
    last = t;
    if (options_.max_rate > 0.0) {  // not ahead of max_rate times the bag's own pace
      const ros::WallTime due = start + ros::WallDuration((t - first).toSec() / options_.max_rate);
      const ros::WallTime now = ros::WallTime::now();
      if (due > now) (due - now).sleep();
    }
    rosgraph_msgs::Clock clock;
    clock.clock = t;
    clock_pub_.publish(clock);
    ++result->messages;
    if (m.getTopic() == kTfStatic) continue;  // published up front
    publishers_.at(m.getTopic()).publish(m);
    if (m.getTopic() != options_.cloud_topic) continue;
    ++result->clouds;
    const size_t in_flight = static_cast<size_t>(std::max(1, options_.max_in_flight));
    if (result->clouds < in_flight) continue;
    const size_t wanted = result->clouds - in_flight + 1 - result->timed_out;
    if (!waitForAcks(wanted, options_.ack_timeout_s)) {
      if (!ros::ok()) continue;
      ++result->timed_out;
      ROS_WARN_STREAM("play_bag: scan " << result->clouds << " (stamp " << t
                                        << ") not acknowledged on " << options_.ack_topic
                                        << " within " << options_.ack_timeout_s << " s; going on");
    }
  }
  waitForAcks(result->clouds - result->timed_out, options_.ack_timeout_s);
  result->acknowledged = std::min(acks_, result->clouds);
  result->wall_s = (ros::WallTime::now() - start).toSec();
  result->bag_s = (last - first).toSec();
  return true;
}

}  // namespace tacs
