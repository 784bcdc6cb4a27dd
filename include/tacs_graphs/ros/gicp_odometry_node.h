// The gicp_odometry node: LiDAR clouds -> LidarOdometry (or external odometry) -> /tacs/odom,
// TF odom -> base, /tacs/keyframe, and /tacs/odometry/scan_done (std_msgs/Header, the header of
// every cloud handled, used or skipped: the pace of play_bag).
//
// Parameters: the pipeline configuration under ~config_ns (default /tacs; sections frames and
// odometry), and private ones:
//   ~points_topic (/velodyne_points)  cloud topic (a remap works as well)
//   ~external_odom_topic ("")         nav_msgs/Odometry to use instead of GICP (S-Graphs bags)
//   ~external_odom_sigma_xyz_m (0.05), ~external_odom_sigma_rot_deg (1.0): its keyframe noise
//   ~publish_tf (true)                broadcast odom -> base (off when the bag already has it)
//   ~points_queue_size (30)           clouds waiting for the odometry (3 s at 10 Hz); scans lost
//                                     to a full queue are counted from the stamps and logged
//   ~resend_capacity (100)            keyframes kept to resend on a tacs_graphs/Resync (a node
//                                     restarted after a crash, message_journal.h)
// Keyframe clouds go out at odometry.keyframe_cloud_voxel_m (finer than the odometry's own grid:
// traversability needs several points per tri-grid node).
#pragma once

#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <sensor_msgs/PointCloud2.h>
#include <std_msgs/Header.h>
#include <tacs_graphs/Keyframe.h>
#include <tacs_graphs/Resync.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_broadcaster.h>
#include <tf2_ros/transform_listener.h>

#include <deque>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>

#include "tacs_graphs/odometry/external_odometry.h"
#include "tacs_graphs/odometry/lidar_odometry.h"
#include "tacs_graphs/pipeline/pipeline_config.h"
#include "tacs_graphs/pipeline/scan_gap_monitor.h"
#include "tacs_graphs/ros/resend_buffer.h"
#include "tacs_graphs/ros/warn_once.h"

namespace tacs {

class GicpOdometryNode {
 public:
  /// Throws ConfigError on a bad configuration.
  GicpOdometryNode(ros::NodeHandle& nh, ros::NodeHandle& pnh);

  size_t scansProcessed() const { return scans_processed_; }
  /// Scans skipped for bad input (a scan used without deskew is not one).
  size_t scansDropped() const { return scans_dropped_; }
  size_t scansMissing() const { return scan_gaps_.missingTotal(); }

 private:
  void cloudCallback(const sensor_msgs::PointCloud2::ConstPtr& msg);
  void externalOdomCallback(const nav_msgs::Odometry::ConstPtr& msg);
  void resyncCallback(const tacs_graphs::Resync::ConstPtr& msg);
  /// processCloud(), then acknowledge() (used or skipped).
  void handleCloud(const sensor_msgs::PointCloud2::ConstPtr& msg);
  void processCloud(const sensor_msgs::PointCloud2::ConstPtr& msg);
  /// Publishes the scan's header on /tacs/odometry/scan_done: the scan is done with.
  void acknowledge(const std_msgs::Header& scan_header);
  /// T_base_sensor for `sensor_frame`: TF first, then frames.base_to_sensor (cached per frame).
  Pose3 sensorExtrinsic(const std::string& sensor_frame);
  void publish(const OdometryResult& result, const Eigen::Vector3d& sensor_in_base);

  PipelineConfig config_;
  bool publish_tf_ = true;
  std::unique_ptr<LidarOdometry> gicp_;
  std::unique_ptr<ExternalOdometry> external_;
  size_t scans_dropped_ = 0;
  std::deque<sensor_msgs::PointCloud2::ConstPtr> waiting_for_odometry_;

  ros::Subscriber cloud_sub_;
  ros::Subscriber external_sub_;
  ros::Subscriber resync_sub_;
  ros::Publisher odom_pub_;
  ros::Publisher keyframe_pub_;
  ros::Publisher scan_done_pub_;
  tf2_ros::Buffer tf_buffer_;
  tf2_ros::TransformListener tf_listener_;
  tf2_ros::TransformBroadcaster tf_broadcaster_;
  std::map<std::string, Pose3> extrinsics_;
  std::set<std::string> fallback_frames_;  // extrinsic from frames.base_to_sensor, not TF
  WarnOnce warnings_;
  ScanGapMonitor scan_gaps_;
  OverloadMonitor overload_;
  std::optional<double> last_stamp_;
  std::unique_ptr<ResendBuffer<tacs_graphs::Keyframe>> sent_keyframes_;
  size_t scans_processed_ = 0;
};

}  // namespace tacs
