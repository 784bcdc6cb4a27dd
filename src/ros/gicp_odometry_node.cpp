#include "tacs_graphs/ros/gicp_odometry_node.h"

#include <pcl/common/transforms.h>
#include <tf2_eigen/tf2_eigen.h>

#include <algorithm>
#include <cmath>

#include "tacs_graphs/common/trajectory_io.h"
#include "tacs_graphs/ros/cloud_conversion.h"
#include "tacs_graphs/ros/graph_messages.h"
#include "tacs_graphs/ros/message_conversion.h"
#include "tacs_graphs/ros/params.h"

namespace tacs {
namespace {

constexpr size_t kMaxScansWaitingForOdometry = 20;

bool sameFrame(const std::string& a, const std::string& b) {
  auto strip = [](const std::string& s) { return s.rfind('/', 0) == 0 ? s.substr(1) : s; };
  return strip(a) == strip(b);
}

}  // namespace

GicpOdometryNode::GicpOdometryNode(ros::NodeHandle& nh, ros::NodeHandle& pnh)
    : tf_listener_(tf_buffer_) {
  const std::string config_ns = pnh.param<std::string>("config_ns", "/tacs");
  config_ = loadPipelineConfigFromRos(nh, config_ns);
  publish_tf_ = pnh.param("publish_tf", true);
  const std::string points_topic = pnh.param<std::string>("points_topic", "/velodyne_points");
  const std::string external_topic = pnh.param<std::string>("external_odom_topic", "");

  odom_pub_ = nh.advertise<nav_msgs::Odometry>("/tacs/odom", 10);
  keyframe_pub_ = nh.advertise<tacs_graphs::Keyframe>("/tacs/keyframe", 100);
  // One message per scan handled, used or skipped: what a paced player (play_bag) waits for.
  scan_done_pub_ = nh.advertise<std_msgs::Header>("/tacs/odometry/scan_done", 100);
  const std::string poses_file = pnh.param<std::string>("poses_file", "");
  if (!poses_file.empty()) {
    // A trajectory file (as tacs_offline --poses): read whole, a bad file stops the node here.
    const Trajectory poses = readTum(poses_file, /*require_increasing=*/true);
    if (poses.size() < 2) throw std::runtime_error(poses_file + ": fewer than 2 poses");
    external_ = ExternalOdometry::fromTrajectory(
        config_.odometry, poses, boundedParam(pnh, "external_odom_sigma_xyz_m", 0.02, 0.0, false),
        boundedParam(pnh, "external_odom_sigma_rot_deg", 0.5, 0.0, false));
    ROS_INFO_STREAM("Odometry from " << poses_file << " (" << poses.size() << " poses, "
                                     << std::fixed << poses.front().stamp << " to "
                                     << poses.back().stamp << ") with clouds on "
                                     << nh.resolveName(points_topic));
  } else if (external_topic.empty()) {
    gicp_ = std::make_unique<LidarOdometry>(config_.odometry);
    ROS_INFO_STREAM("GICP odometry on " << nh.resolveName(points_topic));
  } else {
    external_ = std::make_unique<ExternalOdometry>(
        config_.odometry, boundedParam(pnh, "external_odom_sigma_xyz_m", 0.05, 0.0, false),
        boundedParam(pnh, "external_odom_sigma_rot_deg", 1.0, 0.0, false));
    external_sub_ = nh.subscribe(external_topic, 200, &GicpOdometryNode::externalOdomCallback, this,
                                 ros::TransportHints().tcpNoDelay());
    ROS_INFO_STREAM("External odometry " << nh.resolveName(external_topic) << " with clouds on "
                                         << nh.resolveName(points_topic));
  }
  const int queue_size = static_cast<int>(boundedParam(pnh, "points_queue_size", 30, 1, true));
  cloud_sub_ = nh.subscribe(points_topic, queue_size, &GicpOdometryNode::cloudCallback, this,
                            ros::TransportHints().tcpNoDelay());
  // A keyframe cloud is 0.1-0.5 MB: 100 keyframes cover a restart of a few seconds at 10 Hz.
  sent_keyframes_ = std::make_unique<ResendBuffer<tacs_graphs::Keyframe>>(
      static_cast<size_t>(boundedParam(pnh, "resend_capacity", 100, 0, true)), "keyframes");
  resync_sub_ = nh.subscribe("/tacs/resync", 10, &GicpOdometryNode::resyncCallback, this);
}

void GicpOdometryNode::resyncCallback(const tacs_graphs::Resync::ConstPtr& msg) {
  sent_keyframes_->answer(*msg, keyframe_pub_);
}

Pose3 GicpOdometryNode::sensorExtrinsic(const std::string& sensor_frame) {
  const std::string& base = config_.frames.base_frame;
  const auto cached = extrinsics_.find(sensor_frame);
  // A frame on the parameter fallback switches to TF as soon as TF knows it (a late /tf_static);
  // canTransform without a wait keeps that check cheap for rigs that never publish it.
  const bool from_parameter = fallback_frames_.count(sensor_frame) > 0;
  if (cached != extrinsics_.end() &&
      (!from_parameter || !tf_buffer_.canTransform(base, sensor_frame, ros::Time(0)))) {
    return cached->second;
  }
  if (sameFrame(sensor_frame, base)) return extrinsics_[sensor_frame] = Pose3::Identity();
  try {
    // The extrinsic is static: the latest value is the value. The first lookup waits briefly
    // for the /tf_static of a bag that has just started, in wall time: under use_sim_time a
    // paced player (play_bag) holds the clock until this scan is done.
    const ros::WallTime until =
        ros::WallTime::now() + ros::WallDuration(from_parameter ? 0.0 : 0.5);
    while (!tf_buffer_.canTransform(base, sensor_frame, ros::Time(0)) &&
           ros::WallTime::now() < until) {
      ros::WallDuration(0.01).sleep();
    }
    const auto t = tf_buffer_.lookupTransform(base, sensor_frame, ros::Time(0));
    const Pose3 T = tf2::transformToEigen(t);
    ROS_INFO_STREAM("Sensor extrinsic " << base << " -> " << sensor_frame << " from TF: xyz "
                                        << T.translation().transpose());
    fallback_frames_.erase(sensor_frame);
    return extrinsics_[sensor_frame] = T;
  } catch (const tf2::TransformException& e) {
    const Pose3 T = config_.frames.baseToSensor();
    ROS_WARN_STREAM("No TF " << base << " -> " << sensor_frame << " (" << e.what()
                             << "); using frames.base_to_sensor, xyz "
                             << T.translation().transpose());
    fallback_frames_.insert(sensor_frame);
    return extrinsics_[sensor_frame] = T;
  }
}

void GicpOdometryNode::externalOdomCallback(const nav_msgs::Odometry::ConstPtr& msg) {
  const Pose3 T = fromPoseMsg(msg->pose.pose);
  if (!T.matrix().allFinite()) {
    warnings_.warn("external odometry", "non-finite pose");
    return;
  }
  external_->addPose(msg->header.stamp.toSec(), T);
  // Scans that came before their odometry are processed as soon as it covers them.
  while (!waiting_for_odometry_.empty() &&
         waiting_for_odometry_.front()->header.stamp.toSec() <= external_->latestStamp()) {
    const auto cloud = waiting_for_odometry_.front();
    waiting_for_odometry_.pop_front();
    handleCloud(cloud);
  }
}

void GicpOdometryNode::cloudCallback(const sensor_msgs::PointCloud2::ConstPtr& msg) {
  // Scans missing before this one: the queue of ~points_queue_size was full (the odometry is
  // slower than the sensor or the bag rate) or the input has a gap. Reported per window.
  const size_t missing = scan_gaps_.observe(msg->header.stamp.toSec());
  const double now = ros::WallTime::now().toSec();
  overload_.arrived(now, missing);
  if (const auto report = overload_.poll(now)) ROS_WARN_STREAM("odometry: " << *report);
  if (external_ && msg->header.stamp.toSec() > external_->latestStamp()) {
    waiting_for_odometry_.push_back(msg);
    if (waiting_for_odometry_.size() > kMaxScansWaitingForOdometry) {
      acknowledge(waiting_for_odometry_.front()->header);
      waiting_for_odometry_.pop_front();
      warnings_.warn("cloud", "no external odometry for the scan's time, scan dropped");
      ++scans_dropped_;
    }
    return;
  }
  handleCloud(msg);
}

void GicpOdometryNode::handleCloud(const sensor_msgs::PointCloud2::ConstPtr& msg) {
  processCloud(msg);
  acknowledge(msg->header);
}

void GicpOdometryNode::acknowledge(const std_msgs::Header& scan_header) {
  scan_done_pub_.publish(scan_header);
}

void GicpOdometryNode::processCloud(const sensor_msgs::PointCloud2::ConstPtr& msg) {
  const double stamp = msg->header.stamp.toSec();
  if (last_stamp_ && stamp <= *last_stamp_) {
    warnings_.warn("cloud", "time jump back",
                   "time jump back: stamp " + std::to_string(stamp) + " is not after " +
                       std::to_string(*last_stamp_) + ", scan skipped");
    ++scans_dropped_;
    return;
  }
  TimedScan timed = fromRosCloudWithTimes(*msg, stamp, config_.odometry.point_times);
  const CloudConversionResult& conv = timed.conversion;
  PointCloud& scan = timed.cloud;
  if (!conv.ok) {
    warnings_.warn("cloud", WarnOnce::reasonKey(conv.error), conv.error + ", scan skipped");
    ++scans_dropped_;
    return;
  }
  const std::string sensor_frame =
      config_.frames.sensor_frame.empty() ? msg->header.frame_id : config_.frames.sensor_frame;
  const Pose3 T_base_sensor = sensorExtrinsic(sensor_frame);
  PointCloud scan_in_base;
  pcl::transformPointCloud(scan, scan_in_base, T_base_sensor.matrix().cast<float>());

  if (!timed.times.ok && timed.times.reason != "disabled") {
    warnings_.warn("cloud", "point times: " + timed.times.reason,
                   "no deskew: " + timed.times.message + "; the scan is used as measured");
  }
  const std::vector<float>* offsets = timed.times.ok ? &timed.times.offset_s : nullptr;
  const OdometryResult result = gicp_ ? gicp_->process(stamp, scan_in_base, offsets)
                                      : external_->process(stamp, scan_in_base);
  if (!result.ok) {
    warnings_.warn("odometry", WarnOnce::reasonKey(result.error), result.error + ", scan skipped");
    ++scans_dropped_;
    return;
  }
  last_stamp_ = stamp;
  ++scans_processed_;
  publish(result, T_base_sensor.translation());
}

void GicpOdometryNode::publish(const OdometryResult& result,
                               const Eigen::Vector3d& sensor_in_base) {
  const FramesConfig& f = config_.frames;
  odom_pub_.publish(toOdometryMsg(result.T_odom_base, f.odom_frame, f.base_frame, result.stamp));
  if (publish_tf_) {
    tf_broadcaster_.sendTransform(
        toTransformMsg(result.T_odom_base, f.odom_frame, f.base_frame, result.stamp));
  }
  if (!result.is_keyframe || !result.keyframe_cloud) return;
  // The odometry hands the keyframe cloud at odometry.keyframe_cloud_voxel_m.
  tacs_graphs::Keyframe msg =
      toKeyframeMsg(result.keyframe_id, result.stamp, result.T_odom_base, result.information,
                    *result.keyframe_cloud, sensor_in_base, f.odom_frame, f.base_frame);
  msg.scans_received = static_cast<uint32_t>(overload_.arrivedTotal());
  msg.scans_missing = static_cast<uint32_t>(scan_gaps_.missingTotal());
  const uint32_t id = msg.id;
  keyframe_pub_.publish(sent_keyframes_->keep(id, std::move(msg)));
}

}  // namespace tacs
